// Gmsh meshes without VTK: MSH 2.2 and 4.1, ASCII and binary, read alike; a variant keeps every
// byte but the moved coordinates; VTK's node orders; bad files give an error naming the file and
// the line (a binary one: the section and the byte).
#include "../TestHarness.h"
#include "Common/TextFile.h"
#include "FormatFiles.h"
#include "Gmsh/GmshMesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>

namespace fs = std::filesystem;
using namespace mlsformats;

namespace
{
using testing::contains;
using testing::find;
using testing::midsideNodesOnTheirEdges;
using testing::Point;
using testing::position;
using testing::sameMesh;
using testing::tripleProduct;
using testing::writeFile;

const testing::TestFolders folder{ "gmsh" };
const testing::ReadErrors readError{ gmsh::readMsh };

// The bytes of a binary file's numbers, in this machine's order (as Gmsh writes them).
template <class T>
std::string bytes(T value)
{
  return std::string(reinterpret_cast<const char*>(&value), sizeof(T));
}
std::string i32(std::int32_t value)
{
  return bytes(value);
}
std::string u64(std::uint64_t value)
{
  return bytes(value);
}
std::string f64(double value)
{
  return bytes(value);
}
std::string i32s(std::initializer_list<std::int32_t> values)
{
  std::string out;
  for (const std::int32_t value : values)
  {
    out += i32(value);
  }
  return out;
}
std::string u64s(std::initializer_list<std::uint64_t> values)
{
  std::string out;
  for (const std::uint64_t value : values)
  {
    out += u64(value);
  }
  return out;
}

// One small mesh written four ways: two tetrahedra (4 in volume 1; 5 in volume 2, of two physical
// groups), a boundary triangle, a quadratic line whose midside node 6 is parametric in 4.1, a point.
// The coordinates' texts ("0.50", "1.0", "1e0") are not their shortest. MSH 2.2 writes element 5
// twice (tags 5 and 6), once a physical group.
const char* const physicalNames = "$PhysicalNames\n4\n0 3 \"origin\"\n2 2 \"base\"\n3 1 \"solid\"\n3 7 \"tip part\"\n$EndPhysicalNames\n";
const char* const comments = "$Comments\nnot a $Nodes section\n$EndComments\n";
const char* const nodeData = "$NodeData\n1\n\"temperature\"\n1\n0.0\n3\n0\n1\n6\n1 20\n6 21\n2 22\n3 23\n4 24\n5 25\n$EndNodeData\n";

// A binary file's: each node's tag and value in binary.
std::string binaryNodeData()
{
  const std::int32_t nodes[] = { 1, 6, 2, 3, 4, 5 };
  std::string values;
  for (int i = 0; i < 6; ++i)
  {
    values += i32(nodes[i]) + f64(20 + i);
  }
  return "$NodeData\n1\n\"temperature\"\n1\n0.0\n3\n0\n1\n6\n" + values + "\n$EndNodeData\n";
}

const char* const ascii22Nodes = "$Nodes\n6\n1 0 0 0\n6 0.50 0 0\n2 1.0 0 0\n3 0 1 0\n4 0 0 1\n5 1 1 1e0\n$EndNodes\n";

std::string ascii22()
{
  return std::string("$MeshFormat\n2.2 0 8\n$EndMeshFormat\n") + physicalNames + comments + ascii22Nodes +
    "$Elements\n6\n1 15 2 3 1 1\n2 8 2 5 1 1 2 6\n3 2 2 2 1 1 3 2\n4 4 2 1 1 1 2 3 4\n5 4 2 1 2 2 3 4 5\n6 4 2 7 2 2 3 4 5\n"
    "$EndElements\n" +
    nodeData;
}

std::string ascii41()
{
  return std::string("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n") + physicalNames + comments +
    "$Entities\n1 1 1 2\n1 0 0 0 1 3 \n1 0 0 0 1 0 0 1 5 1 1 \n1 0 0 0 1 1 0 1 2 0 \n1 0 0 0 1 1 1 1 1 0 \n"
    "2 0 0 0 1 1 1 2 1 7 0 \n$EndEntities\n"
    "$Nodes\n3 6 1 6\n0 1 0 1\n1\n0 0 0\n1 1 1 1\n6\n0.50 0 0 0.5\n3 1 0 4\n2\n3\n4\n5\n1.0 0 0\n0 1 0\n0 0 1\n1 1 1e0\n"
    "$EndNodes\n"
    "$Elements\n5 5 1 5\n0 1 15 1\n1 1\n1 1 8 1\n2 1 2 6\n2 1 2 1\n3 1 3 2\n3 1 4 1\n4 1 2 3 4\n3 2 4 1\n5 2 3 4 5\n$EndElements\n" +
    nodeData;
}

std::string binary22Nodes()
{
  return "$Nodes\n6\n" + i32(1) + f64(0) + f64(0) + f64(0) + i32(6) + f64(0.5) + f64(0) + f64(0) + i32(2) + f64(1) + f64(0) + f64(0) +
    i32(3) + f64(0) + f64(1) + f64(0) + i32(4) + f64(0) + f64(0) + f64(1) + i32(5) + f64(1) + f64(1) + f64(1) + "\n$EndNodes\n";
}

std::string binary22()
{
  // blocks of (type, elements, tags), then each element's tag, tags and nodes
  return "$MeshFormat\n2.2 1 8\n" + i32(1) + "\n$EndMeshFormat\n" + physicalNames + comments + binary22Nodes() + "$Elements\n6\n" +
    i32s({ 15, 1, 2, 1, 3, 1, 1 }) + i32s({ 8, 1, 2, 2, 5, 1, 1, 2, 6 }) + i32s({ 2, 1, 2, 3, 2, 1, 1, 3, 2 }) +
    i32s({ 4, 3, 2, 4, 1, 1, 1, 2, 3, 4, 5, 1, 2, 2, 3, 4, 5, 6, 7, 2, 2, 3, 4, 5 }) + "\n$EndElements\n" + binaryNodeData();
}

std::string binary41()
{
  const std::string entities = u64s({ 1, 1, 1, 2 }) + i32(1) + f64(0) + f64(0) + f64(0) + u64(1) + i32(3) + // point 1
    i32(1) + f64(0) + f64(0) + f64(0) + f64(1) + f64(0) + f64(0) + u64(1) + i32(5) + u64(1) + i32(1) +            // curve 1
    i32(1) + f64(0) + f64(0) + f64(0) + f64(1) + f64(1) + f64(0) + u64(1) + i32(2) + u64(0) +                    // surface 1
    i32(1) + f64(0) + f64(0) + f64(0) + f64(1) + f64(1) + f64(1) + u64(1) + i32(1) + u64(0) +                    // volume 1
    i32(2) + f64(0) + f64(0) + f64(0) + f64(1) + f64(1) + f64(1) + u64(2) + i32s({ 1, 7 }) + u64(0);             // volume 2
  const std::string nodes = u64s({ 3, 6, 1, 6 }) + i32s({ 0, 1, 0 }) + u64(1) + u64(1) + f64(0) + f64(0) + f64(0) +
    i32s({ 1, 1, 1 }) + u64(1) + u64(6) + f64(0.5) + f64(0) + f64(0) + f64(0.5) + i32s({ 3, 1, 0 }) + u64(4) + u64s({ 2, 3, 4, 5 }) +
    f64(1) + f64(0) + f64(0) + f64(0) + f64(1) + f64(0) + f64(0) + f64(0) + f64(1) + f64(1) + f64(1) + f64(1);
  const std::string elements = u64s({ 5, 5, 1, 5 }) + i32s({ 0, 1, 15 }) + u64s({ 1, 1, 1 }) + i32s({ 1, 1, 8 }) + u64s({ 1, 2, 1, 2, 6 }) +
    i32s({ 2, 1, 2 }) + u64s({ 1, 3, 1, 3, 2 }) + i32s({ 3, 1, 4 }) + u64s({ 1, 4, 1, 2, 3, 4 }) + i32s({ 3, 2, 4 }) +
    u64s({ 1, 5, 2, 3, 4, 5 });
  return "$MeshFormat\n4.1 1 8\n" + i32(1) + "\n$EndMeshFormat\n" + physicalNames + comments + "$Entities\n" + entities +
    "\n$EndEntities\n$Nodes\n" + nodes + "\n$EndNodes\n$Elements\n" + elements + "\n$EndElements\n" + binaryNodeData();
}

// The four files in dir: 2.2 and 4.1, ASCII and binary.
std::array<std::string, 4> fourFiles(const std::string& dir)
{
  return { writeFile(dir + "/a22.msh", ascii22()), writeFile(dir + "/b22.msh", binary22()), writeFile(dir + "/a41.msh", ascii41()),
    writeFile(dir + "/b41.msh", binary41()) };
}

} // namespace

TEST(FourVariantsReadAlike)
{
  const std::string dir = folder("read");
  const std::array<std::string, 4> files = fourFiles(dir);
  const gmsh::MshFile first = gmsh::readMsh(files[0]);
  const SourceMesh& mesh = first.mesh;
  CHECK(mesh.nodeIds == (std::vector<std::int64_t>{ 1, 6, 2, 3, 4, 5 }));
  CHECK(mesh.xyz == (std::vector<double>{ 0, 0, 0, 0.5, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1 }));
  // the tetrahedra are the cells; the triangle, the line and the point are not
  CHECK(mesh.blocks.size() == 1);
  CHECK(!mesh.blocks.empty() && mesh.blocks[0].name == "tetrahedron 4" && mesh.blocks[0].type == CellType::Tetra);
  CHECK(!mesh.blocks.empty() && mesh.blocks[0].ids == (std::vector<std::int64_t>{ 4, 5 }));
  CHECK(!mesh.blocks.empty() && mesh.blocks[0].nodes == (std::vector<std::int64_t>{ 1, 2, 3, 4, 2, 3, 4, 5 }));
  // every physical group a node set, by (dimension, tag); those of dimension 3 element sets too
  std::vector<std::string> names;
  for (const NamedSet& set : mesh.nodeSets)
  {
    names.push_back(set.name);
  }
  CHECK(names == (std::vector<std::string>{ "origin", "physical 1 5", "base", "solid", "tip part" }));
  CHECK(find(mesh.nodeSets, "origin") && find(mesh.nodeSets, "origin")->ids == std::vector<std::int64_t>{ 1 });
  CHECK(find(mesh.nodeSets, "physical 1 5") && find(mesh.nodeSets, "physical 1 5")->ids == (std::vector<std::int64_t>{ 1, 6, 2 }));
  CHECK(find(mesh.nodeSets, "base") && find(mesh.nodeSets, "base")->ids == (std::vector<std::int64_t>{ 1, 2, 3 }));
  CHECK(find(mesh.nodeSets, "solid") && find(mesh.nodeSets, "solid")->ids == (std::vector<std::int64_t>{ 1, 2, 3, 4, 5 }));
  CHECK(find(mesh.nodeSets, "tip part") && find(mesh.nodeSets, "tip part")->ids == (std::vector<std::int64_t>{ 2, 3, 4, 5 }));
  CHECK(mesh.elementSets.size() == 2);
  CHECK(find(mesh.elementSets, "solid") && find(mesh.elementSets, "solid")->ids == (std::vector<std::int64_t>{ 4, 5 }));
  CHECK(find(mesh.elementSets, "tip part") && find(mesh.elementSets, "tip part")->ids == std::vector<std::int64_t>{ 5 });
  CHECK(mesh.warnings.empty());
  CHECK(!first.binary);
  for (std::size_t f = 1; f < files.size(); ++f)
  {
    const gmsh::MshFile other = gmsh::readMsh(files[f]);
    CHECK(sameMesh(other.mesh, mesh));
    CHECK(other.mesh.warnings.empty());
    CHECK(other.binary == (f % 2 == 1));
  }
  // the layout: the node tags alone
  for (const std::string& file : files)
  {
    const gmsh::MshFile layout = gmsh::readMshLayout(file);
    CHECK(layout.mesh.nodeIds == mesh.nodeIds && layout.mesh.xyz == mesh.xyz && layout.mesh.blocks.empty() && layout.mesh.nodeSets.empty());
  }
  CHECK(gmsh::isMsh("$MeshFormat\n4.1 0 8\n") && !gmsh::isMsh("*HEADING\n") && !gmsh::isMsh(""));
}

TEST(VariantKeepsEveryOtherByte)
{
  const std::string dir = folder("variant");
  for (const std::string& source : fourFiles(dir))
  {
    const gmsh::MshFile file = gmsh::readMsh(source);
    const std::size_t count = file.mesh.nodeIds.size();
    const std::string name = fs::path(source).stem().string();
    // the same coordinates: the same bytes
    file.writeVariant(dir + "/same/" + name + ".msh", file.mesh.nodeIds.data(), file.mesh.xyz.data(), count, false);
    CHECK(readFile(dir + "/same/" + name + ".msh") == readFile(source));
    // nodes 6 and 5 moved, given in reverse order
    std::vector<std::int64_t> ids(file.mesh.nodeIds.rbegin(), file.mesh.nodeIds.rend());
    std::vector<double> xyz;
    for (std::size_t i = count; i-- > 0;)
    {
      xyz.insert(xyz.end(), file.mesh.xyz.begin() + 3 * i, file.mesh.xyz.begin() + 3 * i + 3);
    }
    const double moved6[3] = { 0.5, 0.25, 1.0 / 3.0 }, moved5[3] = { 1.1, 1, -1e-17 };
    std::copy(moved6, moved6 + 3, xyz.begin() + 3 * (count - 2)); // node 6 is second in the file
    std::copy(moved5, moved5 + 3, xyz.begin());                   // node 5 last
    const std::string target = dir + "/moved/" + name + ".msh";
    file.writeVariant(target, ids.data(), xyz.data(), count, false);
    const std::string text = readFile(source), variant = readFile(target);
    if (!file.binary)
    {
      // only the changed numbers' texts change (4.1's parametric u stays)
      std::string expected = text;
      const bool v22 = name == "a22";
      const std::string line6 = v22 ? "6 0.50 0 0\n" : "0.50 0 0 0.5\n", line5 = v22 ? "5 1 1 1e0\n" : "1 1 1e0\n";
      expected.replace(expected.find(line6), line6.size(), v22 ? "6 0.50 0.25 0.3333333333333333\n" : "0.50 0.25 0.3333333333333333 0.5\n");
      expected.replace(expected.rfind(line5), line5.size(), v22 ? "5 1.1 1 -1e-17\n" : "1.1 1 -1e-17\n");
      CHECK(variant == expected);
    }
    else
    {
      // the same size, differing only in the moved doubles' bytes
      CHECK(testing::changedAtMost(text, variant, 4 * 8));
    }
    const gmsh::MshFile again = gmsh::readMsh(target);
    CHECK(again.mesh.nodeIds == file.mesh.nodeIds);
    const Point at6 = position(again.mesh, 6), at5 = position(again.mesh, 5);
    CHECK(at6[0] == moved6[0] && at6[1] == moved6[1] && at6[2] == moved6[2]);
    CHECK(at5[0] == moved5[0] && at5[1] == moved5[1] && at5[2] == moved5[2]);
    CHECK(position(again.mesh, 3) == position(file.mesh, 3));
    SourceMesh unmoved = again.mesh;
    unmoved.xyz = file.mesh.xyz;
    CHECK(sameMesh(unmoved, file.mesh));
    // the layout alone writes the same variant
    const gmsh::MshFile layout = gmsh::readMshLayout(source);
    layout.writeVariant(dir + "/layout/" + name + ".msh", ids.data(), xyz.data(), count, false);
    CHECK(readFile(dir + "/layout/" + name + ".msh") == variant);
  }
}

TEST(VariantRefusesOtherDataAndNeverHalfWrites)
{
  const std::string dir = folder("refuse");
  for (const std::string& source : fourFiles(dir))
  {
    testing::checkVariantRefusals(gmsh::readMsh(source), source, dir, "$Comments\nedited\n$EndComments\n");
  }
}

TEST(NodeOrdersAreVtks)
{
  // one element of each type with midside nodes, and a prism, their nodes where Gmsh's reference
  // manual puts them: a tetrahedron's midside nodes 4-9 on its edges 0-1 1-2 2-0 3-0 3-2 3-1, a
  // hexahedron's 8-19 on 0-1 0-3 0-4 1-2 1-5 2-3 2-6 3-7 4-5 4-7 5-6 6-7 and 20-26 at the centres of
  // the faces 0321 0154 0473 1265 2376 4567 and of the volume, a prism's 6-14 on 0-1 0-2 0-3 1-2 1-4
  // 2-5 3-4 3-5 4-5 (its 0-1-2 turning counter-clockwise seen from 3-4-5)
  const std::string dir = folder("orders");
  const std::vector<Point> tetra = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } },
                           hexahedron = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 },
                             { 0, 1, 1 } },
                           prism = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 0, 1, 1 } };
  const std::vector<std::vector<int>> tetraEdges = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 3, 0 }, { 3, 2 }, { 3, 1 } },
                                      hexahedronEdges = { { 0, 1 }, { 0, 3 }, { 0, 4 }, { 1, 2 }, { 1, 5 }, { 2, 3 }, { 2, 6 },
                                        { 3, 7 }, { 4, 5 }, { 4, 7 }, { 5, 6 }, { 6, 7 }, { 0, 3, 2, 1 }, { 0, 1, 5, 4 },
                                        { 0, 4, 7, 3 }, { 1, 2, 6, 5 }, { 2, 3, 7, 6 }, { 4, 5, 6, 7 }, { 0, 1, 2, 3, 4, 5, 6, 7 } },
                                      prismEdges = { { 0, 1 }, { 0, 2 }, { 0, 3 }, { 1, 2 }, { 1, 4 }, { 2, 5 }, { 3, 4 }, { 3, 5 },
                                        { 4, 5 } };
  // the corners moved apart so that no two nodes meet; each element's nodes from tag first + 1
  std::string nodes, elements;
  int blocks = 0, nodeCount = 0;
  auto add = [&](int type, int first, std::vector<Point> corners, const std::vector<std::vector<int>>& between, std::size_t count) {
    std::vector<Point> points;
    for (Point corner : corners)
    {
      points.push_back({ first + corner[0] * 2, corner[1] * 3, corner[2] * 5 });
    }
    for (std::size_t m = 0; m < count - corners.size(); ++m)
    {
      Point sum{ 0, 0, 0 };
      for (const int corner : between[m])
      {
        for (int c = 0; c < 3; ++c)
        {
          sum[c] += points[corner][c] / between[m].size();
        }
      }
      points.push_back(sum);
    }
    nodes += "3 " + std::to_string(type) + " 0 " + std::to_string(points.size()) + "\n";
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      nodes += std::to_string(first + 1 + i) + "\n";
    }
    for (const Point& p : points)
    {
      nodes += std::to_string(p[0]) + " " + std::to_string(p[1]) + " " + std::to_string(p[2]) + "\n";
    }
    elements += "3 " + std::to_string(type) + " " + std::to_string(type) + " 1\n" + std::to_string(type);
    for (std::size_t i = 0; i < points.size(); ++i)
    {
      elements += " " + std::to_string(first + 1 + i);
    }
    elements += "\n";
    ++blocks;
    nodeCount += static_cast<int>(points.size());
  };
  add(11, 0, tetra, tetraEdges, 10);
  add(17, 100, hexahedron, hexahedronEdges, 20);
  add(12, 200, hexahedron, hexahedronEdges, 27);
  add(18, 300, prism, prismEdges, 15);
  add(6, 400, prism, {}, 6);
  add(4, 500, tetra, {}, 4);
  add(5, 600, hexahedron, {}, 8);
  const std::string counts = std::to_string(blocks) + " " + std::to_string(nodeCount);
  const gmsh::MshFile file = gmsh::readMsh(writeFile(dir + "/orders.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n" + counts +
      " 1 608\n" + nodes + "$EndNodes\n$Elements\n" + std::to_string(blocks) + " " + std::to_string(blocks) + " 6 600\n" + elements +
      "$EndElements\n"));
  const SourceMesh& mesh = file.mesh;
  CHECK(mesh.warnings.empty());
  CHECK(mesh.blocks.size() == 7);
  if (mesh.blocks.size() != 7)
  {
    return;
  }
  const ElementBlock &tetra10 = mesh.blocks[0], &hexa20 = mesh.blocks[1], &hexa27 = mesh.blocks[2], &prism15 = mesh.blocks[3],
                     &prism6 = mesh.blocks[4], &tetra4 = mesh.blocks[5], &hexa8 = mesh.blocks[6];
  CHECK(tetra10.type == CellType::QuadraticTetra && tetra10.name == "tetrahedron 10");
  CHECK(hexa20.type == CellType::QuadraticHexahedron && hexa20.name == "hexahedron 20");
  CHECK(hexa27.type == CellType::TriQuadraticHexahedron && hexa27.name == "hexahedron 27");
  CHECK(prism15.type == CellType::QuadraticWedge && prism15.name == "prism 15");
  CHECK(prism6.type == CellType::Wedge && prism6.name == "prism 6");
  // VTK's edges (vtkQuadraticTetra, vtkQuadraticHexahedron, vtkQuadraticWedge)
  const std::vector<std::array<int, 2>> vtkTetraEdges = { { { 0, 1 } }, { { 1, 2 } }, { { 2, 0 } }, { { 0, 3 } }, { { 1, 3 } }, { { 2, 3 } } },
                                        vtkHexahedronEdges = { { { 0, 1 } }, { { 1, 2 } }, { { 2, 3 } }, { { 3, 0 } }, { { 4, 5 } },
                                          { { 5, 6 } }, { { 6, 7 } }, { { 7, 4 } }, { { 0, 4 } }, { { 1, 5 } }, { { 2, 6 } }, { { 3, 7 } } },
                                        vtkWedgeEdges = { { { 0, 1 } }, { { 1, 2 } }, { { 2, 0 } }, { { 3, 4 } }, { { 4, 5 } },
                                          { { 5, 3 } }, { { 0, 3 } }, { { 1, 4 } }, { { 2, 5 } } };
  CHECK(midsideNodesOnTheirEdges(mesh, tetra10, 4, vtkTetraEdges));
  CHECK(midsideNodesOnTheirEdges(mesh, hexa20, 8, vtkHexahedronEdges));
  CHECK(midsideNodesOnTheirEdges(mesh, hexa27, 8, vtkHexahedronEdges));
  CHECK(midsideNodesOnTheirEdges(mesh, prism15, 6, vtkWedgeEdges));
  // vtkTriQuadraticHexahedron's face centres 20-25: x = 0, x = 1, y = 0, y = 1, z = 0, z = 1 (its
  // parametric coordinates); 26 the centre
  const Point low = position(mesh, hexa27.nodes[0]), high = position(mesh, hexa27.nodes[6]);
  const Point middle{ (low[0] + high[0]) / 2, (low[1] + high[1]) / 2, (low[2] + high[2]) / 2 };
  for (int f = 0; f < 6; ++f)
  {
    Point centre = middle;
    centre[f / 2] = f % 2 == 0 ? low[f / 2] : high[f / 2];
    CHECK(position(mesh, hexa27.nodes[20 + f]) == centre);
  }
  CHECK(position(mesh, hexa27.nodes[26]) == middle);
  // VTK's wedge turns 0-1-2 away from 3-4-5: Gmsh's 0 2 1 3 5 4
  CHECK(prism6.nodes == (std::vector<std::int64_t>{ 401, 403, 402, 404, 406, 405 }));
  CHECK(std::equal(prism6.nodes.begin(), prism6.nodes.end(), prism15.nodes.begin(),
    [](std::int64_t a, std::int64_t b) { return a - 400 == b - 300; }));
  auto sign = [&](const ElementBlock& block, std::array<int, 4> corners) {
    return tripleProduct(position(mesh, block.nodes[corners[0]]), position(mesh, block.nodes[corners[1]]),
      position(mesh, block.nodes[corners[2]]), position(mesh, block.nodes[corners[3]]));
  };
  CHECK(sign(prism6, { 0, 1, 2, 3 }) < 0 && sign(prism15, { 0, 1, 2, 3 }) < 0);
  CHECK(sign(tetra4, { 0, 1, 2, 3 }) > 0 && sign(tetra10, { 0, 1, 2, 3 }) > 0);
  CHECK(sign(hexa8, { 0, 1, 3, 4 }) > 0 && sign(hexa20, { 0, 1, 3, 4 }) > 0 && sign(hexa27, { 0, 1, 3, 4 }) > 0);
}

TEST(SurfaceMeshKeepsItsSurfaceCells)
{
  // a 2D mesh: its quadrangles and triangles are the cells, the boundary line is not; an element
  // type without a cell type, and one that is not Gmsh's, are left out with a warning; a name of
  // two physical groups is told apart
  const std::string dir = folder("surface");
  const std::string source = writeFile(dir + "/plate.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"
                                                            "$PhysicalNames\n2\n1 3 \"plate\"\n2 4 \"plate\"\n$EndPhysicalNames\n$Nodes\n9\n"
                                                            "1 0 0 0\n2 2 0 0\n3 2 2 0\n4 0 2 0\n5 1 0 0\n6 2 1 0\n7 1 2 0\n8 0 1 0\n"
                                                            "9 1 1 0\n$EndNodes\n$Elements\n7\n"
                                                            "1 10 2 4 1 1 2 3 4 5 6 7 8 9\n"
                                                            "2 16 2 4 1 1 2 3 4 5 6 7 8\n"
                                                            "3 9 2 4 1 1 2 3 5 6 9\n"
                                                            "4 2 2 4 1 1 2 3\n"
                                                            "5 8 2 3 1 1 2 5\n"
                                                            "6 20 2 0 1 1 2 3 5 5 6 6 9 9\n"
                                                            "7 250 2 0 1 1 2\n$EndElements\n");
  const gmsh::MshFile file = gmsh::readMsh(source);
  const SourceMesh& mesh = file.mesh;
  CHECK(mesh.blocks.size() == 4);
  const CellType types[] = { CellType::BiQuadraticQuad, CellType::QuadraticQuad, CellType::QuadraticTriangle, CellType::Triangle };
  for (std::size_t b = 0; b < mesh.blocks.size() && b < 4; ++b)
  {
    CHECK(mesh.blocks[b].type == types[b] && mesh.blocks[b].ids == std::vector<std::int64_t>{ static_cast<std::int64_t>(b + 1) });
  }
  CHECK(mesh.elementSets.size() == 1 && mesh.elementSets[0].name == "plate (physical 2 4)" &&
    mesh.elementSets[0].ids == (std::vector<std::int64_t>{ 1, 2, 3, 4 }));
  CHECK(mesh.nodeSets.size() == 2 && mesh.nodeSets[0].name == "plate (physical 1 3)" &&
    mesh.nodeSets[0].ids == (std::vector<std::int64_t>{ 1, 2, 5 }));
  for (const std::string& warning : mesh.warnings)
  {
    std::printf("warning: %s\n", warning.c_str());
  }
  CHECK(mesh.warnings.size() == 2);
  CHECK(mesh.warnings.size() == 2 && contains(mesh.warnings[0], "plate.msh:28: element type 20 (triangle 9) is not supported: its 1 elements are left out"));
  CHECK(mesh.warnings.size() == 2 && contains(mesh.warnings[1], "plate.msh:29: element type 250 is not one of Gmsh's: its 1 elements are left out"));
}

TEST(PartitionedMeshKeepsItsPhysicalGroups)
{
  // a partitioned mesh's elements are in the partitions' entities, which $PartitionedEntities gives
  // their physical groups
  const std::string dir = folder("partitioned");
  const gmsh::MshFile file = gmsh::readMsh(writeFile(dir + "/parts.msh",
    "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n1\n3 1 \"solid\"\n$EndPhysicalNames\n"
    "$Entities\n0 0 0 1\n1 0 0 0 1 1 1 1 1 0 \n$EndEntities\n"
    "$PartitionedEntities\n2\n1\n3 2\n0 0 0 2\n2 3 1 1 1 0 0 0 1 1 1 1 1 0 \n3 3 1 1 2 0 0 0 1 1 1 1 1 0 \n$EndPartitionedEntities\n"
    "$Nodes\n1 5 1 5\n3 2 0 5\n1\n2\n3\n4\n5\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n1 1 1\n$EndNodes\n"
    "$Elements\n2 2 1 2\n3 2 4 1\n1 1 2 3 4\n3 3 4 1\n2 2 3 4 5\n$EndElements\n"));
  CHECK(file.mesh.blocks.size() == 1 && file.mesh.blocks[0].ids == (std::vector<std::int64_t>{ 1, 2 }));
  CHECK(file.mesh.elementSets.size() == 1 && file.mesh.elementSets[0].name == "solid" &&
    file.mesh.elementSets[0].ids == (std::vector<std::int64_t>{ 1, 2 }));
  CHECK(file.mesh.nodeSets.size() == 1 && file.mesh.nodeSets[0].ids == (std::vector<std::int64_t>{ 1, 2, 3, 4, 5 }));
}

TEST(BadFilesNameTheFileAndTheLine)
{
  const std::string dir = folder("bad");
  const std::string format = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
  const std::string nodes = "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n";
  const std::string tetra = "$Elements\n1\n1 4 2 1 1 1 2 3 4\n$EndElements\n";
  CHECK(contains(readError(writeFile(dir + "/version.msh", "$MeshFormat\n4 0 8\n$EndMeshFormat\n")),
    "version.msh:2: MSH version 4 is not supported (2.2 and 4.1 are)"));
  CHECK(contains(readError(writeFile(dir + "/v3.msh", "$MeshFormat\n3.0 0 8\n$EndMeshFormat\n")), "v3.msh:2: MSH version 3.0 is not supported"));
  CHECK(contains(readError(writeFile(dir + "/number.msh", format + "$Nodes\n2\n1 0 0 0\n2 1.0.0 0 0\n$EndNodes\n")),
    "number.msh:7: node 2's coordinate \"1.0.0\" is not a finite number"));
  CHECK(contains(readError(writeFile(dir + "/nan.msh", format + "$Nodes\n1\n1 nan 0 0\n$EndNodes\n")), "nan.msh:6: node 1's coordinate \"nan\""));
  CHECK(contains(readError(writeFile(dir + "/inf.msh", format + "$Nodes\n1\n1 0 1e999 0\n$EndNodes\n")), "inf.msh:6: node 1's coordinate"));
  CHECK(contains(readError(writeFile(dir + "/tag.msh", format + "$Nodes\n1\nx1 0 0 0\n$EndNodes\n")), "tag.msh:6: \"x1\" is not a node tag"));
  CHECK(contains(readError(writeFile(dir + "/fields.msh", format + "$Nodes\n1\n1 0 0\n$EndNodes\n")),
    "fields.msh:6: a line of 3 fields where \"tag x y z\" is expected"));
  // a count the rest of the file can hold, and fewer lines
  CHECK(contains(readError(writeFile(dir + "/cut.msh", format + "$Nodes\n2\n1 0.000000 0.000000 0.000000\n")),
    "cut.msh:6: the file ends inside $Nodes"));
  CHECK(contains(readError(writeFile(dir + "/short.msh", format + "$Nodes\n3\n1 0.0000 0.0000 0.0000\n2 1.0000 0.0000 0.0000\n$EndNodes\n")),
    "short.msh:8: $EndNodes where $Nodes has more data by its counts"));
  CHECK(contains(readError(writeFile(dir + "/long.msh", format + "$Nodes\n1\n1 0 0 0\n2 1 0 0\n$EndNodes\n")),
    "long.msh:7: not $EndNodes, where the counts of $Nodes end"));
  CHECK(contains(readError(writeFile(dir + "/twice.msh", format + "$Nodes\n3\n1 0 0 0\n3 1 0 0\n3 0 1 0\n$EndNodes\n")),
    "twice.msh:8: node 3 is defined twice"));
  CHECK(contains(readError(writeFile(dir + "/missing.msh", format + nodes + "$Elements\n1\n1 4 2 1 1 1 2 3 9\n$EndElements\n")),
    "missing.msh:13: element 1 refers to node 9, which $Nodes does not define"));
  CHECK(contains(readError(writeFile(dir + "/count.msh", format + nodes + "$Elements\n1\n1 4 2 1 1 1 2 3\n$EndElements\n")),
    "count.msh:13: element 1 has 3 nodes; a tetrahedron 4 has 4"));
  CHECK(contains(readError(writeFile(dir + "/eltwice.msh", format + nodes + "$Elements\n2\n1 4 2 1 1 1 2 3 4\n1 4 2 1 1 1 3 2 4\n$EndElements\n")),
    "eltwice.msh:14: element 1 is defined twice"));
  CHECK(contains(readError(writeFile(dir + "/huge.msh", format + "$Nodes\n999999999999\n1 0 0 0\n$EndNodes\n")),
    "huge.msh:5: 999999999999 nodes: more than the rest of the file holds"));
  CHECK(contains(readError(writeFile(dir + "/order.msh", format + tetra + nodes)), "order.msh:4: $Elements before $Nodes"));
  CHECK(contains(readError(writeFile(dir + "/nonodes.msh", format)), "nonodes.msh: has no $Nodes section"));
  CHECK(contains(readError(writeFile(dir + "/notmsh.msh", "*HEADING\n")), "notmsh.msh:1: does not start with $MeshFormat"));
  CHECK(contains(readError(dir + "/none.msh"), "none.msh: cannot be read"));
  // MSH 4.1: a block's coordinates, the header's count
  const std::string format41 = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n";
  CHECK(contains(readError(writeFile(dir + "/block.msh", format41 + "$Nodes\n1 2 1 2\n1 1 1 2\n1\n2\n0 0 0 0.5\n1 0 0\n$EndNodes\n")),
    "block.msh:10: node 2 has 3 coordinates; its block's have 4"));
  CHECK(contains(readError(writeFile(dir + "/header.msh", format41 + "$Nodes\n1 3 1 2\n0 1 0 2\n1\n2\n0 0 0\n1 0 0\n$EndNodes\n")),
    "header.msh:10: the blocks of $Nodes hold 2 nodes, its header says 3"));
  // binary: the section and the byte
  const std::string binary22 = "$MeshFormat\n2.2 1 8\n" + i32(1) + "\n$EndMeshFormat\n";
  CHECK(contains(readError(writeFile(dir + "/endian.msh", "$MeshFormat\n2.2 1 8\n" + i32(0x01000000) + "\n$EndMeshFormat\n")),
    "endian.msh: $MeshFormat, byte 20: the integer 1 does not read as 1: the file was written with another byte order"));
  CHECK(contains(readError(writeFile(dir + "/size.msh", "$MeshFormat\n4.1 1 4\n" + i32(1) + "\n$EndMeshFormat\n")),
    "size.msh:2: data size 4 is not supported (8 is)"));
  CHECK(contains(readError(writeFile(dir + "/bnan.msh", binary22 + "$Nodes\n2\n" + i32(1) + f64(0) + f64(0) + f64(0) + i32(2) + f64(0) +
                                                          f64(std::numeric_limits<double>::infinity()) + f64(0) + "\n$EndNodes\n")),
    "bnan.msh: $Nodes, byte 81: node 2's coordinate inf is not a finite number"));
  CHECK(contains(readError(writeFile(dir + "/bshort.msh", binary22 + "$Nodes\n2\n" + i32(1) + f64(0) + f64(0) + f64(0) + i32(2) + f64(0))),
    "bshort.msh: $Nodes, byte 47: 2 nodes: more than the rest of the file holds"));
  CHECK(contains(readError(writeFile(dir + "/bcut.msh", binary22 + "$Nodes\n1\n" + i32(1) + f64(0) + f64(0) + f64(0))),
    "bcut.msh: $Nodes, byte 77: the file ends inside $Nodes"));
  CHECK(contains(readError(writeFile(dir + "/bhuge.msh", "$MeshFormat\n4.1 1 8\n" + i32(1) + "\n$EndMeshFormat\n$Nodes\n" +
                                                           u64s({ 1, std::uint64_t(1) << 60, 1, 2 }) + "\n$EndNodes\n")),
    "bhuge.msh: $Nodes, byte 47: 1152921504606846976 nodes: more than the rest of the file holds"));
  CHECK(contains(readError(writeFile(dir + "/btype.msh", binary22 + "$Nodes\n1\n" + i32(1) + f64(0) + f64(0) + f64(0) +
                                                           "\n$EndNodes\n$Elements\n1\n" + i32s({ 250, 1, 0, 1, 1 }) + "\n$EndElements\n")),
    "btype.msh: $Elements, byte 100: element type 250 is not one of Gmsh's: its elements cannot be skipped"));
  CHECK(contains(readError(writeFile(dir + "/bmissing.msh", binary22 + "$Nodes\n1\n" + i32(1) + f64(0) + f64(0) + f64(0) +
                                                              "\n$EndNodes\n$Elements\n1\n" + i32s({ 15, 1, 0, 7, 2 }) + "\n$EndElements\n")),
    "bmissing.msh: $Elements, byte 112: element 7 refers to node 2, which $Nodes does not define"));
}

TEST_MAIN
