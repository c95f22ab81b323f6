// The GUI's default look of Constraint Region outputs: their positions drawn as points in one
// colour per role (Handle red, Fixed blue, geometric constraints green, Slip orange), so that the
// regions of a deformation can be told apart at a glance. Applied once, when a region is first
// shown; a state file's or the designer's own colours are kept.
#pragma once

#include <QObject>

class pqRepresentation;

class pqRegionColoring : public QObject
{
  Q_OBJECT

public:
  explicit pqRegionColoring(QObject* parent = nullptr);
  void onStartup();
  void onShutdown() {}

private Q_SLOTS:
  void representationAdded(pqRepresentation* representation);
};
