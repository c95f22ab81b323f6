/**
 * @class vtkHandleBoxRepresentation
 * @brief The handle box of a Handle region: a box whose centre sphere stands out.
 *
 * ParaView's box draws its seven handles alike: the centre sphere, which moves the handle, had the
 * size and colour of the face spheres (which scale it) and of the region's point glyphs. Here the
 * centre sphere is CentreScale times as large as the others and drawn with CentreProperty (its
 * own colour) whenever it is not the highlighted handle. It is picked first: a click anywhere on
 * it moves the handle, even where a face sphere lies in front of it (seen along an axis of the box),
 * and so a face sphere seen over the centre sphere is not drawn.
 *
 * The edges and spheres are drawn with a dark halo (HaloProperty): lines wider than the edges
 * behind them, a ring around each sphere. The box stays visible over a model coloured in its own red, or in any
 * colour map.
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

  /// The halo's look (default black, lines 3 pixels wider than the outline's).
  vtkGetObjectMacro(HaloProperty, vtkProperty);

  ///@{
  /// The centre sphere's radius over the other handles' (default 2, at least 1).
  vtkSetClampMacro(CentreScale, double, 1.0, 10.0);
  vtkGetMacro(CentreScale, double);
  ///@}

  void BuildRepresentation() override;
  int ComputeInteractionState(int X, int Y, int modify = 0) override;
  int RenderOpaqueGeometry(vtkViewport* viewport) override;
  void ReleaseGraphicsResources(vtkWindow* window) override;

protected:
  vtkHandleBoxRepresentation();
  ~vtkHandleBoxRepresentation() override;
  void SizeHandles() override;
  void PositionHandles() override;

  vtkProperty* CentreProperty;
  vtkProperty* HaloProperty;
  vtkActor* EdgeHalo;        // behind the box's edges (vtkBoxRepresentation's HexActor)
  vtkActor* SphereHalo[7];   // around each handle sphere
  bool HiddenBehindCentre[6] = {}; // face spheres not drawn, seen over the centre sphere
  double CentreScale = 2.0;

private:
  void HideFaceSpheresOverCentre();

  vtkHandleBoxRepresentation(const vtkHandleBoxRepresentation&) = delete;
  void operator=(const vtkHandleBoxRepresentation&) = delete;
};

#endif
