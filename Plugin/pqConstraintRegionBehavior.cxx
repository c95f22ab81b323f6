#include "pqConstraintRegionBehavior.h"

#include "Common/CoreTypes.h"
#include "Vocabulary/RegionRoles.h"
#include "vtkConstraintRegion.h"

#include <pqApplicationCore.h>
#include <pqCoreUtilities.h>
#include <pqObjectBuilder.h>
#include <pqOutputPort.h>
#include <pqPipelineFilter.h>
#include <pqPropertiesPanel.h>
#include <pqServerManagerModel.h>
#include <vtkDataObject.h>
#include <vtkPVArrayInformation.h>
#include <vtkPVDataInformation.h>
#include <vtkPVDataSetAttributesInformation.h>
#include <vtkSMPropertyHelper.h>
#include <vtkSMProxy.h>

#include <QMetaObject>
#include <QRegularExpression>
#include <QStringList>

#include <cstring>

namespace
{
// The names shown in full before "+N more".
constexpr int NamesShown = 3;

bool isRegion(pqPipelineSource* source)
{
  return source && source->getProxy() && std::strcmp(source->getProxy()->GetXMLName(), "ConstraintRegion") == 0;
}

// Whether the data has a mesh file's sets (arrays the Mesh File reader marks NAMED_SET).
bool hasNamedSets(vtkPVDataInformation* information)
{
  for (int association : { vtkDataObject::POINT, vtkDataObject::CELL })
  {
    vtkPVDataSetAttributesInformation* arrays = information->GetAttributeInformation(association);
    for (int i = 0; arrays && i < arrays->GetNumberOfArrays(); ++i)
    {
      if (arrays->GetArrayInformation(i)->HasInformationKey("vtkMeshFileReader", "NAMED_SET"))
      {
        return true;
      }
    }
  }
  return false;
}
}

pqConstraintRegionBehavior::pqConstraintRegionBehavior(QObject* parent)
  : QObject(parent)
{
}

void pqConstraintRegionBehavior::onStartup()
{
  pqApplicationCore* core = pqApplicationCore::instance();
  QObject::connect(core->getObjectBuilder(), &pqObjectBuilder::filterCreated, this, &pqConstraintRegionBehavior::filterCreated);
  pqServerManagerModel* model = core->getServerManagerModel();
  QObject::connect(model, &pqServerManagerModel::sourceAdded, this, &pqConstraintRegionBehavior::sourceAdded);
  QObject::connect(model, &pqServerManagerModel::preSourceRemoved, this, &pqConstraintRegionBehavior::sourceRemoved);
  for (pqPipelineSource* source : model->findItems<pqPipelineSource*>())
  {
    this->sourceAdded(source);
  }
}

void pqConstraintRegionBehavior::filterCreated(pqPipelineSource* source)
{
  // made from the Filters menu (a script's regions keep the defaults it knows): on a composite
  // input, the blocks' checklist from the start; on a mesh file's, the sets' list
  auto* filter = qobject_cast<pqPipelineFilter*>(source);
  pqOutputPort* input = filter ? filter->getAnyInput() : nullptr;
  vtkPVDataInformation* information = input ? input->getDataInformation() : nullptr;
  if (isRegion(source) && information && (information->IsCompositeDataSet() || hasNamedSets(information)))
  {
    vtkSMPropertyHelper(source->getProxy(), "SelectionMode").Set(vtkConstraintRegion::Blocks);
    source->getProxy()->UpdateVTKObjects();
  }
  // named by its role from the start (the pipeline browser, the panel's header, the undo
  // entries), not ConstraintRegion1 until its first Apply
  if (isRegion(source))
  {
    this->regionUpdated(source);
  }
}

void pqConstraintRegionBehavior::sourceAdded(pqPipelineSource* source)
{
  if (isRegion(source))
  {
    QObject::connect(source, QOverload<pqPipelineSource*>::of(&pqPipelineSource::dataUpdated), this,
      &pqConstraintRegionBehavior::regionUpdated, Qt::UniqueConnection);
  }
}

void pqConstraintRegionBehavior::sourceRemoved(pqPipelineSource* source)
{
  this->Given.remove(source);
}

void pqConstraintRegionBehavior::regionUpdated(pqPipelineSource* region)
{
  if (!region)
  {
    return;
  }
  // the default name or the one given here last: the user's own name stays
  const QString current = region->getSMName();
  static const QRegularExpression defaultName("^ConstraintRegion[0-9]+$");
  if (!defaultName.match(current).hasMatch() && this->Given.value(region) != current)
  {
    return;
  }
  const QString name = nameOf(region);
  if (!name.isEmpty() && name != current)
  {
    region->rename(name);
    // the Properties panel's header shows the name it had when the panel last updated (its
    // updatePanel is a private slot: called as a slot)
    for (pqPropertiesPanel* panel : pqCoreUtilities::mainWidget()->findChildren<pqPropertiesPanel*>())
    {
      QMetaObject::invokeMethod(panel, "updatePanel", Qt::QueuedConnection);
    }
  }
  this->Given[region] = name.isEmpty() ? current : name;
}

QString pqConstraintRegionBehavior::nameOf(pqPipelineSource* region)
{
  vtkSMProxy* proxy = region->getProxy();
  QString role;
  try
  {
    role = mlsvtk::regionRole(vtkSMPropertyHelper(proxy, "Role").GetAsInt()).name;
  }
  catch (const mlsdeform::InvalidInputException&)
  {
    return QString(); // a value the table does not know: no name from it
  }
  switch (vtkSMPropertyHelper(proxy, "SelectionMode").GetAsInt())
  {
    case vtkConstraintRegion::Blocks:
    {
      QStringList names;
      for (const char* property : { "Blocks", "Sets" })
      {
        vtkSMPropertyHelper entries(proxy, property);
        for (unsigned int i = 0; i < entries.GetNumberOfElements(); ++i)
        {
          // a hierarchy selector by its last block ("/Root/boundary/hull": hull)
          names << QString(entries.GetAsString(i)).section('/', -1);
        }
      }
      const int more = names.size() - NamesShown;
      if (names.isEmpty())
      {
        return role;
      }
      return QString("%1: %2%3").arg(role, names.mid(0, NamesShown).join(", "), more > 0 ? QString(" +%1").arg(more) : QString());
    }
    case vtkConstraintRegion::ImplicitFunction:
    {
      vtkSMProxy* function = vtkSMPropertyHelper(proxy, "Region").GetAsProxy();
      return function ? QString("%1 (%2)").arg(role, function->GetXMLLabel()) : role;
    }
    case vtkConstraintRegion::ArrayRange:
    {
      double range[2];
      vtkSMPropertyHelper(proxy, "Range").Get(range, 2);
      return QString("%1 (%2 %3 to %4)")
        .arg(role, vtkSMPropertyHelper(proxy, "SelectionArray").GetInputArrayNameToProcess())
        .arg(range[0])
        .arg(range[1]);
    }
    case vtkConstraintRegion::AllPoints:
      return QString("%1 (all points)").arg(role);
    case vtkConstraintRegion::Primitive:
      return QString("%1 (primitive %2)").arg(role).arg(vtkSMPropertyHelper(proxy, "PrimitiveId").GetAsInt());
    case vtkConstraintRegion::CellLayers:
      return QString("%1 (%2 cell layers)").arg(role).arg(vtkSMPropertyHelper(proxy, "NumberOfLayers").GetAsInt());
    default:
      return role;
  }
}
