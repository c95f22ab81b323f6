// The deformation's output: the input's structure with every point moved by d(x) and a
// Displacement array, written into the arrays of the previous update when no one else holds them
// (a new handle motion allocates nothing of the mesh's size).
#pragma once

#include "Common/CoreTypes.h"

#include <vtkSmartPointer.h>

#include <functional>
#include <vector>

class vtkDataArray;
class vtkDataObject;
class vtkDoubleArray;
class vtkPoints;
class vtkPointSet;

namespace mlsvtk
{
/// The output starts as the unchanged input: shallow copies in new leaf objects, so that setting
/// new points on them never touches the input.
void copyInput(vtkDataObject* input, vtkDataObject* output);

class DeformedOutput
{
public:
  /// The displacement d at the points [offset, offset + n) into out (3 per point).
  using DisplacementField = std::function<void(long offset, long n, double* out)>;

  /// Writes x + d(x) and d into the output point sets (outSets[s] matching inSets[s]; points
  /// concatenated over the sets). A set with moving[s] == 0 gets the points and d of the previous
  /// write instead (a drag's surface-only update), or is written when it has none of its size.
  void write(const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets, const mlsdeform::PointList& points,
    const DisplacementField& d, const std::vector<char>& moving);

  /// The previous write's points and d into the output point sets again (a cancelled update);
  /// returns false, leaving the sets as they are, when it does not fit the sets (other inputs).
  bool restore(const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets);

  /// Arrays written with set s's points (the design sensitivities dX/dp), given to the set with
  /// its points whenever the previous write is kept or restored (a drag's surface-only update, a
  /// cancel), so that a view coloured by them keeps them. A new write of the set drops them.
  void addDerived(std::size_t s, vtkDataArray* array);

private:
  /// Whether set s's previous write fits the input set (its number of points and precision).
  bool fits(std::size_t s, vtkPointSet* in) const;
  /// Set s's previous write into the output set.
  void keep(std::size_t s, vtkPointSet* out) const;

  std::vector<vtkSmartPointer<vtkPoints>> Moved;
  std::vector<vtkSmartPointer<vtkDoubleArray>> Displacement;
  std::vector<std::vector<vtkSmartPointer<vtkDataArray>>> Derived;
};
} // namespace mlsvtk
