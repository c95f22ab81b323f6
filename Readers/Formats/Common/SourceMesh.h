// A mesh as a solver's file holds it: nodes by id, elements in blocks of one cell type, and the
// named sets (node sets and element sets) that its users name regions by. Every format reads into
// this; the VTK reader converts it to an unstructured grid.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace mlsformats
{
/// The cell types a mesh file's elements become, with VTK's numbers (vtkCellType.h, the legacy
/// file format's: stable). Each element's nodes are stored in VTK's order for its type.
enum class CellType : int
{
  Vertex = 1,
  Line = 3,
  Triangle = 5,
  Quad = 9,
  Tetra = 10,
  Hexahedron = 12,
  Wedge = 13,
  Pyramid = 14,
  QuadraticEdge = 21,
  QuadraticTriangle = 22,
  QuadraticQuad = 23,
  QuadraticTetra = 24,
  QuadraticHexahedron = 25,
  QuadraticWedge = 26,
  QuadraticPyramid = 27,
  BiQuadraticQuad = 28,
  TriQuadraticHexahedron = 29,
};

/// The number of nodes of a cell of a type.
int nodesPerCell(CellType type);

/// Whether a type has midside nodes (the quadratic ones).
bool isQuadratic(CellType type);

/// The elements of one type, in file order.
struct ElementBlock
{
  std::string name;       // the file's name for the type ("C3D10", "tetrahedron 10")
  CellType type;
  std::vector<std::int64_t> ids;   // the file's element ids
  std::vector<std::int64_t> nodes; // nodesPerCell(type) node ids an element, VTK's order
};

/// A named set of node ids or of element ids, in the file's order, without repeats.
struct NamedSet
{
  std::string name;
  std::vector<std::int64_t> ids;
};

/// Consecutive node ids a file groups under a name (a CGNS zone: "base/zone"): firstId, firstId + 1,
/// ... count of them. A reader that gives no node ids (ParaView's CGNS reader) gives each such
/// group as a block of that name (in a block of the base's name), its points in this order.
struct NodeRange
{
  std::string name;
  std::int64_t firstId = 0;
  std::int64_t count = 0;
};

struct SourceMesh
{
  std::vector<std::int64_t> nodeIds; // in file order
  std::vector<double> xyz;           // 3 a node (a 2D mesh's z is 0)
  std::vector<ElementBlock> blocks;
  std::vector<NamedSet> nodeSets;
  std::vector<NamedSet> elementSets;
  std::vector<NodeRange> zones; // formats whose nodes are numbered by position within named zones
  /// What was read but cannot be represented (an element type without a cell type): each names
  /// the file and the line; the elements are left out, their nodes are read.
  std::vector<std::string> warnings;
};
} // namespace mlsformats
