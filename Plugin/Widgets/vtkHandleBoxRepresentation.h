/**
 * @class vtkHandleBoxRepresentation
 * @brief The handle box of a Handle region: a box whose centre sphere stands out.
 *
 * ParaView's box draws its seven handles alike: the centre sphere, which moves the handle, had the
 * size and colour of the face spheres (which scale it) and of the region's point glyphs. Here the
 * centre sphere is CentreScale times as large as the others and drawn with CentreProperty (its
 * own colour) whenever it is not the highlighted handle. It is picked first: a click anywhere on
 * it moves the handle, even where a face sphere lies in front of it (seen along an axis of the box).
 */
#ifndef vtkHandleBoxRepresentation_h
#define vtkHandleBoxRepresentation_h

#include "MLSDeformWidgetsModule.h"
#include "vtkBoxRepresentation.h"

class MLSDEFORMWIDGETS_EXPORT vtkHandleBoxRepresentation : public vtkBoxRepresentation
{
public:
  static vtkHandleBoxRepresentation* New();
  vtkTypeMacro(vtkHandleBoxRepresentation, vtkBoxRepresentation);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The centre sphere's look when it is not highlighted.
  vtkGetObjectMacro(CentreProperty, vtkProperty);

  ///@{
  /// The centre sphere's radius over the other handles' (default 2, at least 1).
  vtkSetClampMacro(CentreScale, double, 1.0, 10.0);
  vtkGetMacro(CentreScale, double);
  ///@}

  void BuildRepresentation() override;
  int ComputeInteractionState(int X, int Y, int modify = 0) override;

protected:
  vtkHandleBoxRepresentation();
  ~vtkHandleBoxRepresentation() override;
  void SizeHandles() override;

  vtkProperty* CentreProperty;
  double CentreScale = 2.0;

private:
  vtkHandleBoxRepresentation(const vtkHandleBoxRepresentation&) = delete;
  void operator=(const vtkHandleBoxRepresentation&) = delete;
};

#endif
