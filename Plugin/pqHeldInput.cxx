#include "pqHeldInput.h"

#include <QCloseEvent>
#include <QContextMenuEvent>
#include <QCoreApplication>
#include <QKeyEvent>
#include <QMouseEvent>
#include <QTabletEvent>
#include <QTouchEvent>
#include <QWheelEvent>
#include <QWindow>

// Qt's own entry for a key event as the window system gives it (QtGui exports it for QtTest's key
// clicks): the shortcut map and the focus widget see a held key as they would have at once.
Q_GUI_EXPORT void qt_handleKeyEvent(
  QWindow* window, QEvent::Type type, int key, Qt::KeyboardModifiers modifiers, const QString& text, bool autorepeat, ushort count);

namespace
{
const QEvent::Type DeliverEvent = static_cast<QEvent::Type>(QEvent::registerEventType());

// A copy of the user's input as the window system gives it to a window (QGuiApplication sends it
// to the QWindow before the window passes it on to its widgets), of the event's own class; none
// for any other event.
std::unique_ptr<QEvent> copyOfInput(const QEvent* event)
{
  switch (event->type())
  {
    case QEvent::MouseButtonPress:
    case QEvent::MouseButtonRelease:
    case QEvent::MouseButtonDblClick:
    case QEvent::MouseMove:
    case QEvent::NonClientAreaMouseButtonPress:
    case QEvent::NonClientAreaMouseButtonRelease:
    case QEvent::NonClientAreaMouseButtonDblClick:
    case QEvent::NonClientAreaMouseMove:
      return std::make_unique<QMouseEvent>(*static_cast<const QMouseEvent*>(event));
    case QEvent::KeyPress:
    case QEvent::KeyRelease:
      return std::make_unique<QKeyEvent>(*static_cast<const QKeyEvent*>(event));
    case QEvent::Wheel:
      return std::make_unique<QWheelEvent>(*static_cast<const QWheelEvent*>(event));
    case QEvent::Enter:
      return std::make_unique<QEnterEvent>(*static_cast<const QEnterEvent*>(event));
    case QEvent::Leave:
      return std::make_unique<QEvent>(*event);
    case QEvent::ContextMenu:
      return std::make_unique<QContextMenuEvent>(*static_cast<const QContextMenuEvent*>(event));
    case QEvent::TabletPress:
    case QEvent::TabletRelease:
    case QEvent::TabletMove:
      return std::make_unique<QTabletEvent>(*static_cast<const QTabletEvent*>(event));
    case QEvent::TouchBegin:
    case QEvent::TouchUpdate:
    case QEvent::TouchEnd:
    case QEvent::TouchCancel:
      return std::make_unique<QTouchEvent>(*static_cast<const QTouchEvent*>(event));
    case QEvent::Close:
      return std::make_unique<QCloseEvent>(*static_cast<const QCloseEvent*>(event));
    default:
      return nullptr;
  }
}

bool dragAndDrop(QEvent::Type type)
{
  return type == QEvent::DragEnter || type == QEvent::DragMove || type == QEvent::DragLeave || type == QEvent::Drop;
}
}

// One held event, a copy, and the window it was given to.
struct pqHeldInput::Held
{
  QPointer<QWindow> window;
  std::unique_ptr<QEvent> event;
};

pqHeldInput::pqHeldInput(QObject* parent)
  : QObject(parent)
{
  // the application quits: what is held goes nowhere, and nothing is held any more
  QObject::connect(qApp, &QCoreApplication::aboutToQuit, this, [this]() {
    this->Queue.clear();
    this->updateFilter();
  });
}

pqHeldInput::~pqHeldInput()
{
  if (this->Filtering)
  {
    qApp->removeEventFilter(this);
  }
}

void pqHeldInput::processEvents(const std::function<void(const QPoint& global)>& pressed)
{
  if (this->Processing)
  {
    return;
  }
  this->Processing = true;
  this->Pressed = pressed;
  this->updateFilter();
  QCoreApplication::processEvents();
  this->Pressed = nullptr;
  this->Processing = false;
  this->updateFilter();
}

void pqHeldInput::updateFilter()
{
  const bool needed = this->Processing || !this->Queue.empty();
  if (needed && !this->Filtering)
  {
    qApp->installEventFilter(this); // before the filters installed earlier (ParaView's progress manager's)
  }
  else if (!needed && this->Filtering)
  {
    qApp->removeEventFilter(this);
  }
  this->Filtering = needed;
}

bool pqHeldInput::eventFilter(QObject* object, QEvent* event)
{
  const QEvent::Type type = event->type();
  if (this->Processing && type == QEvent::Timer)
  {
    return true; // a timer fires again at its next interval, after the update
  }
  if (this->Processing && dragAndDrop(type))
  {
    event->ignore(); // a drop is answered at once: refused while the update runs
    return true;
  }
  auto* window = qobject_cast<QWindow*>(object);
  // held: during an update, and after it while held input waits (but not the input of a dialog
  // that a delivered event opened, nor a close, which QWindow::close() asks for and answers at
  // once)
  const bool holding = this->Processing || (!this->Queue.empty() && this->Delivering == 0 && type != QEvent::Close);
  if (!window || !event->spontaneous() || !holding)
  {
    return this->QObject::eventFilter(object, event);
  }
  if (type == QEvent::ShortcutOverride)
  {
    // taken by the focus: no shortcut runs now; the key press follows and is held, and its
    // delivery looks the shortcut up again
    event->accept();
    return true;
  }
  std::unique_ptr<QEvent> copy = copyOfInput(event);
  if (!copy)
  {
    return this->QObject::eventFilter(object, event);
  }
  auto held = std::make_unique<Held>();
  held->window = window;
  held->event = std::move(copy);
  if (type == QEvent::MouseButtonPress && this->Processing && this->Pressed)
  {
    this->Pressed(static_cast<const QMouseEvent*>(event)->globalPos());
  }
  this->Queue.push_back(std::move(held));
  return true;
}

void pqHeldInput::deliverLater()
{
  if (!this->Queue.empty() && !this->DeliveryPosted)
  {
    this->DeliveryPosted = true;
    QCoreApplication::postEvent(this, new QEvent(DeliverEvent));
  }
}

void pqHeldInput::customEvent(QEvent* event)
{
  if (event->type() != DeliverEvent)
  {
    this->QObject::customEvent(event);
    return;
  }
  this->DeliveryPosted = false;
  this->deliverNext();
}

void pqHeldInput::deliverNext()
{
  if (this->Processing || this->Queue.empty())
  {
    return; // inside an update: its end delivers
  }
  std::unique_ptr<Held> held = std::move(this->Queue.front());
  this->Queue.pop_front();
  ++this->Delivering;
  if (QWindow* window = held->window)
  {
    const QEvent::Type type = held->event->type();
    if (type == QEvent::KeyPress || type == QEvent::KeyRelease)
    {
      // through Qt's key entry: the shortcut map and the focus widget see it as they would have
      const auto* key = static_cast<const QKeyEvent*>(held->event.get());
      qt_handleKeyEvent(window, type, key->key(), key->modifiers(), key->text(), key->isAutoRepeat(), key->count());
    }
    else
    {
      QCoreApplication::sendEvent(window, held->event.get());
    }
  }
  --this->Delivering;
  // the next one on the next pass of the event loop, as the window system's input comes
  this->deliverLater();
  this->updateFilter();
}
