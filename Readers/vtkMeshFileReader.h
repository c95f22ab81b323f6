/**
 * @class vtkMeshFileReader
 * @brief Reads a solver's mesh file (an Abaqus/CalculiX deck, .inp) into an unstructured grid
 * whose variants vtkMeshVariantWriter writes back as that file.
 *
 * Elements become VTK cells (quadratic ones VTK's quadratic cells, their nodes in VTK's order).
 * The output carries what a variant needs and what users name regions by:
 *  - point data "NodeId" and cell data "ElementId": the file's ids;
 *  - a point array per node set (*NSET, *SURFACE) and a cell array per element set (*ELSET),
 *    named after it, 1 in the set and 0 outside (a Constraint Region's SelectionMode Blocks
 *    selects a set by name);
 *  - field data "SourceFile": the file read, and "QualityVerdict": "FemSolver" for a structural
 *    solver's format (its elements' Jacobian judge a variant), "CheckMesh" for a finite-volume
 *    solver's (OpenFOAM checkMesh's face measures).
 * A file that cannot be read gives an error naming the file and the line, and an empty output;
 * what the file holds but a grid cannot (an element type without a VTK cell) is a warning, its
 * elements left out. Under MPI the whole mesh is read on the first process.
 */
#ifndef vtkMeshFileReader_h
#define vtkMeshFileReader_h

#include "MLSDeformReadersModule.h"
#include "vtkUnstructuredGridAlgorithm.h"

#include <string>

class vtkInformationIntegerKey;

class MLSDEFORMREADERS_EXPORT vtkMeshFileReader : public vtkUnstructuredGridAlgorithm
{
public:
  static vtkMeshFileReader* New();
  vtkTypeMacro(vtkMeshFileReader, vtkUnstructuredGridAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /// 1 if the file is of a format this reader reads (by its extension and first bytes), else 0.
  static int CanReadFile(const char* filename);

  /// Set on the information of every set's array: a Constraint Region's panel lists these.
  static vtkInformationIntegerKey* NAMED_SET();

  /// Why the last read failed ("file:line: reason"), or "" when it succeeded; the error code
  /// (GetErrorCode) is then nonzero. For scripts, which cannot read the output window.
  vtkGetCharFromStdStringMacro(LastError);

protected:
  vtkMeshFileReader();
  ~vtkMeshFileReader() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;
  std::string LastError;

private:
  vtkMeshFileReader(const vtkMeshFileReader&) = delete;
  void operator=(const vtkMeshFileReader&) = delete;
};

#endif
