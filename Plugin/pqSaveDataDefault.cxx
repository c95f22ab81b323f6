#include "pqSaveDataDefault.h"

#include "pqActiveObjects.h"
#include "pqApplicationCore.h"
#include "pqOutputPort.h"
#include "pqPipelineSource.h"
#include "pqSettings.h"
#include "vtkPVDataInformation.h"
#include "vtkSMInputProperty.h"
#include "vtkSMProxyManager.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMSourceProxy.h"

namespace
{
// The writer (MLSDeform.xml) and a text of its file type that no other type holds: the Save Data
// dialog preselects the first type that contains the remembered extension.
constexpr const char* VariantWriter = "AMeshVariantWriter";
constexpr const char* Marker = "variant of the source mesh file";

QString extensionKey(vtkPVDataInformation* information)
{
  const int type =
    information->GetCompositeDataSetType() == -1 ? information->GetDataSetType() : information->GetCompositeDataSetType();
  return QString("extensions/SaveDataExtension/%1").arg(type); // pqSaveDataReaction's setting
}
}

pqSaveDataDefault::pqSaveDataDefault(QObject* parent)
  : QObject(parent)
{
}

void pqSaveDataDefault::onStartup()
{
  connect(&pqActiveObjects::instance(), &pqActiveObjects::portChanged, this, &pqSaveDataDefault::portChanged);
  // applied data changes its type and source: look again once it updated
  connect(&pqActiveObjects::instance(), &pqActiveObjects::dataUpdated, this,
    [this] { this->portChanged(pqActiveObjects::instance().activePort()); });
}

bool pqSaveDataDefault::fromSourceFile(pqOutputPort* port)
{
  vtkSMSessionProxyManager* proxies = vtkSMProxyManager::GetProxyManager()->GetActiveSessionProxyManager();
  vtkSMProxy* writer = proxies ? proxies->GetPrototypeProxy("writers", VariantWriter) : nullptr;
  auto* input = writer ? vtkSMInputProperty::SafeDownCast(writer->GetProperty("Input")) : nullptr;
  auto* source = port ? vtkSMSourceProxy::SafeDownCast(port->getSource()->getProxy()) : nullptr;
  if (!input || !source)
  {
    return false;
  }
  // as vtkSMWriterFactory::CanWrite asks it
  input->RemoveAllUncheckedProxies();
  input->AddUncheckedInputConnection(source, port->getPortNumber());
  const bool accepted = input->IsInDomains() != 0;
  input->RemoveAllUncheckedProxies();
  return accepted;
}

void pqSaveDataDefault::portChanged(pqOutputPort* port)
{
  vtkPVDataInformation* information = port ? port->getDataInformation() : nullptr;
  if (!information || information->GetDataSetType() == -1)
  {
    return; // not yet applied
  }
  pqSettings* settings = pqApplicationCore::instance()->settings();
  const QString key = extensionKey(information);
  const QString kept = "MLSDeform/SaveDataExtensionOfUser/" + key.section('/', -1);
  const bool marked = settings->value(key).toString() == Marker;
  if (fromSourceFile(port))
  {
    if (!marked)
    {
      settings->setValue(kept, settings->value(key)); // the user's own (or none)
      settings->setValue(key, Marker);
    }
  }
  else if (marked)
  {
    const QVariant own = settings->value(kept);
    if (own.isValid() && !own.isNull() && !own.toString().isEmpty())
    {
      settings->setValue(key, own);
    }
    else
    {
      settings->remove(key);
    }
    settings->remove(kept);
  }
}
