#include "pqOutputColoring.h"

#include "Common/CoreTypes.h"
#include "Vocabulary/RegionRoles.h"

#include <pqApplicationCore.h>
#include <pqDataRepresentation.h>
#include <pqServerManagerModel.h>
#include <vtkDataObject.h>
#include <vtkPVArrayInformation.h>
#include <vtkPVDataInformation.h>
#include <vtkPVDataSetAttributesInformation.h>
#include <vtkSMPVRepresentationProxy.h>
#include <vtkSMTransferFunctionProxy.h>
#include <vtkSMPropertyHelper.h>
#include <vtkSMSessionProxyManager.h>
#include <vtkSMSourceProxy.h>

#include <cmath>
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
    if (auto* data = qobject_cast<pqDataRepresentation*>(representation))
    {
      QObject::connect(data, &pqDataRepresentation::dataUpdated, this, &pqOutputColoring::deformationUpdated);
    }
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

void pqOutputColoring::deformationUpdated()
{
  auto* representation = qobject_cast<pqDataRepresentation*>(sender());
  vtkSMProxy* proxy = representation ? representation->getProxy() : nullptr;
  vtkSMProxy* lut = proxy ? vtkSMPropertyHelper(proxy, "LookupTable", /*quiet=*/true).GetAsProxy() : nullptr;
  if (!lut || !vtkSMPVRepresentationProxy::GetUsingScalarColoring(proxy))
  {
    return;
  }
  // the current range, not the largest seen; force = false keeps a range the user locked
  if (!vtkSMPVRepresentationProxy::RescaleTransferFunctionToDataRange(proxy, /*extend=*/false, /*force=*/false))
  {
    return;
  }
  // a motion of zero: ParaView widens the empty range [0, 0] to [0, 1.2e-38], a legend that reads
  // as round-off; it reads 0 to 1% of the model's size instead, every point at its lowest colour
  vtkPVDataInformation* information = representation->getInputDataInformation();
  vtkPVArrayInformation* displacement =
    information ? information->GetPointDataInformation()->GetArrayInformation("Displacement") : nullptr;
  const char* colouredBy = vtkSMPropertyHelper(proxy, "ColorArrayName").GetInputArrayNameToProcess();
  if (!displacement || !colouredBy || std::strcmp(colouredBy, "Displacement") != 0)
  {
    return;
  }
  const double* range = displacement->GetComponentRange(-1);
  if (range[1] == 0)
  {
    const double* bounds = information->GetBounds();
    const double diagonal = std::sqrt(std::pow(bounds[1] - bounds[0], 2) + std::pow(bounds[3] - bounds[2], 2) + std::pow(bounds[5] - bounds[4], 2));
    const double top = diagonal > 0 ? 0.01 * diagonal : 1.0;
    vtkSMTransferFunctionProxy::RescaleTransferFunction(lut, 0.0, top);
    if (vtkSMProxy* opacity = vtkSMPropertyHelper(lut, "ScalarOpacityFunction", /*quiet=*/true).GetAsProxy())
    {
      vtkSMTransferFunctionProxy::RescaleTransferFunction(opacity, 0.0, top);
    }
  }
}
