#include "pqOutputColoring.h"

#include "Common/CoreTypes.h"
#include "Vocabulary/FieldNames.h"
#include "Vocabulary/RegionRoles.h"

#include <pqApplicationCore.h>
#include <pqDataRepresentation.h>
#include <pqOutputPort.h>
#include <pqPipelineFilter.h>
#include <pqServer.h>
#include <pqServerManagerModel.h>
#include <vtkSMTransferFunctionManager.h>
#include <vtkCommand.h>
#include <vtkEventQtSlotConnect.h>
#include <vtkDataObject.h>
#include <vtkPVDataInformation.h>
#include <vtkSMPVRepresentationProxy.h>
#include <vtkSMTransferFunctionProxy.h>
#include <vtkSMPropertyHelper.h>
#include <vtkSMSessionProxyManager.h>
#include <vtkSMSourceProxy.h>
#include <vtkSmartPointer.h>

#include <QPointer>
#include <QTimer>

#include <algorithm>
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

pqOutputColoring::~pqOutputColoring() = default;

void pqOutputColoring::onStartup()
{
  QObject::connect(pqApplicationCore::instance()->getServerManagerModel(), &pqServerManagerModel::representationAdded, this,
    &pqOutputColoring::representationAdded);
  QObject::connect(pqApplicationCore::instance()->getServerManagerModel(), &pqServerManagerModel::serverAdded, this,
    &pqOutputColoring::drawingArraysUnlisted);
  for (pqServer* server : pqApplicationCore::instance()->getServerManagerModel()->findItems<pqServer*>())
  {
    this->drawingArraysUnlisted(server);
  }
}

void pqOutputColoring::drawingArraysUnlisted(pqServer* server)
{
  // ParaView's geometry filter marks the edges inside a quadratic element's subdivided faces in
  // the point array vtkEdgeFlags (vtkPVRecoverGeometryWireframe); the colouring menu listed it
  // among a deck's fields. A filter expression of the settings proxy (not of its VTK object
  // alone, which the Settings dialog would overwrite)
  vtkSMProxy* settings = server ? server->proxyManager()->GetProxy("settings", "RepresentedArrayListSettings") : nullptr;
  if (!settings)
  {
    return;
  }
  const char* const drawingArray = "^vtkEdgeFlags$";
  vtkSMPropertyHelper expressions(settings, "FilterExpressions");
  for (unsigned int i = 0; i < expressions.GetNumberOfElements(); ++i)
  {
    if (std::strcmp(expressions.GetAsString(i), drawingArray) == 0)
    {
      return;
    }
  }
  expressions.SetNumberOfElements(expressions.GetNumberOfElements() + 1);
  expressions.Set(expressions.GetNumberOfElements() - 1, drawingArray);
  settings->UpdateVTKObjects();
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
  // beads with a white highlight and a dark rim: told apart from a model coloured in the role's
  // own colour (the Handle's red on the red end of a displacement colour map)
  vtkSMPropertyHelper(proxy, "Ambient").Set(0.0);
  vtkSMPropertyHelper(proxy, "Diffuse").Set(1.0);
  vtkSMPropertyHelper(proxy, "Specular").Set(1.0);
  vtkSMPropertyHelper(proxy, "SpecularPower").Set(5.0); // a highlight a third of a bead across
  vtkSMRepresentationProxy::SetRepresentationType(proxy, "Points");
  proxy->UpdateVTKObjects();
  if (auto* data = qobject_cast<pqDataRepresentation*>(representation))
  {
    QObject::connect(data, &pqDataRepresentation::dataUpdated, this, &pqOutputColoring::controlPointsDrawn, Qt::UniqueConnection);
  }
}

void pqOutputColoring::controlPointsDrawn()
{
  auto* representation = qobject_cast<pqDataRepresentation*>(sender());
  vtkSMProxy* proxy = representation ? representation->getProxy() : nullptr;
  vtkPVDataInformation* information = representation ? representation->getInputDataInformation() : nullptr;
  if (!proxy || this->Arrows.contains(proxy) || !information ||
    !information->GetArrayInformation(mlsvtk::fields::ControlDirection, vtkDataObject::POINT) ||
    std::strcmp(vtkSMPropertyHelper(proxy, "Representation").GetAsString(), "Points") != 0)
  {
    return; // no control points, drawn already, or the user's own representation
  }
  this->Arrows.insert(proxy);
  QObject::connect(representation, &QObject::destroyed, this, [this, proxy]() { this->Arrows.remove(proxy); });
  // the arrows' length: a twentieth of the model the region selects from
  auto* region = vtkSMSourceProxy::SafeDownCast(vtkSMPropertyHelper(proxy, "Input").GetAsProxy());
  auto* model = region ? vtkSMSourceProxy::SafeDownCast(vtkSMPropertyHelper(region, "Input").GetAsProxy()) : nullptr;
  const double* b = (model ? model->GetDataInformation() : information)->GetBounds();
  const double diagonal = b[0] <= b[1] ? std::sqrt(std::pow(b[1] - b[0], 2) + std::pow(b[3] - b[2], 2) + std::pow(b[5] - b[4], 2)) : 0.0;
  // after the render that updated the data (a representation changed during it has no glyphs yet)
  QTimer::singleShot(0, this, [shown = QPointer<pqDataRepresentation>(representation), proxy = vtkSmartPointer<vtkSMProxy>(proxy), diagonal]() {
    vtkSMRepresentationProxy::SetRepresentationType(proxy, "3D Glyphs"); // arrows by default
    vtkSMPropertyHelper(proxy, "Orient").Set(1);
    vtkSMPropertyHelper(proxy, "OrientationMode").Set(0); // along the vectors
    vtkSMPropertyHelper(proxy, "SelectOrientationVectors").Set(mlsvtk::fields::ControlDirection);
    vtkSMPropertyHelper(proxy, "ScaleByArray").Set(0);
    vtkSMPropertyHelper(proxy, "Scaling").Set(1); // by ScaleFactor alone
    vtkSMPropertyHelper(proxy, "ScaleFactor").Set(diagonal > 0 && std::isfinite(diagonal) ? diagonal / 20 : 1.0);
    proxy->UpdateVTKObjects();
    if (shown)
    {
      shown->renderViewEventually();
    }
  });
}

void pqOutputColoring::legendFollows()
{
  auto* representation = qobject_cast<pqDataRepresentation*>(sender());
  vtkSMProxy* proxy = representation ? representation->getProxy() : nullptr;
  vtkSMProxy* lut = proxy ? vtkSMPropertyHelper(proxy, "LookupTable", /*quiet=*/true).GetAsProxy() : nullptr;
  std::set<pqPipelineSource*> seen;
  if (!lut || !vtkSMPVRepresentationProxy::GetUsingScalarColoring(proxy) || !showsDeformation(representation->getInput(), seen))
  {
    return; // not a deformation's data
  }
  if (!this->Followed.contains(lut))
  {
    this->Followed.insert(lut);
    this->Connections->Connect(lut, vtkCommand::PropertyModifiedEvent, this, SLOT(legendRescaled(vtkObject*, unsigned long, void*, void*)));
    this->Connections->Connect(lut, vtkCommand::DeleteEvent, this, SLOT(legendDeleted(vtkObject*)));
  }
  this->rescale(lut);
}

void pqOutputColoring::legendDeleted(vtkObject* legend)
{
  this->Followed.remove(static_cast<vtkSMProxy*>(legend));
}

void pqOutputColoring::legendRescaled(vtkObject* legend, unsigned long, void*, void* property)
{
  auto* lut = vtkSMProxy::SafeDownCast(legend);
  if (this->Rescaling || !lut || !property || std::strcmp(static_cast<const char*>(property), "RGBPoints") != 0)
  {
    return;
  }
  // ParaView widened an empty range (a zero field: [0, 1.2e-38]) after an action of its own
  vtkSMPropertyHelper points(lut, "RGBPoints");
  const unsigned int n = points.GetNumberOfElements();
  if (n >= 4 && points.GetAsDouble(n - 4) - points.GetAsDouble(0) < 1e-30)
  {
    this->rescale(lut);
  }
}

void pqOutputColoring::rescale(vtkSMProxy* lut)
{
  // the range of every shown representation coloured with this legend, not the largest seen;
  // not a range the user locked
  double range[2];
  if (vtkSMPropertyHelper(lut, "AutomaticRescaleRangeMode", /*quiet=*/true).GetAsInt() == vtkSMTransferFunctionManager::NEVER ||
    !vtkSMTransferFunctionProxy::ComputeDataRange(lut, range))
  {
    return;
  }
  if (range[0] == 0 && range[1] == 0)
  {
    // a zero field (no motion): ParaView widens the empty range [0, 0] to [0, 1.2e-38], a legend
    // that reads as round-off; it reads 0 to 1% of the shown models' size instead, all at its
    // lowest colour
    double diagonal = 0;
    for (unsigned int c = 0; c < lut->GetNumberOfConsumers(); ++c)
    {
      vtkSMProxy* consumer = lut->GetConsumerProxy(c) ? lut->GetConsumerProxy(c)->GetTrueParentProxy() : nullptr;
      auto* shown = pqApplicationCore::instance()->getServerManagerModel()->findItem<pqDataRepresentation*>(consumer);
      if (shown && shown->isVisible() && shown->getInputDataInformation())
      {
        const double* b = shown->getInputDataInformation()->GetBounds();
        if (b[0] <= b[1])
        {
          diagonal = std::max(diagonal, std::sqrt(std::pow(b[1] - b[0], 2) + std::pow(b[3] - b[2], 2) + std::pow(b[5] - b[4], 2)));
        }
      }
    }
    range[1] = diagonal > 0 && std::isfinite(diagonal) ? 0.01 * diagonal : 1.0;
  }
  this->Rescaling = true;
  vtkSMTransferFunctionProxy::RescaleTransferFunction(lut, range[0], range[1]);
  if (vtkSMProxy* opacity = vtkSMPropertyHelper(lut, "ScalarOpacityFunction", /*quiet=*/true).GetAsProxy())
  {
    vtkSMTransferFunctionProxy::RescaleTransferFunction(opacity, range[0], range[1]);
  }
  this->Rescaling = false;
}
