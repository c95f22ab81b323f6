// The key of the deformation's first stage: what its subspace (shape functions and energies)
// depends on besides the input's points and cells.
#pragma once

#include "Adapters/Stamp.h"

#include <vector>

namespace mlsvtk
{
/// What a deformation's subspace (shape functions and energies) depends on besides the input's
/// point coordinates and cells: property values, compared exactly, and the stamps of further
/// inputs (external samples); and whether it depends on the input's points and cells (internal
/// sampling, energies on the input's mesh). It is rebuilt when any of them changes.
struct SubspaceDependencies
{
  std::vector<double> settings;
  Stamp inputs;
  bool geometry = true;
  bool operator==(const SubspaceDependencies& other) const
  {
    return settings == other.settings && inputs == other.inputs && geometry == other.geometry;
  }
};

} // namespace mlsvtk
