#include "Adapters/BlockSelection.h"

#include "Adapters/CasePath.h"
#include "Common/CoreTypes.h"
#include "Foam/PolyMeshFiles.h"

#include <vtkCellData.h>
#include <vtkCompositeDataIterator.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkDataAssembly.h>
#include <vtkDataAssemblyUtilities.h>
#include <vtkIdList.h>
#include <vtkInformation.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkSmartPointer.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <map>
#include <regex>
#include <set>

namespace mlsvtk
{
namespace
{
// The edit distance (Levenshtein) of a and b, letters compared without case.
std::size_t editDistance(const std::string& a, const std::string& b)
{
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
  {
    row[j] = j;
  }
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
    {
      const std::size_t above = row[j];
      const bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) == std::tolower(static_cast<unsigned char>(b[j - 1]));
      row[j] = std::min({ row[j] + 1, row[j - 1] + 1, diagonal + (same ? 0 : 1) });
      diagonal = above;
    }
  }
  return row[b.size()];
}

// The known name closest to a mistyped one: within a third of its length (at least 1 edit), else "".
std::string closestName(const std::string& name, const std::set<std::string>& known)
{
  std::string best;
  std::size_t bestDistance = std::max<std::size_t>(1, name.size() / 3) + 1;
  for (const std::string& candidate : known)
  {
    const std::size_t distance = editDistance(name, candidate);
    if (distance < bestDistance)
    {
      best = candidate;
      bestDistance = distance;
    }
  }
  return best;
}
} // namespace

namespace
{
// An entry's kind: its prefix ("patch/", "group/") restricts what it may name.
struct Entry
{
  std::string name;
  bool blocks = true, groups = true, sets = true;
};

Entry parse(const std::string& text)
{
  Entry e{ text };
  for (const char* prefix : { "patch/", "group/" })
  {
    if (text.rfind(prefix, 0) == 0)
    {
      e.name = text.substr(std::string(prefix).size());
      e.blocks = prefix[0] == 'p';
      e.groups = !e.blocks;
      e.sets = false;
    }
  }
  return e;
}

// A name, or a pattern that matches the whole name (an entry that is no valid pattern names only itself).
bool matches(const std::string& entry, const std::string& name)
{
  if (entry == name)
  {
    return true;
  }
  try
  {
    return std::regex_match(name, std::regex(entry, std::regex::ECMAScript));
  }
  catch (const std::regex_error&)
  {
    return false;
  }
}

// The patch groups of the OpenFOAM case the data came from: group -> its patches, and every
// patch of the case (read or not); none when the data came from no case (why, in reason).
std::map<std::string, std::set<std::string>> patchGroups(vtkDataObject* input, std::set<std::string>& casePatches, std::string& reason)
{
  std::map<std::string, std::set<std::string>> groups;
  const std::string casePath = casePathOf(input);
  if (casePath.empty())
  {
    reason = "the input was not read from an OpenFOAM case (no CasePath)";
    return groups;
  }
  std::string polyMesh = casePath + "/constant/polyMesh";
  if (!std::filesystem::exists(polyMesh) && std::filesystem::exists(casePath + "/processor0/constant/polyMesh"))
  {
    polyMesh = casePath + "/processor0/constant/polyMesh"; // a decomposed case: every processor has the patches
  }
  try
  {
    for (const mlsfoam::FoamPatch& patch : mlsfoam::readFoamBoundary(polyMesh))
    {
      casePatches.insert(patch.name);
      for (const std::string& g : patch.groups)
      {
        groups[g].insert(patch.name);
      }
    }
  }
  catch (const std::exception& e)
  {
    reason = e.what();
  }
  return groups;
}

bool integral(vtkDataArray* array)
{
  switch (array->GetDataType())
  {
    case VTK_CHAR:
    case VTK_SIGNED_CHAR:
    case VTK_UNSIGNED_CHAR:
    case VTK_SHORT:
    case VTK_UNSIGNED_SHORT:
    case VTK_INT:
    case VTK_UNSIGNED_INT:
    case VTK_LONG:
    case VTK_UNSIGNED_LONG:
    case VTK_LONG_LONG:
    case VTK_UNSIGNED_LONG_LONG:
    case VTK_ID_TYPE:
      return array->GetNumberOfComponents() == 1;
    default:
      return false;
  }
}

// The set array of that name among a set's point (or cell) arrays, if it is one.
vtkDataArray* setArray(vtkFieldData* arrays, const std::string& name)
{
  vtkDataArray* array = arrays->GetArray(name.c_str());
  return array && integral(array) ? array : nullptr;
}
}

bool namesBlock(const std::string& entry, const std::string& name)
{
  const Entry e = parse(entry);
  return e.blocks && matches(e.name, name);
}

bool namesGroup(const std::string& entry, const std::string& group)
{
  const Entry e = parse(entry);
  return e.groups && matches(e.name, group);
}

BlockSelection selectBlocks(vtkDataObject* input, const std::vector<vtkPointSet*>& sets, const std::vector<std::string>& entries,
  const mlsdeform::Collective& group)
{
  BlockSelection out;
  out.block.assign(sets.size(), 0);
  for (vtkPointSet* set : sets)
  {
    out.points.emplace_back(static_cast<std::size_t>(set->GetNumberOfPoints()), 0);
  }
  std::vector<char> matched(entries.size(), 0);
  std::set<std::string> known; // what can be named, for the error message
  std::string groupsUnread;    // why there are no patch groups, if there are none
  std::set<std::string> casePatches; // every patch of the OpenFOAM case, read or not

  // blocks: by their place in ParaView's hierarchy, their names, their patches' groups
  auto* composite = vtkCompositeDataSet::SafeDownCast(input);
  vtkNew<vtkDataAssembly> hierarchy;
  if (composite && vtkDataAssemblyUtilities::GenerateHierarchy(composite, hierarchy))
  {
    const std::map<std::string, std::set<std::string>> groups = patchGroups(input, casePatches, groupsUnread);
    const bool isCase = !casePathOf(input).empty();
    const std::vector<int> nodes = hierarchy->GetChildNodes(hierarchy->GetRootNode(), true);
    std::set<unsigned int> chosen;
    for (std::size_t e = 0; e < entries.size(); ++e)
    {
      std::vector<std::string> selectors;
      if (entries[e].rfind('/', 0) == 0)
      {
        selectors.push_back(entries[e]);
      }
      else
      {
        std::set<std::string> patches; // of the groups it names
        for (const auto& [name, members] : groups)
        {
          if (namesGroup(entries[e], name))
          {
            patches.insert(members.begin(), members.end());
          }
        }
        const Entry entry = parse(entries[e]);
        for (int node : nodes)
        {
          // a name names any block; a pattern only blocks without children, and of an OpenFOAM
          // case not its internal mesh (a top-level block): OpenFOAM's patterns name patches
          const std::string label = hierarchy->GetAttributeOrDefault(node, "label", hierarchy->GetNodeName(node));
          const bool patternable = hierarchy->GetNumberOfChildren(node) == 0 &&
            !(isCase && hierarchy->GetParent(node) == hierarchy->GetRootNode());
          if ((entry.blocks && entry.name == label) || (patternable && namesBlock(entries[e], label)) || patches.count(label))
          {
            selectors.push_back(hierarchy->GetNodePath(node));
          }
        }
      }
      for (unsigned int id : vtkDataAssemblyUtilities::GetSelectedCompositeIds(selectors, hierarchy, nullptr, true))
      {
        chosen.insert(id);
        matched[e] = 1;
      }
    }
    for (int node : nodes)
    {
      known.insert(hierarchy->GetAttributeOrDefault(node, "label", hierarchy->GetNodeName(node)));
    }
    for (const auto& named : groups)
    {
      known.insert("group/" + named.first);
    }
    // the leaves in pointSets' order, each whole when its composite id was chosen
    vtkSmartPointer<vtkCompositeDataIterator> it = vtkSmartPointer<vtkCompositeDataIterator>::Take(composite->NewIterator());
    std::size_t s = 0;
    for (it->InitTraversal(); !it->IsDoneWithTraversal() && s < sets.size(); it->GoToNextItem())
    {
      if (vtkPointSet::SafeDownCast(it->GetCurrentDataObject()) != sets[s])
      {
        continue; // not a point set: pointSets skipped it
      }
      if (chosen.count(it->GetCurrentFlatIndex()))
      {
        out.points[s].assign(out.points[s].size(), 1);
        out.block[s] = static_cast<int>(it->GetCurrentFlatIndex());
        vtkInformation* meta = it->HasCurrentMetaData() ? it->GetCurrentMetaData() : nullptr;
        out.names.push_back(meta && meta->Has(vtkCompositeDataSet::NAME()) ? meta->Get(vtkCompositeDataSet::NAME()) : "");
      }
      ++s;
    }
  }

  // sets: point or cell arrays of integers named by an entry
  vtkNew<vtkIdList> ids;
  for (std::size_t e = 0; e < entries.size(); ++e)
  {
    const Entry entry = parse(entries[e]);
    for (std::size_t s = 0; entry.sets && s < sets.size(); ++s)
    {
      vtkPointSet* set = sets[s];
      if (vtkDataArray* points = setArray(set->GetPointData(), entry.name))
      {
        matched[e] = 1;
        for (vtkIdType i = 0; i < set->GetNumberOfPoints(); ++i)
        {
          out.points[s][i] |= points->GetTuple1(i) != 0;
        }
      }
      if (vtkDataArray* cells = setArray(set->GetCellData(), entry.name))
      {
        matched[e] = 1;
        for (vtkIdType c = 0; c < set->GetNumberOfCells(); ++c)
        {
          if (cells->GetTuple1(c) != 0)
          {
            set->GetCellPoints(c, ids);
            for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
            {
              out.points[s][ids->GetId(k)] = 1;
            }
          }
        }
      }
    }
  }
  for (vtkPointSet* set : sets)
  {
    for (vtkFieldData* arrays : { static_cast<vtkFieldData*>(set->GetPointData()), static_cast<vtkFieldData*>(set->GetCellData()) })
    {
      for (int a = 0; a < arrays->GetNumberOfArrays(); ++a)
      {
        const char* name = arrays->GetArrayName(a);
        // the ids a mesh file's nodes and elements carry are no sets
        if (arrays->GetArray(a) && integral(arrays->GetArray(a)) && name && std::strcmp(name, "NodeId") != 0 &&
          std::strcmp(name, "ElementId") != 0)
        {
          known.insert(name);
        }
      }
    }
  }

  // an entry that names nothing on any process is a mistake the user is told of (with the name
  // it most likely means)
  std::string unmatched;
  for (std::size_t e = 0; e < entries.size(); ++e)
  {
    if (!group.any(matched[e] != 0))
    {
      const std::string meant = closestName(entries[e], known);
      const std::string why = casePatches.count(entries[e]) ? " (a patch of the case that the reader did not read: tick it in the "
                                                               "reader's Mesh Regions, or give it to mlsdeform's open_case)"
        : meant.empty()                                      ? ""
                                                             : " (did you mean '" + meant + "'?)";
      unmatched += (unmatched.empty() ? "'" : ", '") + entries[e] + "'" + why;
    }
  }
  if (!unmatched.empty())
  {
    std::string names;
    for (const std::string& name : known)
    {
      names += (names.empty() ? "" : ", ") + name;
    }
    throw mlsdeform::InvalidInputException("Blocks or Sets " + unmatched + " name no block, patch, patch group or set of the input (it has: " +
      (names.empty() ? std::string("none") : names) + (groupsUnread.empty() ? "" : "; no patch groups: " + groupsUnread) + ")");
  }
  return out;
}
} // namespace mlsvtk
