// The handle motion of a Constraint Region in the ParaView GUI: a box in the render view around
// the selected positions, centred on the pivot, that the designer drags (its centre handle moves
// the handle, its faces rotate it about the pivot, its face handles scale it), and the
// Translation, Rotation and Scale fields, which follow the box and move it when typed. The box
// shows where the handle region goes, and the region's points are drawn there with it. One box at
// a time: a row of choices (the handle box, the region's selection box, none) decides which box
// the view shows, so that a click never lands on a box the designer did not mean; the handle box
// shows once the region has selected its positions (its first Apply). Its centre sphere, which
// moves the handle, is twice the size of the others and of its own colour
// (vtkHandleBoxRepresentation), and never beside a face handle: the box is at least a quarter as
// thick as it is long.
#pragma once

#include "Adapters/HandleMotion.h"

#include <pqInteractivePropertyWidget.h>
#include <vtkNew.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkWeakPointer.h>

class QButtonGroup;
class pqDataRepresentation;
class pqDoubleLineEdit;
class pqPipelineSource;
class vtkSMProperty;

class pqHandleMotionWidget : public pqInteractivePropertyWidget
{
  Q_OBJECT
  using Superclass = pqInteractivePropertyWidget;

public:
  pqHandleMotionWidget(vtkSMProxy* proxy, vtkSMPropertyGroup* group, QWidget* parent = nullptr);
  ~pqHandleMotionWidget() override;

  /// Shows the box in the view, and once more over everything (OnTop).
  void setView(pqView* view) override;

  /// The boxes a Handle region can show in the view, one at a time.
  enum class Box
  {
    Handle,
    Selection,
    None
  };

protected:
  /// Keeps the designer's Show Box choice while the panel is hidden (the base keeps whether the
  /// box was on screen, which it is not while the region is not the active source).
  void hideEvent(QHideEvent* event) override;
  /// The chosen box shown again, once the panel's other widgets have shown theirs.
  void showEvent(QShowEvent* event) override;

protected Q_SLOTS:
  /// Places the box around the selected positions (the region's output at rest), centred on the
  /// pivot of the last update, and moves it by the current motion.
  void placeWidget() override;

private Q_SLOTS:
  /// The box was dragged: the motion fields take its transform.
  void boxMoved();
  /// The motion fields changed (typed, reset, or set from Python): the box follows.
  void motionEdited();
  /// The region's points are shown in a view (its first Apply): drawn where the handle goes.
  void regionShown(pqPipelineSource*, pqDataRepresentation* representation);
  /// A drag begins: what it changes, and what Auto Apply applies on the way, is one undo step.
  void dragStarted();
  /// A drag ends: its undo step closes once its last motion is applied (at once without Auto
  /// Apply: Apply is then a step of its own).
  void dragEnded();
  /// Shows the chosen box and hides the other (a Handle whose positions are selected), or the
  /// selection box alone (another role, or no positions yet).
  void showChosenBox();
  /// A selection box shown or hidden with its own Show Box: it becomes the choice.
  void selectionBoxToggled(bool shown);

private:
  /// The region's Dragging (vtkConstraintRegion): on while a drag's steps are applied one by one,
  /// so that MLS Deform moves the surface blocks only; off on release.
  void setRegionDragging(bool dragging);
  /// The box's transform for the motion in the fields (applied or not).
  mlsvtk::BoxTransform motionTransform() const;
  /// Draws the region's points (in the given representation, or in the active view) moved by the
  /// box's transform, where the handle goes; unmoved once the region is no Handle.
  void moveRegionPoints(pqDataRepresentation* shown = nullptr);

  /// Draws the box once more over everything in the view's window (OnTop), or nowhere.
  void showOnTop(pqView* view);
  /// Takes the box out of that window.
  void removeOnTop();
  /// The region's other box widgets in its panel (the selection box of its Region function).
  QList<pqInteractivePropertyWidget*> selectionBoxes() const;

  vtkSMProperty* Motion[3]; // Translation, Rotation, Scale
  // The box drawn once more in a renderer on the layer above the view's, whose depth buffer is
  // cleared: its centre sphere, which moves the handle, sits at the pivot inside the solid,
  // where the model hides it. The view's renderer picks it (a box handle is picked whatever hides it).
  vtkNew<vtkRenderer> OnTop;
  vtkWeakPointer<vtkRenderWindow> OnTopWindow;
  double Pivot[3] = { 0, 0, 0 };
  bool Updating = false; // set while one side is written from the other
  bool Dragging = false;  // a drag's undo step is open
  bool DragEnded = false; // its end event came (the step closes once the drag is applied)
  Box Shown = Box::Handle; // the designer's choice of box
  QButtonGroup* BoxChoice;
  bool ShowingBoxes = false; // set while showChosenBox sets the boxes' visibility
};
