#include "pqSetUpCancel.h"
#include "pqHeldInput.h"

#include "vtkDeformationQuality.h"
#include "vtkMLSSampler.h"
#include "vtkPrimitiveDetector.h"
#include "vtkSubspaceDeformFilter.h"

#include <pqApplicationCore.h>
#include <pqCoreUtilities.h>
#include <pqPipelineSource.h>
#include <pqProgressManager.h>
#include <pqProgressWidget.h>
#include <pqServerManagerModel.h>
#include <vtkAlgorithm.h>
#include <vtkCommand.h>
#include <vtkEventQtSlotConnect.h>
#include <vtkPVGeneralSettings.h>
#include <vtkSMProxy.h>
#include <vtkTimerLog.h>

#include <QApplication>
#include <QMainWindow>
#include <QStatusBar>
#include <QThread>
#include <QToolButton>

namespace
{
// Seconds between two event processings within one update: the progress bar repaints ten times a
// second and a click reaches the algorithm within that, at a negligible cost to the update.
constexpr double ProcessingInterval = 0.1;

// The plugin's algorithms that check AbortExecute within or between their stages.
bool cancellable(vtkObject* object)
{
  return vtkSubspaceDeformFilter::SafeDownCast(object) || vtkMLSSampler::SafeDownCast(object) ||
    vtkPrimitiveDetector::SafeDownCast(object) || vtkDeformationQuality::SafeDownCast(object);
}

vtkAlgorithm* algorithmOf(pqPipelineSource* source)
{
  // the object itself on the built-in server only (none on a remote server's client)
  vtkObjectBase* object = source && source->getProxy() ? source->getProxy()->GetClientSideObject() : nullptr;
  auto* algorithm = vtkAlgorithm::SafeDownCast(object);
  return algorithm && cancellable(algorithm) ? algorithm : nullptr;
}

// The main window's status bar.
QStatusBar* statusBar()
{
  auto* window = qobject_cast<QMainWindow*>(pqCoreUtilities::mainWidget());
  return window ? window->statusBar() : nullptr;
}

// The progress bar's abort button, if the main window has one.
QToolButton* abortButton()
{
  for (const QPointer<QObject>& object : pqApplicationCore::instance()->getProgressManager()->nonBlockableObjects())
  {
    if (auto* bar = qobject_cast<pqProgressWidget*>(object.data()))
    {
      return bar->abortButton();
    }
  }
  return nullptr;
}
}

pqSetUpCancel::pqSetUpCancel(QObject* parent)
  : QObject(parent)
  , Input(new pqHeldInput(this))
{
}

pqSetUpCancel::~pqSetUpCancel() = default;

void pqSetUpCancel::onStartup()
{
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  QObject::connect(model, &pqServerManagerModel::sourceAdded, this, &pqSetUpCancel::sourceAdded);
  QObject::connect(model, &pqServerManagerModel::preSourceRemoved, this, &pqSetUpCancel::sourceRemoved);
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    this->sourceAdded(source);
  }
  QObject::connect(pqApplicationCore::instance()->getProgressManager(), &pqProgressManager::abort, this, &pqSetUpCancel::abort);
}

void pqSetUpCancel::sourceAdded(pqPipelineSource* source)
{
  if (vtkAlgorithm* algorithm = algorithmOf(source))
  {
    this->Connections->Connect(algorithm, vtkCommand::StartEvent, this, SLOT(started(vtkObject*)));
    this->Connections->Connect(algorithm, vtkCommand::ProgressEvent, this, SLOT(progressed(vtkObject*)));
    this->Connections->Connect(algorithm, vtkCommand::EndEvent, this, SLOT(ended(vtkObject*)));
  }
}

void pqSetUpCancel::sourceRemoved(pqPipelineSource* source)
{
  if (vtkAlgorithm* algorithm = algorithmOf(source))
  {
    this->Connections->Disconnect(algorithm);
  }
}

void pqSetUpCancel::started(vtkObject* algorithm)
{
  if (this->Running)
  {
    return; // one of the plugin's algorithms updates another (the first one keeps the button)
  }
  this->Running = vtkAlgorithm::SafeDownCast(algorithm);
  this->Cancelled = false;
  this->LastProcessed = 0; // the first progress report already processes events
  pqApplicationCore::instance()->getProgressManager()->setEnableAbort(true);
}

void pqSetUpCancel::progressed(vtkObject* algorithm)
{
  const double now = vtkTimerLog::GetUniversalTime();
  if (algorithm != this->Running || QThread::currentThread() != qApp->thread() || now - this->LastProcessed < ProcessingInterval)
  {
    return;
  }
  // a press on the abort button, whether the window or the button receives it, is the abort
  // (ParaView's progress manager holds back a press on the button itself)
  this->Input->processEvents([](const QPoint& at) {
    QToolButton* button = abortButton();
    if (button && button->isEnabled() && button->isVisible() && button->rect().contains(button->mapFromGlobal(at)))
    {
      pqApplicationCore::instance()->getProgressManager()->triggerAbort();
    }
  });
  this->LastProcessed = vtkTimerLog::GetUniversalTime();
}

void pqSetUpCancel::abort()
{
  if (this->Running)
  {
    this->Cancelled = true;
    this->Running->SetAbortExecute(1); // checked by the set-up within and between its stages
  }
}

void pqSetUpCancel::ended(vtkObject* algorithm)
{
  if (algorithm != this->Running)
  {
    return;
  }
  this->Running = nullptr;
  pqApplicationCore::instance()->getProgressManager()->setEnableAbort(false);
  this->Input->deliverLater(); // the input that came during the update
  if (!this->Cancelled)
  {
    if (QStatusBar* bar = this->Told ? statusBar() : nullptr)
    {
      bar->clearMessage(); // the set-up ran through: the cancel's note is done
    }
    this->Told = false;
    return;
  }
  this->Cancelled = false;
  auto* cancelled = vtkAlgorithm::SafeDownCast(algorithm);
  cancelled->SetAbortExecute(0); // a request that came after the last check stops nothing later
  pqServerManagerModel* model = pqApplicationCore::instance()->getServerManagerModel();
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    if (algorithmOf(source) == cancelled)
    {
      // Apply lit again: applied, the set-up starts anew (with Auto Apply, a change starts it)
      this->CancelledSource = source;
      QObject::connect(source, &pqProxy::modifiedStateChanged, this, &pqSetUpCancel::reapplied, Qt::UniqueConnection);
      const bool autoApply = vtkPVGeneralSettings::GetInstance()->GetAutoApply();
      if (!autoApply)
      {
        source->setModifiedState(pqProxy::MODIFIED);
      }
      // where the user looks (the output window's line is out of sight): the view is not the panel's
      if (QStatusBar* bar = statusBar())
      {
        // short: the progress bar beside it takes most of the bar's width
        auto* deform = vtkSubspaceDeformFilter::SafeDownCast(cancelled);
        const bool previous = !deform || deform->GetOutputDeformed();
        bar->showMessage(QString("%1: set-up cancelled, %2 shown. %3 runs it again.")
                           .arg(source->getSMName(), previous ? "the previous deformation" : "the undeformed model",
                             autoApply ? "The next change" : "Apply"));
        this->Told = true;
      }
    }
  }
}

void pqSetUpCancel::reapplied(pqServerManagerModelItem* item)
{
  pqPipelineSource* source = this->CancelledSource;
  if (!source || item != source || source->modifiedState() != pqProxy::UNMODIFIED)
  {
    return;
  }
  QObject::disconnect(source, &pqProxy::modifiedStateChanged, this, &pqSetUpCancel::reapplied);
  this->CancelledSource = nullptr;
  if (vtkAlgorithm* algorithm = algorithmOf(source))
  {
    // runs again at the render that follows the Apply: the algorithm is out of date, and so is
    // what the views hold of it (no property changed, so the Apply alone marks nothing)
    algorithm->Modified();
    source->getProxy()->MarkModified(source->getProxy());
  }
}
