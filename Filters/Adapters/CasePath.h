// Where a dataset was read from: the OpenFOAM case (the field data CasePath that VTK's OpenFOAM
// reader puts on its output) or the solver's mesh file (the field data SourceFile of the Mesh File
// reader, and QualityVerdict: whose verdict its variants get; or one of ParaView's readers up the
// pipeline). Header only: the writers (Readers/) and the mesh quality share it.
#pragma once

#include <vtkAbstractArray.h>
#include <vtkAlgorithm.h>
#include <vtkAlgorithmOutput.h>
#include <vtkCharArray.h>
#include <vtkDataObject.h>
#include <vtkFieldData.h>
#include <vtkStringArray.h>

#include <string>

namespace mlsvtk
{
/// The CasePath field data of data (a char array, or a string array), or "" when it has none.
inline std::string casePathOf(vtkDataObject* data)
{
  vtkAbstractArray* array = data && data->GetFieldData() ? data->GetFieldData()->GetAbstractArray("CasePath") : nullptr;
  if (auto* strings = vtkStringArray::SafeDownCast(array))
  {
    return strings->GetNumberOfValues() > 0 ? strings->GetValue(0) : std::string();
  }
  std::string path;
  if (auto* chars = vtkCharArray::SafeDownCast(array))
  {
    for (vtkIdType i = 0; i < chars->GetNumberOfValues() && chars->GetValue(i) != '\0'; ++i)
    {
      path += chars->GetValue(i);
    }
  }
  return path;
}

/// The SourceFile field data of data (the Mesh File reader's), or "" when it has none.
inline std::string sourceFileOf(vtkDataObject* data)
{
  auto* array = vtkStringArray::SafeDownCast(
    data && data->GetFieldData() ? data->GetFieldData()->GetAbstractArray("SourceFile") : nullptr);
  return array && array->GetNumberOfValues() > 0 ? array->GetValue(0) : std::string();
}

/// Whether data came from a structural solver's mesh file, whose variants an FEM solver's verdict
/// judges (the Mesh File reader's field data QualityVerdict "FemSolver").
inline bool femVerdictOf(vtkDataObject* data)
{
  auto* array = vtkStringArray::SafeDownCast(
    data && data->GetFieldData() ? data->GetFieldData()->GetAbstractArray("QualityVerdict") : nullptr);
  return array && array->GetNumberOfValues() > 0 && array->GetValue(0) == "FemSolver";
}

/// Whether algorithm's input (along each first input) was read by one of ParaView's readers of a
/// structural solver's mesh file (Exodus II: vtkIOSSReader, vtkExodusIIReader and its series
/// reader), which do not record it in their output as the Mesh File reader does. By class name:
/// no link to the readers' modules.
inline bool femReaderUpstream(vtkAlgorithm* algorithm)
{
  while (algorithm && algorithm->GetNumberOfInputPorts() > 0 && algorithm->GetNumberOfInputConnections(0) > 0)
  {
    algorithm = algorithm->GetInputConnection(0, 0)->GetProducer();
    for (const char* reader : { "vtkIOSSReader", "vtkExodusIIReader", "vtkExodusFileSeriesReader" })
    {
      if (algorithm->IsA(reader))
      {
        return true;
      }
    }
  }
  return false;
}
} // namespace mlsvtk
