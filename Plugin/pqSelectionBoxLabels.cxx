#include "pqSelectionBoxLabels.h"

#include <QCheckBox>
#include <QEvent>
#include <QTimer>

#include <cstring>

namespace
{
// ParaView's words and the panel's.
struct Label
{
  const char* paraview;
  const char* shown;
};
const Label CheckBoxes[] = { { "Show Box", "Show Selection Box" }, { "Translation", "Move Box" }, { "Rotation", "Rotate Box" },
  { "Scaling", "Scale Box" }, { "Face Movement", "Move Box Faces" } };

bool isA(QObject* object, const char* className)
{
  return std::strcmp(object->metaObject()->className(), className) == 0;
}
}

pqSelectionBoxLabels::pqSelectionBoxLabels(QWidget* panel)
  : QObject(panel)
  , Panel(panel)
{
  QTimer::singleShot(0, this, &pqSelectionBoxLabels::relabel); // once the panel's widgets are all made
}

bool pqSelectionBoxLabels::eventFilter(QObject* watched, QEvent* event)
{
  if (event->type() == QEvent::ChildAdded)
  {
    QTimer::singleShot(0, this, &pqSelectionBoxLabels::relabel); // a Region's widget made anew
  }
  return this->QObject::eventFilter(watched, event);
}

void pqSelectionBoxLabels::relabel()
{
  if (!this->Panel)
  {
    return;
  }
  for (QWidget* widget : this->Panel->findChildren<QWidget*>())
  {
    if (isA(widget, "pqProxySelectionWidget"))
    {
      widget->removeEventFilter(this); // (installed once)
      widget->installEventFilter(this);
    }
    if (!isA(widget, "pqBoxPropertyWidget"))
    {
      continue;
    }
    for (QCheckBox* box : widget->findChildren<QCheckBox*>())
    {
      for (const Label& label : CheckBoxes)
      {
        if (box->text() == label.paraview)
        {
          box->setText(label.shown);
        }
      }
    }
  }
}
