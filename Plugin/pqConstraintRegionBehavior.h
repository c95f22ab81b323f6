// What the GUI does for Constraint Regions beyond their panel, so that a case's regions take a few
// clicks and can be told apart in the pipeline browser:
//  - a region made from the Filters menu on a composite input (an OpenFOAM case, a mesh file's
//    blocks) starts in SelectionMode Blocks, its panel showing the input's blocks to tick;
//  - a region is named after its role and what it selects ("Handle: hull", "Fixed: inlet,
//    outlet", "Slip: ground, top +2", "Handle (Box)") from its creation in the Filters menu
//    ("Handle") and whenever that changes once applied, unless the user gave it a name of their
//    own; the Properties panel's header follows.
#pragma once

#include <QMap>
#include <QObject>
#include <QPointer>
#include <QString>

class pqPipelineSource;

class pqConstraintRegionBehavior : public QObject
{
  Q_OBJECT

public:
  explicit pqConstraintRegionBehavior(QObject* parent = nullptr);
  void onStartup();
  void onShutdown() {}

  /// The name a region's role and selection give it (vtkSMProxy of a ConstraintRegion).
  static QString nameOf(pqPipelineSource* region);

private Q_SLOTS:
  void filterCreated(pqPipelineSource* source);
  void sourceAdded(pqPipelineSource* source);
  void sourceRemoved(pqPipelineSource* source);
  /// Applied and updated: the name follows the role and the selection.
  void regionUpdated(pqPipelineSource* region);

private:
  QMap<pqPipelineSource*, QString> Given; // the name each region was last given here
};
