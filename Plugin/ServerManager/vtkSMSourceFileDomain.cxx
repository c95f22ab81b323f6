#include "vtkSMSourceFileDomain.h"

#include "vtkObjectFactory.h"
#include "vtkSMInputProperty.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMProxy.h"
#include "vtkSMProxyManager.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMUncheckedPropertyHelper.h"

vtkStandardNewMacro(vtkSMSourceFileDomain);

vtkSMSourceFileDomain::vtkSMSourceFileDomain() = default;
vtkSMSourceFileDomain::~vtkSMSourceFileDomain() = default;

int vtkSMSourceFileDomain::IsInDomain(vtkSMProperty* property)
{
  if (this->IsOptional)
  {
    return vtkSMDomain::IN_DOMAIN;
  }
  if (!property)
  {
    return vtkSMDomain::NOT_IN_DOMAIN;
  }
  // the plugin's setting (MLSDeform.xml: MLSDeformSettings), on unless the user turned it off
  vtkSMSessionProxyManager* proxies = vtkSMProxyManager::GetProxyManager()->GetActiveSessionProxyManager();
  vtkSMProxy* settings = proxies ? proxies->GetProxy("settings", "MLSDeformSettings") : nullptr;
  if (settings && settings->GetProperty("SaveDataWritesVariants") &&
    vtkSMPropertyHelper(settings, "SaveDataWritesVariants").GetAsInt() == 0)
  {
    return vtkSMDomain::NOT_IN_DOMAIN;
  }
  vtkSMUncheckedPropertyHelper inputs(property);
  if (inputs.GetNumberOfElements() == 0)
  {
    return vtkSMDomain::NOT_IN_DOMAIN;
  }
  for (unsigned int i = 0; i < inputs.GetNumberOfElements(); ++i)
  {
    vtkSMProxy* proxy = inputs.GetAsProxy(i);
    // up the pipeline along each proxy's first input; a pipeline is a DAG, so this ends
    while (proxy && !this->IsListed(proxy))
    {
      auto* input = vtkSMInputProperty::SafeDownCast(proxy->GetProperty("Input"));
      proxy = input && input->GetNumberOfProxies() > 0 ? input->GetProxy(0) : nullptr;
    }
    if (!proxy)
    {
      return vtkSMDomain::NOT_IN_DOMAIN;
    }
  }
  return vtkSMDomain::IN_DOMAIN;
}
