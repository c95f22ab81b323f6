#include "pqCompositeInputDecorator.h"

#include <pqApplicationCore.h>
#include <pqOutputPort.h>
#include <pqPipelineSource.h>
#include <pqPropertyWidget.h>
#include <pqServerManagerModel.h>
#include <vtkPVDataInformation.h>
#include <vtkSMProxy.h>
#include <vtkSMUncheckedPropertyHelper.h>

pqCompositeInputDecorator::pqCompositeInputDecorator(vtkPVXMLElement* config, pqPropertyWidget* parent)
  : pqPropertyWidgetDecorator(config, parent)
{
}

bool pqCompositeInputDecorator::canShowWidget(bool showAdvanced) const
{
  vtkSMProxy* proxy = this->parentWidget()->proxy();
  vtkSMProperty* input = proxy ? proxy->GetProperty("Input") : nullptr;
  if (input)
  {
    vtkSMUncheckedPropertyHelper helper(input);
    auto* source = helper.GetNumberOfElements() > 0
      ? pqApplicationCore::instance()->getServerManagerModel()->findItem<pqPipelineSource*>(helper.GetAsProxy(0))
      : nullptr;
    pqOutputPort* port = source ? source->getOutputPort(static_cast<int>(helper.GetOutputPort(0))) : nullptr;
    vtkPVDataInformation* information = port ? port->getDataInformation() : nullptr;
    if (information && information->GetNumberOfPoints() > 0 && !information->IsCompositeDataSet())
    {
      return false; // a single dataset: no blocks to tick
    }
  }
  return this->pqPropertyWidgetDecorator::canShowWidget(showAdvanced);
}
