// The user's input that arrives while one of the plugin's algorithms processes events inside its
// update (pqSetUpCancel: the progress bar repaints and its stop button takes a click). The update
// must not be re-entered, so that input is held, never dropped: every mouse, key, wheel, tablet,
// touch and close event the window system gives a window is kept and, once the update is over,
// delivered to the same window in the order it came, before any input that came after it. A
// release straight after a drag's last move thus ends the drag after the move's update, and keys
// typed during an update reach their widget.
#pragma once

#include <QObject>
#include <QPoint>
#include <QPointer>

#include <deque>
#include <functional>
#include <memory>

class QEvent;
class QWindow;

class pqHeldInput : public QObject
{
  Q_OBJECT

public:
  explicit pqHeldInput(QObject* parent = nullptr);
  ~pqHeldInput() override;

  /// Inside an update: processes the pending events with the user's input held and timers left
  /// for their next interval; `pressed` learns of each mouse press held (at its global position),
  /// which is how the progress bar's stop button is clicked during an update.
  void processEvents(const std::function<void(const QPoint& global)>& pressed);
  /// After the update: the held input is delivered, one event per pass of the event loop, and
  /// input that comes meanwhile waits behind it.
  void deliverLater();

protected:
  bool eventFilter(QObject* object, QEvent* event) override;
  void customEvent(QEvent* event) override;

private:
  struct Held;
  void deliverNext();
  void updateFilter();

  std::deque<std::unique_ptr<Held>> Queue;
  std::function<void(const QPoint& global)> Pressed;
  bool Processing = false;  // inside processEvents
  int Delivering = 0;       // inside the delivery of a held event (a dialog it opens gets its input)
  bool Filtering = false;   // installed on the application
  bool DeliveryPosted = false;
};
