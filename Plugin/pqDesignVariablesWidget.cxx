#include "pqDesignVariablesWidget.h"

#include "Adapters/DesignVariables.h"

#include <QComboBox>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QPushButton>
#include <QScrollBar>
#include <QSet>
#include <QSignalBlocker>
#include <QTableWidget>

#include <iterator>
#include <QVBoxLayout>

#include <algorithm>
#include <cmath>
#include <functional>

namespace
{
// The property's 8 elements per row, in its order (Plugin/MLSDeform.xml, DesignVariables).
constexpr int Columns = 8;
constexpr int NameColumn = 0;
constexpr int KindColumn = 1;
const char* const Headers[Columns] = { "Name", "Kind", "Axis X", "Axis Y", "Axis Z", "Value", "Lower", "Upper" };
const char* const HeaderTips[Columns] = { "The variable's name: its sensitivity array is dX/d<name>.",
  "Translate, Rotate (about the pivot) or Scale (about the pivot) the handle, or Local: a local shape variable "
  "(its control points, set up by mlsdeform.DesignVariables.addLocalDV; axis 0 0 0).",
  "The axis vector's x: its direction times its coefficient (model units, degrees or change of the scale "
  "factor per unit of the variable).",
  "The axis vector's y.", "The axis vector's z.", "The variable's value; it adds to the typed motion (0: the motion as typed).",
  "The value's lower bound.", "The value's upper bound." };
// A new row: translate along z by the value, at 0 within [-1, 1].
const char* const NewRow[Columns - 1] = { "0", "0", "0", "1", "0", "-1", "1" };
// The table grows with its rows up to this many, then scrolls.
constexpr int MostRowsShown = 8;

// The last accepted text of a cell, put back when a typed one is not accepted.
constexpr int AcceptedRole = Qt::UserRole;

bool acceptable(int column, const QString& text)
{
  if (column == NameColumn)
  {
    return !text.isEmpty();
  }
  bool ok = false;
  const double value = text.toDouble(&ok); // the C locale, as the server reads the element
  return ok && std::isfinite(value);
}
}

pqDesignVariablesWidget::pqDesignVariablesWidget(vtkSMProxy* proxy, vtkSMProperty* property, QWidget* parent)
  : Superclass(proxy, parent)
  , Table(new QTableWidget(0, Columns, this))
{
  this->setShowLabel(false); // the group's heading names it; the table needs the panel's width
  this->Table->setObjectName("Table");
  this->Table->verticalHeader()->hide();
  this->Table->setSelectionBehavior(QAbstractItemView::SelectRows);
  this->Table->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOn); // its height is fitted with it
  for (int c = 0; c < Columns; ++c)
  {
    auto* header = new QTableWidgetItem(Headers[c]);
    header->setToolTip(HeaderTips[c]);
    this->Table->setHorizontalHeaderItem(c, header);
  }
  auto* add = new QPushButton("Add", this);
  add->setObjectName("Add");
  add->setToolTip("Add a design variable: a new name, Translate along z, value 0 within -1 to 1.");
  auto* remove = new QPushButton("Remove", this);
  remove->setObjectName("Remove");
  remove->setToolTip("Remove the selected design variables.");

  auto* buttons = new QHBoxLayout;
  buttons->addWidget(add);
  buttons->addWidget(remove);
  buttons->addStretch();
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->addWidget(this->Table);
  layout->addLayout(buttons);

  this->connect(add, SIGNAL(clicked()), SLOT(addRow()));
  this->connect(remove, SIGNAL(clicked()), SLOT(removeRows()));
  this->connect(this->Table, SIGNAL(itemChanged(QTableWidgetItem*)), SLOT(cellEdited(QTableWidgetItem*)));
  this->addPropertyLink(this, "rows", SIGNAL(rowsChanged()), property); // shows the property's rows
  this->rowsMoved();
}

QVariantList pqDesignVariablesWidget::rows() const
{
  QVariantList values;
  for (int row = 0; row < this->Table->rowCount(); ++row)
  {
    for (int c = 0; c < Columns; ++c)
    {
      if (c == KindColumn)
      {
        // -1 (none) for a kind the table could not show: the filter reports it
        values.append(QString::number(static_cast<QComboBox*>(this->Table->cellWidget(row, c))->currentIndex()));
      }
      else
      {
        values.append(this->Table->item(row, c)->text());
      }
    }
  }
  return values;
}

void pqDesignVariablesWidget::setRows(const QVariantList& values)
{
  if (values == this->rows())
  {
    return; // the rows being edited: keep the selection
  }
  this->Table->setRowCount(0);
  for (int first = 0; first + Columns <= values.size(); first += Columns)
  {
    QStringList row;
    for (int c = 0; c < Columns; ++c)
    {
      row.append(values[first + c].toString());
    }
    this->appendRow(row);
  }
  this->rowsMoved();
}

void pqDesignVariablesWidget::appendRow(const QStringList& values)
{
  const QSignalBlocker blocker(this->Table); // filled, not edited
  const int row = this->Table->rowCount();
  this->Table->insertRow(row);
  for (int c = 0; c < Columns; ++c)
  {
    if (c == KindColumn)
    {
      auto* kind = new QComboBox;
      for (const char* text : mlsvtk::DesignKindNames)
      {
        kind->addItem(text);
      }
      bool ok = false;
      const int value = values[c].toInt(&ok);
      kind->setCurrentIndex(ok && value >= 0 && value < static_cast<int>(std::size(mlsvtk::DesignKindNames)) ? value : -1);
      kind->setToolTip(HeaderTips[c]);
      this->connect(kind, SIGNAL(currentIndexChanged(int)), SIGNAL(rowsChanged()));
      this->Table->setCellWidget(row, c, kind);
    }
    else
    {
      auto* item = new QTableWidgetItem(values[c]);
      item->setData(AcceptedRole, values[c]);
      this->Table->setItem(row, c, item);
    }
  }
}

void pqDesignVariablesWidget::rowsMoved()
{
  for (int row = 0; row < this->Table->rowCount(); ++row)
  {
    this->Table->cellWidget(row, KindColumn)->setObjectName(QString("Kind%1").arg(row)); // for recorded tests
  }
  this->Table->resizeColumnsToContents();
  if (this->Table->rowCount() > 0)
  {
    const int comboWidth = this->Table->cellWidget(0, KindColumn)->sizeHint().width();
    this->Table->setColumnWidth(KindColumn, std::max(this->Table->columnWidth(KindColumn), comboWidth));
  }
  const int shown = std::max(1, std::min(this->Table->rowCount(), MostRowsShown));
  this->Table->setFixedHeight(2 * this->Table->frameWidth() + this->Table->horizontalHeader()->sizeHint().height() +
    shown * this->Table->verticalHeader()->defaultSectionSize() + this->Table->horizontalScrollBar()->sizeHint().height());
}

void pqDesignVariablesWidget::addRow()
{
  QSet<QString> names;
  for (int row = 0; row < this->Table->rowCount(); ++row)
  {
    names.insert(this->Table->item(row, NameColumn)->text());
  }
  int k = 1;
  while (names.contains(QString("p%1").arg(k)))
  {
    ++k;
  }
  QStringList row{ QString("p%1").arg(k) };
  for (const char* value : NewRow)
  {
    row.append(value);
  }
  this->appendRow(row);
  this->rowsMoved();
  this->Table->selectRow(this->Table->rowCount() - 1);
  Q_EMIT this->rowsChanged();
}

void pqDesignVariablesWidget::removeRows()
{
  QList<int> rows;
  for (const QModelIndex& index : this->Table->selectionModel()->selectedRows())
  {
    rows.append(index.row());
  }
  if (rows.isEmpty() && this->Table->currentRow() >= 0)
  {
    rows.append(this->Table->currentRow());
  }
  if (rows.isEmpty())
  {
    return;
  }
  std::sort(rows.begin(), rows.end(), std::greater<int>()); // the last first: the others keep their index
  for (int row : rows)
  {
    this->Table->removeRow(row);
  }
  this->rowsMoved();
  Q_EMIT this->rowsChanged();
}

void pqDesignVariablesWidget::cellEdited(QTableWidgetItem* item)
{
  const QString text = item->text().trimmed();
  const QSignalBlocker blocker(this->Table); // the corrections below are not edits
  if (!acceptable(item->column(), text))
  {
    item->setText(item->data(AcceptedRole).toString());
    return;
  }
  item->setText(text);
  item->setData(AcceptedRole, text);
  Q_EMIT this->rowsChanged();
}
