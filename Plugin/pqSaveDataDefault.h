// File > Save Data of data read from a solver's file (a deck, a CGNS or Exodus file: what the
// Mesh File Variant writer's SourceFileDomain accepts) preselects that writer's file type, so
// that a deformation is saved as its source file's variant (boundary conditions, sets and zones
// kept) unless the user picks another type. ParaView 5.11's dialog preselects the first type
// that holds the data type's remembered extension (setting extensions/SaveDataExtension/<type>):
// while such data is active that setting holds the variant writer's marker, and the user's own
// value is put back when other data becomes active.
#pragma once

#include <QObject>

class pqOutputPort;

class pqSaveDataDefault : public QObject
{
  Q_OBJECT

public:
  explicit pqSaveDataDefault(QObject* parent = nullptr);
  void onStartup();
  void onShutdown() {}

  /// Whether the Mesh File Variant writer accepts the data of port (its Input's domains).
  static bool fromSourceFile(pqOutputPort* port);

private Q_SLOTS:
  void portChanged(pqOutputPort* port);
};
