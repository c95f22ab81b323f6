#include "vtkAVSucdReaderUnlessDeck.h"

#include "vtkMeshFileReader.h"

#include <vtkObjectFactory.h>

vtkStandardNewMacro(vtkAVSucdReaderUnlessDeck);

int vtkAVSucdReaderUnlessDeck::CanReadFile(const char* filename)
{
  return vtkMeshFileReader::CanReadFile(filename) ? 0 : 1;
}
