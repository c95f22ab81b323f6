// The GUI's default look of the plugin's outputs: a deformed model (MLS Deform, Shell Deform)
// coloured by its displacement's magnitude, and Constraint Regions' positions drawn as points in
// one colour per role (Handle red, Fixed blue, geometric constraints green, Slip orange), so that
// the regions of a deformation can be told apart at a glance. Applied once, when an output is
// first shown; a state file's or the designer's own colours are kept. A Handle with control
// points (local shape variables: its output carries ControlDirection) draws them as arrows along
// their directions (3D Glyphs, a twentieth of its model's size), once they appear, unless the
// user chose another representation. After each update of a
// deformed model, or of anything downstream of it (an Extract Block of a deformed case), the
// colour legend of what it is coloured by (Displacement, dX/d<variable>, ...) shows the range of
// the data shown now (unless the user locked it), and a zero field shows as zero, also when
// ParaView rescales the legend itself (another component, colouring anew, Reset Range).
// The colouring menu lists the data's fields, not the arrays ParaView makes to draw them
// (vtkEdgeFlags, of a mesh with quadratic elements: a filter expression of Edit > Settings >
// Miscellaneous, added to each server's settings if missing).
#pragma once

#include <QObject>
#include <QSet>

#include <vtkNew.h>

class pqRepresentation;
class pqServer;
class vtkEventQtSlotConnect;
class vtkObject;
class vtkSMProxy;

class pqOutputColoring : public QObject
{
  Q_OBJECT

public:
  explicit pqOutputColoring(QObject* parent = nullptr);
  ~pqOutputColoring() override;
  void onStartup();
  void onShutdown() {}

private Q_SLOTS:
  void representationAdded(pqRepresentation* representation);
  /// The arrays ParaView makes to draw data out of the server's colouring menus.
  void drawingArraysUnlisted(pqServer* server);
  /// A representation's data changed: the legend follows, if it shows a deformation's data.
  void legendFollows();
  /// A followed legend's range changed (ParaView rescaled it): an empty range of a zero field
  /// reads as zero.
  void legendRescaled(vtkObject* legend, unsigned long, void*, void* property);
  void legendDeleted(vtkObject* legend);
  /// A region's data changed: its control points, if it has them now, drawn as arrows.
  void controlPointsDrawn();

private:
  /// Rescales a legend to the range of the data it colours (zero: 0 to 1% of the model's size).
  void rescale(vtkSMProxy* lut);

  vtkNew<vtkEventQtSlotConnect> Connections;
  QSet<vtkSMProxy*> Followed; // the legends of deformations' data
  QSet<vtkSMProxy*> Arrows;   // the region representations whose control points are drawn as arrows
  bool Rescaling = false;     // set while rescale() changes a legend
};
