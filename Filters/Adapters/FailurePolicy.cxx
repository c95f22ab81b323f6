#include "Adapters/FailurePolicy.h"

#include "Common/CoreTypes.h"
#include "Vocabulary/FieldNames.h"

#include <vtkAlgorithm.h>
#include <vtkDataObject.h>
#include <vtkFieldData.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkOutputWindow.h>
#include <vtkStringArray.h>

namespace mlsvtk
{
int reportFailure(vtkAlgorithm* algorithm, vtkInformationVector* outputs, const std::exception& failure, const char* outcome,
  const std::string& context)
{
  const std::string message = context + failure.what();
  // a cancel (CheckAbort) asked the executive to empty the outputs: they keep this convention's
  // instead; the request stopped this update only, the next one runs
  algorithm->SetAbortOutput(false);
  algorithm->SetAbortExecute(0);
  for (int port = 0; port < outputs->GetNumberOfInformationObjects(); ++port)
  {
    vtkDataObject* output = vtkDataObject::GetData(outputs, port);
    if (!output)
    {
      continue;
    }
    if (!output->GetFieldData())
    {
      output->SetFieldData(vtkNew<vtkFieldData>());
    }
    vtkNew<vtkStringArray> error;
    error->SetName(fields::Error);
    error->InsertNextValue(message);
    output->GetFieldData()->AddArray(error);
  }
  const bool sentence = !message.empty() && message.back() == '.';
  if (dynamic_cast<const mlsdeform::AbortedException*>(&failure))
  {
    // the user's cancel: an information line in the output window (no error pops it up)
    const std::string line = std::string(algorithm->GetClassName()) + ": cancelled. " + outcome + "\n";
    vtkOutputWindowDisplayText(line.c_str());
    return 1;
  }
  vtkErrorWithObjectMacro(algorithm, << algorithm->GetClassName() << " failed: " << message << (sentence ? " " : ". ") << outcome);
  return 1;
}
} // namespace mlsvtk
