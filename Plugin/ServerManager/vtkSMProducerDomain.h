/**
 * @class vtkSMProducerDomain
 * @brief An input property's domain: only outputs of the listed proxies.
 *
 * MLS Deform's Regions take Constraint Region outputs only: ParaView's Change Input dialog and the
 * input dialog of the Filters menu offer no other source for them.
 *
 *   <ProducerDomain name="producer">
 *     <Proxy group="filters" name="ConstraintRegion" />
 *   </ProducerDomain>
 *
 * (ParaView creates a domain from its XML tag as vtkSM<tag>; the plugin's client-server wrapping
 * registers this class for that.)
 */
#ifndef vtkSMProducerDomain_h
#define vtkSMProducerDomain_h

#include "MLSDeformServerManagerModule.h"
#include "vtkSMDomain.h"

#include <string>  // for std::string
#include <utility> // for std::pair
#include <vector>  // for std::vector

class vtkSMProxy;

class MLSDEFORMSERVERMANAGER_EXPORT vtkSMProducerDomain : public vtkSMDomain
{
public:
  static vtkSMProducerDomain* New();
  vtkTypeMacro(vtkSMProducerDomain, vtkSMDomain);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// IN_DOMAIN when every input of the property (its unchecked values, which the dialogs try)
  /// comes from one of the listed proxies.
  int IsInDomain(vtkSMProperty* property) override;

protected:
  vtkSMProducerDomain();
  ~vtkSMProducerDomain() override;
  int ReadXMLAttributes(vtkSMProperty* property, vtkPVXMLElement* element) override;

  /// Whether proxy is one of the listed proxies.
  bool IsListed(vtkSMProxy* proxy) const;

private:
  vtkSMProducerDomain(const vtkSMProducerDomain&) = delete;
  void operator=(const vtkSMProducerDomain&) = delete;

  std::vector<std::pair<std::string, std::string>> Producers; // (group, name) of each listed proxy
};

#endif
