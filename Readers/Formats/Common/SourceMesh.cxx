#include "Common/SourceMesh.h"

namespace mlsformats
{
int nodesPerCell(CellType type)
{
  switch (type)
  {
    case CellType::Vertex: return 1;
    case CellType::Line: return 2;
    case CellType::Triangle: return 3;
    case CellType::Quad: return 4;
    case CellType::Tetra: return 4;
    case CellType::Hexahedron: return 8;
    case CellType::Wedge: return 6;
    case CellType::Pyramid: return 5;
    case CellType::QuadraticEdge: return 3;
    case CellType::QuadraticTriangle: return 6;
    case CellType::QuadraticQuad: return 8;
    case CellType::QuadraticTetra: return 10;
    case CellType::QuadraticHexahedron: return 20;
    case CellType::QuadraticWedge: return 15;
    case CellType::QuadraticPyramid: return 13;
    case CellType::BiQuadraticQuad: return 9;
    case CellType::TriQuadraticHexahedron: return 27;
  }
  return 0;
}

bool isQuadratic(CellType type)
{
  return static_cast<int>(type) >= static_cast<int>(CellType::QuadraticEdge);
}
} // namespace mlsformats
