#include "pqOutputColoring.h"

#include <pqApplicationCore.h>
#include <pqRepresentation.h>
#include <pqServerManagerModel.h>
#include <vtkDataObject.h>
#include <vtkSMPVRepresentationProxy.h>
#include <vtkSMPropertyHelper.h>
#include <vtkSMSessionProxyManager.h>
#include <vtkSMSourceProxy.h>

#include <cstring>

namespace
{
// per Role of vtkConstraintRegion: Handle, Fixed, the constraints (Planarity .. FromPrimitive), Slip
const double Handle[3] = { 0.9, 0.1, 0.1 };
const double Fixed[3] = { 0.15, 0.35, 1.0 };
const double Constraint[3] = { 0.1, 0.75, 0.2 };
const double Slip[3] = { 1.0, 0.6, 0.0 };

const double* roleColour(int role)
{
  return role == 0 ? Handle : role == 1 ? Fixed : role == 8 ? Slip : Constraint;
}
}

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
  const double* colour = roleColour(vtkSMPropertyHelper(producer, "Role").GetAsInt());
  vtkSMPVRepresentationProxy::SetScalarColoring(proxy, nullptr, vtkDataObject::POINT);
  vtkSMPropertyHelper(proxy, "DiffuseColor").Set(colour, 3);
  vtkSMPropertyHelper(proxy, "AmbientColor").Set(colour, 3);
  vtkSMPropertyHelper(proxy, "PointSize").Set(8.0);
  vtkSMPropertyHelper(proxy, "RenderPointsAsSpheres", /*quiet=*/true).Set(1);
  vtkSMRepresentationProxy::SetRepresentationType(proxy, "Points");
  proxy->UpdateVTKObjects();
}
