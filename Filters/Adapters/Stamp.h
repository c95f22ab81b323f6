// Versions of VTK data by VTK's own change tracking (objects and their modification times): what
// the deformation's cache compares to know whether an input changed.
#pragma once

#include <vtkType.h>
#include <utility>
#include <vector>

class vtkObject;
class vtkPointSet;

namespace mlsvtk
{
/// Identifies versions of VTK data by VTK's own change tracking: the objects and their
/// modification times. A modification gives an object a newer MTime than any before it, and a
/// new object starts newer than all existing ones, so equal stamps mean unmodified data.
struct Stamp
{
  std::vector<std::pair<const void*, vtkMTimeType>> objects;
  void add(vtkObject* object);
  bool operator==(const Stamp& other) const { return objects == other.objects; }
  bool operator!=(const Stamp& other) const { return !(*this == other); }
};

/// The stamp of the point coordinates of the sets.
Stamp pointsStamp(const std::vector<vtkPointSet*>& sets);

/// The stamp of the cells (connectivity and types) of the sets.
Stamp cellsStamp(const std::vector<vtkPointSet*>& sets);
} // namespace mlsvtk
