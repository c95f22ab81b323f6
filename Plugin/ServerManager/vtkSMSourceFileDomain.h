/**
 * @class vtkSMSourceFileDomain
 * @brief A writer input's domain: only data read from a solver's file by one of the listed readers.
 *
 * The Mesh File Variant writer applies to a deformation of what a solver's mesh file gave (the
 * Mesh File reader, or ParaView's CGNS, IOSS or Exodus II reader up the pipeline), and to nothing
 * else: for other data ParaView's own writers of the same extensions are offered and chosen.
 *
 *   <SourceFileDomain name="source_file">
 *     <Proxy group="sources" name="MeshFileReader" />
 *     <Proxy group="sources" name="CGNSSeriesReader" />
 *   </SourceFileDomain>
 *
 * The readers are looked for along each input's first inputs (property Input), as the writer
 * looks for its source file (Readers/VariantInput.h). With the plugin's setting
 * SaveDataWritesVariants off (Edit > Settings > MLS Deform) no input is in the domain, and Save
 * Data writes with ParaView's own writers.
 */
#ifndef vtkSMSourceFileDomain_h
#define vtkSMSourceFileDomain_h

#include "MLSDeformServerManagerModule.h"
#include "vtkSMProducerDomain.h"

class MLSDEFORMSERVERMANAGER_EXPORT vtkSMSourceFileDomain : public vtkSMProducerDomain
{
public:
  static vtkSMSourceFileDomain* New();
  vtkTypeMacro(vtkSMSourceFileDomain, vtkSMProducerDomain);

  /// IN_DOMAIN when every input of the property (its unchecked values) has one of the listed
  /// readers up its pipeline.
  int IsInDomain(vtkSMProperty* property) override;

protected:
  vtkSMSourceFileDomain();
  ~vtkSMSourceFileDomain() override;

private:
  vtkSMSourceFileDomain(const vtkSMSourceFileDomain&) = delete;
  void operator=(const vtkSMSourceFileDomain&) = delete;
};

#endif
