#include "vtkSMProducerDomain.h"

#include "vtkObjectFactory.h"
#include "vtkPVXMLElement.h"
#include "vtkSMProxy.h"
#include "vtkSMUncheckedPropertyHelper.h"

#include <algorithm>
#include <cstring>

vtkStandardNewMacro(vtkSMProducerDomain);

vtkSMProducerDomain::vtkSMProducerDomain() = default;
vtkSMProducerDomain::~vtkSMProducerDomain() = default;

int vtkSMProducerDomain::ReadXMLAttributes(vtkSMProperty* property, vtkPVXMLElement* element)
{
  if (!this->Superclass::ReadXMLAttributes(property, element))
  {
    return 0;
  }
  this->Producers.clear();
  for (unsigned int i = 0; i < element->GetNumberOfNestedElements(); ++i)
  {
    vtkPVXMLElement* proxy = element->GetNestedElement(i);
    if (std::strcmp(proxy->GetName(), "Proxy") == 0 && proxy->GetAttribute("group") && proxy->GetAttribute("name"))
    {
      this->Producers.emplace_back(proxy->GetAttribute("group"), proxy->GetAttribute("name"));
    }
  }
  return 1;
}

int vtkSMProducerDomain::IsInDomain(vtkSMProperty* property)
{
  if (this->IsOptional)
  {
    return vtkSMDomain::IN_DOMAIN;
  }
  if (!property)
  {
    return vtkSMDomain::NOT_IN_DOMAIN;
  }
  vtkSMUncheckedPropertyHelper inputs(property);
  for (unsigned int i = 0; i < inputs.GetNumberOfElements(); ++i)
  {
    if (!this->IsListed(inputs.GetAsProxy(i)))
    {
      return vtkSMDomain::NOT_IN_DOMAIN;
    }
  }
  return vtkSMDomain::IN_DOMAIN;
}

bool vtkSMProducerDomain::IsListed(vtkSMProxy* proxy) const
{
  return proxy && proxy->GetXMLGroup() && proxy->GetXMLName() &&
    std::any_of(this->Producers.begin(), this->Producers.end(), [&](const std::pair<std::string, std::string>& p) {
      return p.first == proxy->GetXMLGroup() && p.second == proxy->GetXMLName();
    });
}

void vtkSMProducerDomain::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  for (const auto& producer : this->Producers)
  {
    os << indent << "Producer: " << producer.first << " " << producer.second << "\n";
  }
}
