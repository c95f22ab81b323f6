// The field-data arrays an algorithm adds to its output are reports (figures, names, messages:
// InvertedCells, HandleResidual, Role, DeformationError, ...), not fields to colour a model by.
// ReportArrays marks them vtkAbstractArray::GUI_HIDE when RequestData returns, whatever way it
// returns, so that ParaView's array lists (the colouring menu) leave them out; scripts, the
// Information panel and the data information still see them. Arrays that came with the input
// (the same objects, passed on) are left as they are: the input is never modified.
#pragma once

class vtkInformationVector;

namespace mlsvtk
{
class ReportArrays
{
public:
  /// At the start of RequestData: the input of port 0 and the outputs.
  ReportArrays(vtkInformationVector* input, vtkInformationVector* outputs);
  ~ReportArrays();
  ReportArrays(const ReportArrays&) = delete;
  ReportArrays& operator=(const ReportArrays&) = delete;

private:
  vtkInformationVector* Input;
  vtkInformationVector* Outputs;
};
} // namespace mlsvtk
