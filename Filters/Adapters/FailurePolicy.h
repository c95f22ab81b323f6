// The one failure convention of the plugin's algorithms. RequestData catches every exception at
// the VTK boundary, resets its outputs (to the unchanged input for a filter that passes its input
// on, else empty) and calls reportFailure: the message goes to the output window (ParaView's
// Output Messages) and every output carries the
// field-data string fields::Error ("DeformationError") with the message, which a script tests;
// the algorithm sets its error code to vtkErrorCode::UserError (a protected member of vtkAlgorithm)
// and to NoError at the start of RequestData.
// The request itself succeeds, so that a pipeline (ParaView's among them) updates normally once
// the input is fixed: a failed request left ParaView's representation stale after two failures in
// a row. A cancel (AbortExecute, checked within and between the stages of a long set-up: an
// AbortedException) is a failure like the others, except that a deformation filter leaves its
// previous output in place (what the user had before asking for a change and cancelling it) and
// the output window gets an information line, not an error: the user asked for it. reportFailure
// clears the request, so that it stops one update only.
#pragma once

#include <exception>
#include <string>

class vtkAlgorithm;
class vtkInformationVector;

namespace mlsvtk
{
/// outcome says what the outputs are now ("The output is the unchanged input."); context, if
/// any, precedes the exception's message. Returns 1, the value RequestData returns.
int reportFailure(vtkAlgorithm* algorithm, vtkInformationVector* outputs, const std::exception& failure, const char* outcome,
  const std::string& context = std::string());
} // namespace mlsvtk
