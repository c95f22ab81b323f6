// The sampling properties MLS Sampler and MLS Deform (its internal sampling) share (section 4,
// Fig. 2): declared once here, in both classes' public sections, with their members; and the one
// copy into the core's SamplingParameters and into PrintSelf. Included by the filters' headers:
// VTK only.
#pragma once

#include <vtkIndent.h>
#include <vtkSetGet.h>

#include <cstdint>
#include <ostream>

// The properties' accessors and members (the members after "protected:"; the class continues
// public). Defaults: the core's SamplingParameters'.
#define mlsSamplingPropertiesMacro()                                                                                      \
  /** Integration points per MLS sample, N / k (default 4). */                                                           \
  vtkSetClampMacro(IntegrationPointRatio, double, 1.0, 100.0);                                                           \
  vtkGetMacro(IntegrationPointRatio, double);                                                                            \
  /** Lloyd relaxation steps (default 5). */                                                                             \
  vtkSetClampMacro(LloydIterations, int, 0, 1000);                                                                       \
  vtkGetMacro(LloydIterations, int);                                                                                     \
  /** Cover s: every sampled position lies in the supports of at least s samples (default 5). */                         \
  vtkSetClampMacro(Cover, double, 4.0, 100.0);                                                                           \
  vtkGetMacro(Cover, double);                                                                                            \
  /** Seed of the random dense sampling (default 0); the same seed gives the same samples. */                           \
  vtkSetClampMacro(RandomSeed, int, 0, VTK_INT_MAX);                                                                     \
  vtkGetMacro(RandomSeed, int);                                                                                          \
  /** Sample density follows the mesh's element density (default on); off: uniform. */                                  \
  vtkSetMacro(FollowMeshGrading, vtkTypeBool);                                                                           \
  vtkGetMacro(FollowMeshGrading, vtkTypeBool);                                                                           \
  vtkBooleanMacro(FollowMeshGrading, vtkTypeBool);                                                                       \
                                                                                                                         \
protected:                                                                                                               \
  double IntegrationPointRatio = 4.0;                                                                                    \
  int LloydIterations = 5;                                                                                               \
  double Cover = 5.0;                                                                                                    \
  int RandomSeed = 0;                                                                                                    \
  vtkTypeBool FollowMeshGrading = 1;                                                                                     \
                                                                                                                         \
public:

namespace mlsvtk
{
/// The shared sampling properties of filter (MLS Sampler or MLS Deform) into parameters (the
/// core's mlsdeform::SamplingParameters: a template, so that the filters' headers need no core).
template <class Filter, class SamplingParameters>
void copySamplingProperties(Filter* filter, SamplingParameters& parameters)
{
  parameters.integrationPointRatio = filter->GetIntegrationPointRatio();
  parameters.lloydIterations = filter->GetLloydIterations();
  parameters.cover = filter->GetCover();
  parameters.randomSeed = static_cast<std::uint64_t>(filter->GetRandomSeed());
  parameters.followMeshGrading = filter->GetFollowMeshGrading() != 0;
}

/// The shared sampling properties of filter, for PrintSelf.
template <class Filter>
void printSamplingProperties(Filter* filter, std::ostream& os, vtkIndent indent)
{
  os << indent << "IntegrationPointRatio: " << filter->GetIntegrationPointRatio() << "\n"
     << indent << "LloydIterations: " << filter->GetLloydIterations() << "\n"
     << indent << "Cover: " << filter->GetCover() << "\n"
     << indent << "RandomSeed: " << filter->GetRandomSeed() << "\n"
     << indent << "FollowMeshGrading: " << filter->GetFollowMeshGrading() << "\n";
}
} // namespace mlsvtk
