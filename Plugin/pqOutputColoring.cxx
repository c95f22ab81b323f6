#include "pqOutputColoring.h"

#include "Common/CoreTypes.h"
#include "Vocabulary/RegionRoles.h"

#include <pqApplicationCore.h>
#include <pqDataRepresentation.h>
#include <pqOutputPort.h>
#include <pqPipelineFilter.h>
#include <pqServerManagerModel.h>
#include <vtkSMTransferFunctionManager.h>
#include <vtkDataObject.h>
#include <vtkPVDataInformation.h>
#include <vtkSMPVRepresentationProxy.h>
#include <vtkSMTransferFunctionProxy.h>
#include <vtkSMPropertyHelper.h>
#include <vtkSMSessionProxyManager.h>
#include <vtkSMSourceProxy.h>

#include <cmath>
#include <cstring>
#include <set>

namespace
{
bool isDeformation(vtkSMProxy* proxy)
{
  const char* name = proxy ? proxy->GetXMLName() : "";
  return std::strcmp(name, "MLSDeform") == 0 || std::strcmp(name, "ShellDeform") == 0;
}

// Whether a deformation is this source or upstream of it.
bool showsDeformation(pqPipelineSource* source, std::set<pqPipelineSource*>& seen)
{
  if (!source || !seen.insert(source).second)
  {
    return false;
  }
  if (isDeformation(source->getProxy()))
  {
    return true;
  }
  if (auto* filter = qobject_cast<pqPipelineFilter*>(source))
  {
    for (pqOutputPort* port : filter->getInputs())
    {
      if (showsDeformation(port->getSource(), seen))
      {
        return true;
      }
    }
  }
  return false;
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
  // geometry representations only
  if (!proxy || !proxy->GetProperty("Input") || !proxy->GetProperty("DiffuseColor") || !proxy->GetProperty("PointSize"))
  {
    return;
  }
  if (auto* data = qobject_cast<pqDataRepresentation*>(representation))
  {
    QObject::connect(data, &pqDataRepresentation::dataUpdated, this, &pqOutputColoring::legendFollows, Qt::UniqueConnection);
  }
  // the default look: not while a state file is loaded (it has its own colours)
  if (proxy->GetSessionProxyManager()->GetInLoadXMLState() || pqApplicationCore::instance()->isLoadingState())
  {
    return;
  }
  auto* producer = vtkSMSourceProxy::SafeDownCast(vtkSMPropertyHelper(proxy, "Input").GetAsProxy());
  const char* name = producer ? producer->GetXMLName() : "";
  if (isDeformation(producer))
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

void pqOutputColoring::legendFollows()
{
  auto* representation = qobject_cast<pqDataRepresentation*>(sender());
  vtkSMProxy* proxy = representation ? representation->getProxy() : nullptr;
  vtkSMProxy* lut = proxy ? vtkSMPropertyHelper(proxy, "LookupTable", /*quiet=*/true).GetAsProxy() : nullptr;
  std::set<pqPipelineSource*> seen;
  if (!lut || !vtkSMPVRepresentationProxy::GetUsingScalarColoring(proxy) || !showsDeformation(representation->getInput(), seen) ||
    vtkSMPropertyHelper(lut, "AutomaticRescaleRangeMode", /*quiet=*/true).GetAsInt() == vtkSMTransferFunctionManager::NEVER)
  {
    return; // not a deformation's data, or the user locked the range
  }
  // the range of every shown representation coloured with this legend, not the largest seen
  double range[2];
  if (!vtkSMTransferFunctionProxy::ComputeDataRange(lut, range))
  {
    return;
  }
  if (range[0] == 0 && range[1] == 0)
  {
    // a zero field (no motion): ParaView widens the empty range [0, 0] to [0, 1.2e-38], a legend
    // that reads as round-off; it reads 0 to 1% of the model's size instead, all at its lowest colour
    const double* bounds = representation->getInputDataInformation()->GetBounds();
    const double diagonal = std::sqrt(std::pow(bounds[1] - bounds[0], 2) + std::pow(bounds[3] - bounds[2], 2) + std::pow(bounds[5] - bounds[4], 2));
    range[1] = diagonal > 0 && std::isfinite(diagonal) ? 0.01 * diagonal : 1.0;
  }
  vtkSMTransferFunctionProxy::RescaleTransferFunction(lut, range[0], range[1]);
  if (vtkSMProxy* opacity = vtkSMPropertyHelper(lut, "ScalarOpacityFunction", /*quiet=*/true).GetAsProxy())
  {
    vtkSMTransferFunctionProxy::RescaleTransferFunction(opacity, range[0], range[1]);
  }
}
