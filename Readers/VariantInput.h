// What a variant is written from: the source file a dataset came from and the source's node id of
// each of its points. The Mesh File reader records both (field data SourceFile, point data
// NodeId); ParaView's own readers of the formats we write do not, so the file is found up the
// pipeline (their FileName) and the node ids in what they do give: the Exodus readers' node ids
// (IOSS: "ids", Exodus II: "GlobalNodeId"), the CGNS reader's blocks named by base and zone.
#pragma once

#include "Common/SourceMesh.h"

#include <cstdint>
#include <string>
#include <vector>

class vtkAlgorithm;
class vtkDataObject;

namespace mlsformats
{
/// The file the input of writer (port 0) was read from: its field data SourceFile, else the
/// file of the first reader up the pipeline that is one of ParaView's readers of the formats
/// (CGNS, IOSS, Exodus II); "" if none.
std::string sourceFileOf(vtkAlgorithm* writer, vtkDataObject* input);

/// The input's points as node ids and xyz (3 a node), each node once: a dataset's or every
/// leaf's of a composite. A node in several blocks (the Exodus readers give each block its
/// nodes) must be at one position. Throws std::runtime_error saying what is missing.
void variantNodesOf(vtkDataObject* input, const SourceMesh& layout, const std::string& source, std::vector<std::int64_t>& ids,
  std::vector<double>& xyz);
} // namespace mlsformats
