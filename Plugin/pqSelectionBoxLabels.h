// The Constraint Region's selection box (ParaView's box widget, "InteractiveBox") in words that
// say what they move, apart from the handle motion's (issue 32, point 2): "Show Selection Box",
// and the interactivity check boxes "Move Box", "Rotate Box", "Scale Box", "Move Box Faces"
// (ParaView's "Rotation" check box beside its Rotation field was one word twice in the panel).
// Applied once the panel is built and again whenever the Region's widget is made anew (another
// implicit function chosen and back).
#pragma once

#include <QObject>
#include <QPointer>
#include <QWidget>

class pqSelectionBoxLabels : public QObject
{
  Q_OBJECT

public:
  /// Relabels the selection boxes in panel (a Constraint Region's panel), now and later; owned by it.
  explicit pqSelectionBoxLabels(QWidget* panel);

protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

private Q_SLOTS:
  void relabel();

private:
  QPointer<QWidget> Panel;
};
