// The design variables of a Handle region in the ParaView GUI: a table with one row per variable
// (Name, Kind, Axis X/Y/Z, Value, Lower, Upper) and Add/Remove buttons, for the Constraint
// Region's DesignVariables (8 strings per row: name, kind 0-2, axis, value, lower, upper).
// ParaView's default for that property is a table of 8 unlabelled text columns whose Add button
// appends an empty row (no kind choice, no usable default). Editing marks the panel changed
// (Apply); the table shows the property's rows, so Reset, Python and Load State show here.
#pragma once

#include <pqPropertyWidget.h>

#include <QStringList>
#include <QVariantList>

class QTableWidget;
class QTableWidgetItem;

class pqDesignVariablesWidget : public pqPropertyWidget
{
  Q_OBJECT
  Q_PROPERTY(QVariantList rows READ rows WRITE setRows)
  using Superclass = pqPropertyWidget;

public:
  pqDesignVariablesWidget(vtkSMProxy* proxy, vtkSMProperty* property, QWidget* parent = nullptr);

  /// The table as the property's elements: 8 strings per row.
  QVariantList rows() const;
  /// Shows the property's elements (8 per row); leaves the table as it is when they are its rows.
  void setRows(const QVariantList& values);

Q_SIGNALS:
  void rowsChanged();

private Q_SLOTS:
  /// Appends the default row: a name p<k> not in the table, Translate along z, value 0, bounds -1 1.
  void addRow();
  /// Removes the selected rows (the current row when none is selected).
  void removeRows();
  /// A typed cell: an empty name or a number that does not read as one is put back.
  void cellEdited(QTableWidgetItem* item);

private:
  /// Appends a row showing 8 elements of the property.
  void appendRow(const QStringList& values);
  /// The kind combo boxes named Kind<row> after rows moved, the table's height fitted to its rows.
  void rowsMoved();

  QTableWidget* Table;
};
