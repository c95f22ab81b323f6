/**
 * @class vtkOpenFOAMCaseWriter
 * @brief Writes a deformed OpenFOAM case: the source case with new constant/polyMesh/points.
 *
 * The input is MLS Deform's output on what ParaView's OpenFOAM reader read (a multiblock with
 * an "internalMesh" block, or that block alone), with the reader's field data CasePath naming
 * the source case. FileName is the new case's .foam file: its folder becomes the new case, with
 * the source's system/ and constant/ and its initial-condition folder (the earliest time, and
 * 0.orig if there is one) copied, and of each processor* folder its constant/ and earliest time;
 * later time folders and postProcessing are left out. constant/polyMesh/points is replaced by the source's own double points plus the
 * internal mesh's point array Displacement, in the source file's format (ascii or binary,
 * compressed or not). The reader's float32 points are never written: they only check that the
 * input came from this case (each point within float round-off of the source's). Points the
 * reader appends for *Decompose polyhedra* (cell centres, after the polyMesh points) are ignored.
 *
 * Every mesh of a decomposed case is moved: the input is matched to the reconstructed mesh, or
 * (Case Type Decomposed) to the processor folders the reader gives each MPI rank (rank r:
 * processor r, r + N, ..., one after the other); the meshes not read are moved through the
 * processors' pointProcAddressing. Under MPI every rank writes the folders it read and rank 0
 * assembles the case; the ranks agree on every step, so an error on one stops all.
 *
 * Nothing partial is written: the case is assembled in a sibling folder and renamed into place.
 * Errors (no CasePath, a point count or positions that do not match the case, a FileName that is
 * not a .foam file, an existing target without Overwrite or that is not an OpenFOAM case, the
 * source itself as target, an unwritable folder) leave the target untouched, are reported in the
 * output window and by LastError, and set the error code.
 */
#ifndef vtkOpenFOAMCaseWriter_h
#define vtkOpenFOAMCaseWriter_h

#include "MLSDeformReadersModule.h"
#include "vtkWriter.h"

#include <string>

class MLSDEFORMREADERS_EXPORT vtkOpenFOAMCaseWriter : public vtkWriter
{
public:
  static vtkOpenFOAMCaseWriter* New();
  vtkTypeMacro(vtkOpenFOAMCaseWriter, vtkWriter);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The new case's .foam file (its folder is the new case).
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  ///@{
  /// The source case folder; empty (default): the input's field data CasePath.
  vtkSetStdStringFromCharMacro(SourceCase);
  vtkGetCharFromStdStringMacro(SourceCase);
  ///@}

  ///@{
  /// Replace an existing target case folder (default off: an existing target is an error). Only
  /// a folder that is an OpenFOAM case (system/controlDict) is replaced, never any other folder.
  vtkSetMacro(Overwrite, vtkTypeBool);
  vtkGetMacro(Overwrite, vtkTypeBool);
  vtkBooleanMacro(Overwrite, vtkTypeBool);
  ///@}

  ///@{
  /// Link the source's unchanged files (symbolic links to their absolute paths; OpenFOAM reads
  /// through them) instead of copying them: a variant then holds its own points only, and its
  /// dictionaries and initial fields are the source's (default off: a self-contained copy). A
  /// solver run on a linked variant writes its own time folders and leaves the source as it is;
  /// a tool that edits a dictionary in place would edit the source's through the link.
  vtkSetMacro(LinkUnchangedFiles, vtkTypeBool);
  vtkGetMacro(LinkUnchangedFiles, vtkTypeBool);
  vtkBooleanMacro(LinkUnchangedFiles, vtkTypeBool);
  ///@}

  /// Why the last write wrote nothing, or "" when it wrote the case (the error code is then 0).
  vtkGetCharFromStdStringMacro(LastError);

protected:
  vtkOpenFOAMCaseWriter() = default;
  ~vtkOpenFOAMCaseWriter() override = default;

  int FillInputPortInformation(int port, vtkInformation* info) override;
  void WriteData() override;

  std::string FileName;
  std::string SourceCase;
  vtkTypeBool Overwrite = 0;
  vtkTypeBool LinkUnchangedFiles = 0;
  std::string LastError;

private:
  vtkOpenFOAMCaseWriter(const vtkOpenFOAMCaseWriter&) = delete;
  void operator=(const vtkOpenFOAMCaseWriter&) = delete;
};

#endif
