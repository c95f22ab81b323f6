/**
 * @class vtkOFFReader
 * @brief Reads Object File Format (.off) meshes into vtkPolyData.
 *
 * Headers OFF, COFF (per-vertex colors), NOFF (per-vertex normals), CNOFF and NCOFF, optionally
 * prefixed with ST (texture coordinates, skipped); '#' starts a comment anywhere. Faces are
 * polygons of any size; colors after a face's indices are skipped. Vertex colors become the point
 * array "Colors" (RGBA, 0-255; float colors in [0,1] are scaled), normals the point normals.
 */
#ifndef vtkOFFReader_h
#define vtkOFFReader_h

#include "MLSDeformReadersModule.h"
#include "vtkPolyDataAlgorithm.h"

#include <string>

class MLSDEFORMREADERS_EXPORT vtkOFFReader : public vtkPolyDataAlgorithm
{
public:
  static vtkOFFReader* New();
  vtkTypeMacro(vtkOFFReader, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  ///@{
  /// The file to read.
  vtkSetStdStringFromCharMacro(FileName);
  vtkGetCharFromStdStringMacro(FileName);
  ///@}

  /// 1 if the file starts with an OFF header, else 0.
  static int CanReadFile(const char* filename);

protected:
  vtkOFFReader();
  ~vtkOFFReader() override = default;

  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  std::string FileName;

private:
  vtkOFFReader(const vtkOFFReader&) = delete;
  void operator=(const vtkOFFReader&) = delete;
};

#endif
