// What a list of names selects in a dataset: a Constraint Region's SelectionMode Blocks, the
// vocabulary CFD and FEM users name regions in (a case's patches, a mesh's sets). Each entry is
//  - a selector of ParaView's block hierarchy, as Extract Block's checklist writes it
//    ("/Root/boundary/hull"): those blocks and the blocks under them;
//  - a block's name: that block and the blocks under it; or a pattern of whole names (an
//    ECMAScript regular expression, as OpenFOAM's "motorBike.*" matches): the blocks without
//    children so named, except an OpenFOAM case's internal mesh ("in.*" names the inlet, not the
//    internalMesh; OpenFOAM's patterns name patches). "patch/NAME": blocks only;
//  - a patch group of the OpenFOAM case the data came from (the inGroups of its boundary file,
//    "motorBikeGroup", "wall", or a pattern of group names; "group/NAME": groups only): the blocks
//    of its patches;
//  - a set: a point or cell array of integers (a mesh file's named set: 1 in the set, 0 outside),
//    selecting the points where it is not 0, or the points of the cells where it is not 0.
#pragma once

#include "Common/Collective.h"

#include <string>
#include <vector>

class vtkDataObject;
class vtkPointSet;

namespace mlsvtk
{
struct BlockSelection
{
  /// For each point set of pointSets(input), whether each of its points is selected.
  std::vector<std::vector<char>> points;
  /// For each point set, when it was selected whole (by a selector, a name or a group), its
  /// composite id (its flat index: the same on every process of a dataset split over processes);
  /// 0 when it was not (its points are selected by a set array, or none).
  std::vector<int> block;
  /// The names of the blocks selected whole, in the input's order (a patch's name).
  std::vector<std::string> names;
};

/// Whether an entry names a block (a patch) called name: the name itself or a pattern of whole
/// names, bare or after "patch/". The scripts that choose which patches a reader reads ask this too.
bool namesBlock(const std::string& entry, const std::string& name);

/// Whether an entry names a patch group called group: the group's name or a pattern of whole
/// names, bare or after "group/".
bool namesGroup(const std::string& entry, const std::string& group);

/// The selection of entries in input, whose point sets (pointSets(input)) are sets. Throws
/// InvalidInputException naming the entries that select nothing on any process (with the
/// names that can be selected), or a group when the case's boundary file cannot be read.
BlockSelection selectBlocks(vtkDataObject* input, const std::vector<vtkPointSet*>& sets, const std::vector<std::string>& entries,
  const mlsdeform::Collective& group);
} // namespace mlsvtk
