#include "Adapters/ReportArrays.h"

#include <vtkAbstractArray.h>
#include <vtkDataObject.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>

namespace mlsvtk
{
ReportArrays::ReportArrays(vtkInformationVector* input, vtkInformationVector* outputs)
  : Input(input)
  , Outputs(outputs)
{
}

ReportArrays::~ReportArrays()
{
  vtkFieldData* passed = nullptr;
  if (this->Input && this->Input->GetNumberOfInformationObjects() > 0)
  {
    vtkDataObject* input = vtkDataObject::GetData(this->Input, 0);
    passed = input ? input->GetFieldData() : nullptr;
  }
  for (int port = 0; port < this->Outputs->GetNumberOfInformationObjects(); ++port)
  {
    vtkDataObject* output = vtkDataObject::GetData(this->Outputs, port);
    vtkFieldData* field = output ? output->GetFieldData() : nullptr;
    for (int i = 0; field && i < field->GetNumberOfArrays(); ++i)
    {
      vtkAbstractArray* array = field->GetAbstractArray(i);
      bool fromInput = false;
      for (int j = 0; passed && j < passed->GetNumberOfArrays() && !fromInput; ++j)
      {
        fromInput = passed->GetAbstractArray(j) == array;
      }
      if (array && !fromInput && !array->GetInformation()->Has(vtkAbstractArray::GUI_HIDE()))
      {
        array->GetInformation()->Set(vtkAbstractArray::GUI_HIDE(), 1);
      }
    }
  }
}
} // namespace mlsvtk
