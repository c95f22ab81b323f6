// Cancel from ParaView's progress bar for the plugin's long set-ups (issue 32, point 5).
// ParaView 5.11 keeps the bar's abort button disabled and processes no events while a filter
// runs, so a click could neither be made nor reach the filter. For the plugin's algorithms on
// the built-in server this enables the button while one runs and, at the algorithm's progress
// reports (at most every 0.1 s), processes the pending events with the user's input held
// (pqHeldInput: delivered in order after the update) and timers waiting, so that the bar repaints
// and a press on its button is seen without anything else running inside the update. The press
// sets the algorithm's AbortExecute, which its set-up checks within its stages
// (Adapters/AlgorithmProgress.h); a deformation then keeps its previous output and reports the
// cancel as a warning. The cancelled filter's Apply button is lit again (without Auto Apply), and
// Apply starts the set-up anew.
#pragma once

#include <QObject>
#include <QPointer>

#include <vtkNew.h>
#include <vtkWeakPointer.h>

class pqHeldInput;
class pqPipelineSource;
class pqServerManagerModelItem;
class vtkAlgorithm;
class vtkEventQtSlotConnect;
class vtkObject;

class pqSetUpCancel : public QObject
{
  Q_OBJECT

public:
  explicit pqSetUpCancel(QObject* parent = nullptr);
  ~pqSetUpCancel() override;
  void onStartup();
  void onShutdown() {}

private Q_SLOTS:
  void sourceAdded(pqPipelineSource* source);
  void sourceRemoved(pqPipelineSource* source);
  void started(vtkObject* algorithm);
  void progressed(vtkObject* algorithm);
  void ended(vtkObject* algorithm);
  void abort();
  /// A cancelled source applied again: its algorithm runs anew.
  void reapplied(pqServerManagerModelItem* item);

private:
  vtkNew<vtkEventQtSlotConnect> Connections;
  vtkWeakPointer<vtkAlgorithm> Running; // the plugin's algorithm in its update, if any
  bool Cancelled = false;               // the running one was asked to stop
  pqHeldInput* Input;                   // the user's input during an update, delivered after it
  double LastProcessed = 0;             // when events were last processed (seconds)
  QPointer<pqPipelineSource> CancelledSource; // waits for its next Apply
  bool Told = false;                          // the status bar says a set-up was cancelled
};
