// The GUI's default look of the plugin's outputs: a deformed model (MLS Deform, Shell Deform)
// coloured by its displacement's magnitude, and Constraint Regions' positions drawn as points in
// one colour per role (Handle red, Fixed blue, geometric constraints green, Slip orange), so that
// the regions of a deformation can be told apart at a glance. Applied once, when an output is
// first shown; a state file's or the designer's own colours are kept. After each update of a
// deformed model, or of anything downstream of it (an Extract Block of a deformed case), the
// colour legend of what it is coloured by (Displacement, dX/d<variable>, ...) shows the range of
// the data shown now (unless the user locked it), and a zero field shows as zero.
#pragma once

#include <QObject>

class pqRepresentation;

class pqOutputColoring : public QObject
{
  Q_OBJECT

public:
  explicit pqOutputColoring(QObject* parent = nullptr);
  void onStartup();
  void onShutdown() {}

private Q_SLOTS:
  void representationAdded(pqRepresentation* representation);
  /// A representation's data changed: the legend follows, if it shows a deformation's data.
  void legendFollows();
};
