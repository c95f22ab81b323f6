/**
 * @class vtkMeshVariantWriter
 * @brief Writes a variant of a solver's mesh file: the source file (and the files it includes)
 * with only the node coordinates changed, every other byte as it was.
 *
 * The input is a deformation of what vtkMeshFileReader read: its points are the new coordinates,
 * its point data "NodeId" the file's node ids (any order), its field data "SourceFile" the source
 * (or SourceFile set here). Or a deformation of what ParaView's own CGNS, IOSS or Exodus II reader
 * read: the source is that reader's file, the nodes the Exodus node ids ("ids", "GlobalNodeId")
 * or a CGNS zone's (the blocks named by base and zone, points in the zone's order). The source's format (vtkMeshFileReader's formats) decides how the
 * variant is written; an Abaqus/CalculiX deck's includes are written beside FileName under the
 * names the deck gives them.
 *
 * Nothing partial is written: the files are written aside and renamed into place. Errors (no
 * NodeId or source, data that did not come from the source: another node count or other ids, a
 * target that is the source or one of its files, an existing target without Overwrite, NaN
 * coordinates) leave every file as it was, are reported in the output window and set the error
 * code.
 */
#ifndef vtkMeshVariantWriter_h
#define vtkMeshVariantWriter_h

#include "MLSDeformReadersModule.h"
#include "vtkWriter.h"

#include <string>

class MLSDEFORMREADERS_EXPORT vtkMeshVariantWriter : public vtkWriter
{
public:
  static vtkMeshVariantWriter* New();
  vtkTypeMacro(vtkMeshVariantWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The variant's file (its includes are written beside it).
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// The source file; empty (default): the input's field data SourceFile.
  vtkSetStdStringFromCharMacro(SourceFile);
  vtkGetCharFromStdStringMacro(SourceFile);
  ///@}

  ///@{
  /// Replace existing files (default off: an existing target is an error).
  vtkSetMacro(Overwrite, vtkTypeBool);
  vtkGetMacro(Overwrite, vtkTypeBool);
  vtkBooleanMacro(Overwrite, vtkTypeBool);
  ///@}

  /// The source file Write writes a variant of: SourceFile, else the input's field data
  /// SourceFile, else the file of ParaView's CGNS, IOSS or Exodus II reader up the pipeline; ""
  /// when none. Whether variants of it get an FEM solver's verdict: FindSourceIsFem.
  std::string FindSourceFile();
  bool FindSourceIsFem();

  /// Why the last write wrote nothing, or "" when it wrote the variant (the error code is then 0).
  vtkGetCharFromStdStringMacro(LastError);

protected:
  vtkMeshVariantWriter() = default;
  ~vtkMeshVariantWriter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  std::string FileName;
  std::string SourceFile;
  vtkTypeBool Overwrite = 0;
  std::string LastError;

private:
  vtkMeshVariantWriter(const vtkMeshVariantWriter&) = delete;
  void operator=(const vtkMeshVariantWriter&) = delete;
};

#endif
