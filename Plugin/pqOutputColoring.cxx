#include "pqOutputColoring.h"

#include "Common/CoreTypes.h"
#include "Vocabulary/RegionRoles.h"

#include <pqApplicationCore.h>
#include <pqRepresentation.h>
#include <pqServerManagerModel.h>
#include <vtkDataObject.h>
#include <vtkSMPVRepresentationProxy.h>
#include <vtkSMPropertyHelper.h>
#include <vtkSMSessionProxyManager.h>
#include <vtkSMSourceProxy.h>

#include <cstring>

pqOutputColoring::pqOutputColoring(QObject* parent)
  : QObject(parent)
{
}

void pqOutputColoring::onStartup()
{
  QObject::connect(pqApplicationCore::instance()->getServerManagerModel(), &pqServerManagerModel::representationAdded, this,
    &pqOutputColoring::representationAdded);
}

void pqOutputColoring::representationAdded(pqRepresentation* representation)
{
  vtkSMProxy* proxy = representation ? representation->getProxy() : nullptr;
  // not while a state file is loaded (it has its own colours), only geometry representations
  if (!proxy || proxy->GetSessionProxyManager()->GetInLoadXMLState() || pqApplicationCore::instance()->isLoadingState() ||
    !proxy->GetProperty("Input") || !proxy->GetProperty("DiffuseColor") || !proxy->GetProperty("PointSize"))
  {
    return;
  }
  auto* producer = vtkSMSourceProxy::SafeDownCast(vtkSMPropertyHelper(proxy, "Input").GetAsProxy());
  const char* name = producer ? producer->GetXMLName() : "";
  if (std::strcmp(name, "MLSDeform") == 0 || std::strcmp(name, "ShellDeform") == 0)
  {
    vtkSMPVRepresentationProxy::SetScalarColoring(proxy, "Displacement", vtkDataObject::POINT); // by magnitude
    proxy->UpdateVTKObjects();
    return;
  }
  if (std::strcmp(name, "ConstraintRegion") != 0)
  {
    return;
  }
  // the role's colour from the table of roles; a value it does not know keeps ParaView's defaults
  const double* colour = nullptr;
  try
  {
    colour = mlsvtk::regionRole(vtkSMPropertyHelper(producer, "Role").GetAsInt()).colour.data();
  }
  catch (const mlsdeform::InvalidInputException&)
  {
    return;
  }
  vtkSMPVRepresentationProxy::SetScalarColoring(proxy, nullptr, vtkDataObject::POINT);
  vtkSMPropertyHelper(proxy, "DiffuseColor").Set(colour, 3);
  vtkSMPropertyHelper(proxy, "AmbientColor").Set(colour, 3);
  vtkSMPropertyHelper(proxy, "PointSize").Set(8.0);
  vtkSMPropertyHelper(proxy, "RenderPointsAsSpheres", /*quiet=*/true).Set(1);
  vtkSMRepresentationProxy::SetRepresentationType(proxy, "Points");
  proxy->UpdateVTKObjects();
}
