#include "VariantInput.h"

#include <vtkAlgorithm.h>
#include <vtkAlgorithmOutput.h>
#include <vtkCGNSFileSeriesReader.h>
#include <vtkCGNSReader.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkExodusIIReader.h>
#include <vtkFieldData.h>
#include <vtkFileSeriesReader.h>
#include <vtkIOSSReader.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkMultiBlockDataSet.h>
#include <vtkPartitionedDataSet.h>
#include <vtkPartitionedDataSetCollection.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkStringArray.h>

#include <stdexcept>
#include <unordered_map>

namespace mlsformats
{
namespace
{
// A leaf of the input and the names of the blocks down to it ("base", "zone").
struct Leaf
{
  vtkPointSet* points;
  std::vector<std::string> path;
};

std::string blockName(vtkInformation* meta)
{
  return meta && meta->Has(vtkCompositeDataSet::NAME()) ? meta->Get(vtkCompositeDataSet::NAME()) : "";
}

void collectLeaves(vtkDataObject* data, std::vector<std::string>& path, std::vector<Leaf>& leaves)
{
  auto child = [&](vtkDataObject* block, const std::string& name) {
    path.push_back(name);
    collectLeaves(block, path, leaves);
    path.pop_back();
  };
  if (auto* multiblock = vtkMultiBlockDataSet::SafeDownCast(data))
  {
    for (unsigned b = 0; b < multiblock->GetNumberOfBlocks(); ++b)
    {
      child(multiblock->GetBlock(b), multiblock->HasMetaData(b) ? blockName(multiblock->GetMetaData(b)) : "");
    }
  }
  else if (auto* collection = vtkPartitionedDataSetCollection::SafeDownCast(data))
  {
    for (unsigned b = 0; b < collection->GetNumberOfPartitionedDataSets(); ++b)
    {
      child(collection->GetPartitionedDataSet(b), collection->HasMetaData(b) ? blockName(collection->GetMetaData(b)) : "");
    }
  }
  else if (auto* partitions = vtkPartitionedDataSet::SafeDownCast(data))
  {
    for (unsigned p = 0; p < partitions->GetNumberOfPartitions(); ++p)
    {
      child(partitions->GetPartitionAsDataObject(p), path.empty() ? "" : path.back());
    }
  }
  else if (auto* points = vtkPointSet::SafeDownCast(data))
  {
    if (points->GetNumberOfPoints() > 0)
    {
      leaves.push_back({ points, path });
    }
  }
}

std::string fieldSourceFile(vtkDataObject* data)
{
  vtkStringArray* named = data ? vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray("SourceFile")) : nullptr;
  return named && named->GetNumberOfValues() > 0 ? named->GetValue(0) : "";
}

// The file a reader of ParaView's read, if it is one of the formats' readers.
std::string readerFileName(vtkAlgorithm* algorithm)
{
  const char* name = nullptr;
  if (auto* cgns = vtkCGNSReader::SafeDownCast(algorithm))
  {
    name = cgns->GetFileName();
  }
  else if (auto* cgnsSeries = vtkCGNSFileSeriesReader::SafeDownCast(algorithm))
  {
    name = cgnsSeries->GetCurrentFileName();
  }
  else if (auto* ioss = vtkIOSSReader::SafeDownCast(algorithm))
  {
    name = ioss->GetNumberOfFileNames() > 0 ? ioss->GetFileName(0) : nullptr;
  }
  else if (auto* exodus = vtkExodusIIReader::SafeDownCast(algorithm))
  {
    name = exodus->GetFileName();
  }
  else if (auto* series = vtkFileSeriesReader::SafeDownCast(algorithm))
  {
    name = series->GetCurrentFileName();
  }
  return name ? name : "";
}

// The leaf's node ids: a reader's node id array, or its zone's (CGNS: the block of the zone's
// name in the block of its base's, or that block's "Internal" block when patches are read too).
// Empty for a block of a zone's boundary patches (its points are the zone's).
std::vector<std::int64_t> leafNodeIds(const Leaf& leaf, const SourceMesh& layout, const std::string& source)
{
  const vtkIdType count = leaf.points->GetNumberOfPoints();
  std::vector<std::int64_t> ids(count);
  for (const char* name : { "NodeId", "ids", "GlobalNodeId" })
  {
    vtkDataArray* array = leaf.points->GetPointData()->GetArray(name);
    if (array && array->GetNumberOfComponents() == 1)
    {
      vtkIdTypeArray* integers = vtkIdTypeArray::SafeDownCast(array);
      for (vtkIdType i = 0; i < count; ++i)
      {
        // as integers: a double holds ids only up to 2^53
        ids[i] = integers ? static_cast<std::int64_t>(integers->GetValue(i)) : static_cast<std::int64_t>(array->GetTuple1(i));
      }
      return ids;
    }
  }
  std::vector<std::string> path = leaf.path;
  for (std::size_t at = 0; at < path.size(); ++at)
  {
    if (path[at] == "Patches")
    {
      return {};
    }
  }
  if (!path.empty() && path.back() == "Internal")
  {
    path.pop_back();
  }
  const std::string zone = path.size() >= 2 ? path[path.size() - 2] + "/" + path.back() : "";
  for (const NodeRange& range : layout.zones)
  {
    if (range.name == zone && range.count == count)
    {
      for (vtkIdType i = 0; i < count; ++i)
      {
        ids[i] = range.firstId + i;
      }
      return ids;
    }
  }
  std::string name;
  for (const std::string& part : leaf.path)
  {
    name += "/" + part;
  }
  throw std::runtime_error((leaf.path.empty() ? std::string("the input") : "the input's block " + name) + " has no node ids (point data " +
    "NodeId, ids or GlobalNodeId)" + (layout.zones.empty() ? "" : " and is no zone of " + source + " with its node count") +
    ": it did not come from " + source);
}
} // namespace

std::string sourceFileOf(vtkAlgorithm* writer, vtkDataObject* input)
{
  std::vector<std::string> path;
  std::vector<Leaf> leaves;
  collectLeaves(input, path, leaves);
  std::string named = fieldSourceFile(input);
  if (named.empty() && !leaves.empty())
  {
    named = fieldSourceFile(leaves.front().points);
  }
  // up the pipeline along each algorithm's first input
  for (vtkAlgorithm* algorithm = writer; named.empty() && algorithm && algorithm->GetNumberOfInputPorts() > 0 &&
       algorithm->GetNumberOfInputConnections(0) > 0;)
  {
    algorithm = algorithm->GetInputConnection(0, 0)->GetProducer();
    named = readerFileName(algorithm);
  }
  return named;
}

void variantNodesOf(vtkDataObject* input, const SourceMesh& layout, const std::string& source, std::vector<std::int64_t>& ids,
  std::vector<double>& xyz)
{
  std::vector<std::string> path;
  std::vector<Leaf> leaves;
  collectLeaves(input, path, leaves);
  if (leaves.empty())
  {
    throw std::runtime_error("the input has no points");
  }
  ids.clear();
  xyz.clear();
  std::unordered_map<std::int64_t, std::size_t> seen; // with several leaves: each node's first position
  for (const Leaf& leaf : leaves)
  {
    const std::vector<std::int64_t> leafIds = leafNodeIds(leaf, layout, source);
    for (std::size_t i = 0; i < leafIds.size(); ++i)
    {
      double point[3];
      leaf.points->GetPoint(static_cast<vtkIdType>(i), point);
      if (leaves.size() > 1)
      {
        const auto found = seen.emplace(leafIds[i], ids.size());
        if (!found.second)
        {
          const double* first = xyz.data() + 3 * found.first->second;
          if (first[0] != point[0] || first[1] != point[1] || first[2] != point[2])
          {
            throw std::runtime_error("node " + std::to_string(leafIds[i]) + " is at two positions in the input's blocks");
          }
          continue;
        }
      }
      ids.push_back(leafIds[i]);
      xyz.insert(xyz.end(), point, point + 3);
    }
  }
}
} // namespace mlsformats
