/**
 * @class vtkAVSucdReaderUnlessDeck
 * @brief ParaView's AVS UCD reader, which declines Abaqus/CalculiX decks.
 *
 * AVS UCD files and Abaqus decks share the extension .inp, and ParaView's AVS UCD reader claims
 * every .inp file, so that ParaView asks which reader to open a deck with. The plugin's
 * definition of the AVS UCD reader's proxy uses this class, whose CanReadFile declines a deck:
 * a deck opens with the Mesh File reader, an AVS UCD file with the AVS UCD reader, unasked.
 */
#ifndef vtkAVSucdReaderUnlessDeck_h
#define vtkAVSucdReaderUnlessDeck_h

#include "MLSDeformReadersModule.h"
#include "vtkAVSucdReader.h"

class MLSDEFORMREADERS_EXPORT vtkAVSucdReaderUnlessDeck : public vtkAVSucdReader
{
public:
  static vtkAVSucdReaderUnlessDeck* New();
  vtkTypeMacro(vtkAVSucdReaderUnlessDeck, vtkAVSucdReader);

  /// 0 for a file the Mesh File reader reads, else 1.
  int CanReadFile(const char* filename);

protected:
  vtkAVSucdReaderUnlessDeck() = default;
  ~vtkAVSucdReaderUnlessDeck() override = default;

private:
  vtkAVSucdReaderUnlessDeck(const vtkAVSucdReaderUnlessDeck&) = delete;
  void operator=(const vtkAVSucdReaderUnlessDeck&) = delete;
};

#endif
