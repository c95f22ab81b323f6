// Fluent meshes without VTK: ASCII and binary (single and double precision) read alike; cells
// rebuilt from their faces in VTK's node order; a variant keeps every byte but the moved
// coordinates; bad files give an error naming the file and the line (in a binary section: the
// section and the byte); a Fluent .msh is told from a Gmsh one.
#include "../TestHarness.h"
#include "Common/TextFile.h"
#include "FormatFiles.h"
#include "Fluent/FluentMesh.h"
#include "Gmsh/GmshMesh.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <map>
#include <set>
#include <string>

namespace fs = std::filesystem;
using namespace mlsformats;

namespace
{
using testing::contains;
using testing::find;
using testing::Point;
using testing::position;
using testing::sameMesh;
using testing::tripleProduct;
using testing::writeFile;

const testing::TestFolders folder{ "fluent" };
const testing::ReadErrors readError{ fluent::readFluent };

using Nodes = std::vector<std::int64_t>;

// A mesh to write as a Fluent file: its nodes (ids from 1, in two node zones: up to split and the
// rest), its cells (ids from 1, VTK's node order) in named cell zones of consecutive cells, its
// boundary faces in the zone "bottom" when bottom(node) holds for each of their nodes, else "skin".
struct Sample
{
  int dimension;
  std::vector<Point> nodes;
  std::size_t split;
  std::vector<Nodes> cells;
  std::vector<std::pair<std::string, std::size_t>> cellZones; // name, number of cells
  bool (*bottom)(const Point&);
};

// A hexahedron, a wedge beside it, a pyramid on it and a tetrahedron on the pyramid, in the cell
// zones "solid" (id 1) and "cap" (id 16, hexadecimal 10 in the headers).
Sample solid()
{
  return { 3,
    { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 }, { 2, 0, 0 }, { 2, 1, 0 },
      { 0.5, 0.5, 2 }, { 1.5, 0.5, 1.75 } },
    8, { { 1, 2, 3, 4, 5, 6, 7, 8 }, { 2, 9, 6, 3, 10, 7 }, { 5, 6, 7, 8, 11 }, { 6, 7, 11, 12 } }, { { "solid", 2 }, { "cap", 2 } },
    [](const Point& p) { return p[2] == 0; } };
}

// Two quadrilaterals (zone "plate") and a triangle (zone "tip").
Sample plate()
{
  return { 2, { { 0, 0, 0 }, { 1, 0, 0 }, { 2, 0, 0 }, { 0, 1, 0 }, { 1, 1, 0 }, { 2, 1, 0 }, { 3, 0.5, 0 } }, 4,
    { { 1, 2, 5, 4 }, { 2, 3, 6, 5 }, { 3, 7, 6 } }, { { "plate", 2 }, { "tip", 1 } }, [](const Point& p) { return p[1] == 0; } };
}

// The faces of a cell of each type as VTK numbers its nodes, each turning about the normal into
// the cell (2D: the edges with the cell on their left): as a face whose c0 the cell is lists them.
const std::vector<std::vector<int>>& sides(int dimension, std::size_t nodes)
{
  static const std::vector<std::vector<int>> triangle = { { 0, 1 }, { 1, 2 }, { 2, 0 } },
                                             quadrilateral = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 } },
                                             tetra = { { 0, 1, 2 }, { 0, 3, 1 }, { 1, 3, 2 }, { 0, 2, 3 } },
                                             pyramid = { { 0, 1, 2, 3 }, { 0, 4, 1 }, { 1, 4, 2 }, { 2, 4, 3 }, { 3, 4, 0 } },
                                             wedge = { { 0, 2, 1 }, { 3, 4, 5 }, { 0, 1, 4, 3 }, { 1, 2, 5, 4 }, { 2, 0, 3, 5 } },
                                             hexahedron = { { 0, 1, 2, 3 }, { 4, 7, 6, 5 }, { 0, 4, 5, 1 }, { 1, 5, 6, 2 },
                                               { 2, 6, 7, 3 }, { 3, 7, 4, 0 } };
  if (dimension == 2)
  {
    return nodes == 3 ? triangle : quadrilateral;
  }
  return nodes == 4 ? tetra : nodes == 5 ? pyramid : nodes == 6 ? wedge : hexahedron;
}

// A cell's faces, each as its sorted nodes.
std::set<Nodes> faceSet(int dimension, const std::int64_t* cell, std::size_t count)
{
  std::set<Nodes> faces;
  for (const std::vector<int>& side : sides(dimension, count))
  {
    Nodes face;
    for (const int k : side)
    {
      face.push_back(cell[k]);
    }
    std::sort(face.begin(), face.end());
    faces.insert(face);
  }
  return faces;
}

// The VTK type of a cell.
CellType typeOf(int dimension, std::size_t nodes)
{
  if (dimension == 2)
  {
    return nodes == 3 ? CellType::Triangle : CellType::Quad;
  }
  return nodes == 4 ? CellType::Tetra : nodes == 5 ? CellType::Pyramid : nodes == 6 ? CellType::Wedge : CellType::Hexahedron;
}

// Fluent's element type of a cell.
int elementType(int dimension, std::size_t nodes)
{
  return dimension == 2 ? (nodes == 3 ? 1 : 3) : nodes == 4 ? 2 : nodes == 5 ? 5 : nodes == 6 ? 6 : 4;
}

struct Face
{
  Nodes nodes;
  std::int64_t c0, c1;
};

// The mesh's faces, each listed by the first cell that has it (its c0), in zones: the interior
// ones, then "bottom", then "skin".
std::array<std::vector<Face>, 3> facesOf(const Sample& sample)
{
  std::vector<Face> faces;
  std::map<Nodes, std::size_t> found;
  for (std::size_t c = 0; c < sample.cells.size(); ++c)
  {
    const Nodes& cell = sample.cells[c];
    for (const std::vector<int>& side : sides(sample.dimension, cell.size()))
    {
      Nodes nodes;
      for (const int k : side)
      {
        nodes.push_back(cell[k]);
      }
      Nodes key = nodes;
      std::sort(key.begin(), key.end());
      const auto [at, added] = found.emplace(key, faces.size());
      if (added)
      {
        faces.push_back({ nodes, static_cast<std::int64_t>(c + 1), 0 });
      }
      else
      {
        faces[at->second].c1 = static_cast<std::int64_t>(c + 1);
      }
    }
  }
  std::array<std::vector<Face>, 3> zones;
  for (const Face& face : faces)
  {
    const bool bottom = std::all_of(face.nodes.begin(), face.nodes.end(), [&](std::int64_t n) { return sample.bottom(sample.nodes[n - 1]); });
    zones[face.c1 != 0 ? 0 : bottom ? 1 : 2].push_back(face);
  }
  return zones;
}

enum class Encoding
{
  Text,
  Single,
  Double
};

std::string hex(std::int64_t value)
{
  char text[32];
  std::snprintf(text, sizeof(text), "%llx", static_cast<long long>(value));
  return text;
}

// The bytes of a binary file's numbers, in this machine's order (as Fluent writes them).
template <class T>
std::string bytes(T value)
{
  return std::string(reinterpret_cast<const char*>(&value), sizeof(T));
}

// A section "(index (header)(data))", binary: "(20index (header)(" data ")\nEnd of Binary Section   20index)".
std::string section(Encoding encoding, int index, const std::string& header, const std::string& data)
{
  if (encoding == Encoding::Text)
  {
    return "(" + std::to_string(index) + " (" + header + ")(\n" + data + "))\n";
  }
  const std::string code = std::to_string((encoding == Encoding::Single ? 2000 : 3000) + index);
  return "(" + code + " (" + header + ")(" + data + ")\nEnd of Binary Section   " + code + ")\n";
}

// The sample as a Fluent mesh: its node coordinates as text ("%.10e", as foamMeshToFluent writes
// them) or binary, its faces and cells' element types as text or 32-bit integers. Zone ids: the
// interior faces 2, "bottom" 3, "skin" 11 (hexadecimal b), the cell zones 1 and 16. A comment
// holds parentheses in its string.
std::string fluentFile(const Sample& sample, Encoding encoding)
{
  const int dimension = sample.dimension;
  const std::array<std::vector<Face>, 3> zones = facesOf(sample);
  const std::size_t faces = zones[0].size() + zones[1].size() + zones[2].size();
  std::string out = "(0 \"hand-made: a comment with (\")\n\n(2 " + std::to_string(dimension) + ")\n(10 (0 1 " + hex(sample.nodes.size()) +
    " 0 " + std::to_string(dimension) + "))\n(13 (0 1 " + hex(faces) + " 0))\n(12 (0 1 " + hex(sample.cells.size()) + " 0))\n";
  // the nodes, in two zones
  for (const auto& [first, last] : { std::make_pair(std::size_t(0), sample.split), std::make_pair(sample.split, sample.nodes.size()) })
  {
    std::string data;
    for (std::size_t n = first; n < last; ++n)
    {
      for (int c = 0; c < dimension; ++c)
      {
        char text[32];
        std::snprintf(text, sizeof(text), c + 1 < dimension ? "%.10e " : "%.10e\n", sample.nodes[n][c]);
        data += encoding == Encoding::Text     ? std::string(text)
          : encoding == Encoding::Single ? bytes(static_cast<float>(sample.nodes[n][c]))
                                         : bytes(sample.nodes[n][c]);
      }
    }
    out += section(encoding, 10, std::string(first == 0 ? "1" : "2") + " " + hex(first + 1) + " " + hex(last) + " 1 " + std::to_string(dimension), data);
  }
  // the faces: 2D lines (face type 2), 3D mixed (0: each face's number of nodes first)
  const int ids[3] = { 2, 3, 11 }, types[3] = { 2, 3, 3 };
  const char* const names[3] = { "interior-fluid", "bottom", "skin" };
  std::size_t next = 1;
  for (int z = 0; z < 3; ++z)
  {
    std::string data;
    for (const Face& face : zones[z])
    {
      std::vector<std::int64_t> numbers = face.nodes;
      numbers.insert(numbers.begin(), static_cast<std::int64_t>(face.nodes.size()));
      numbers.push_back(face.c0);
      numbers.push_back(face.c1);
      for (std::size_t k = dimension == 2 ? 1 : 0; k < numbers.size(); ++k)
      {
        data += encoding == Encoding::Text ? hex(numbers[k]) + (k + 1 < numbers.size() ? " " : "\n") : bytes(static_cast<std::int32_t>(numbers[k]));
      }
    }
    out += section(encoding, 13,
      hex(ids[z]) + " " + hex(next) + " " + hex(next + zones[z].size() - 1) + " " + hex(types[z]) + " " + (dimension == 2 ? "2" : "0"), data);
    next += zones[z].size();
  }
  // the cells: 3D zones mixed (their element types listed), 2D zones of one type
  std::size_t cell = 0;
  for (std::size_t z = 0; z < sample.cellZones.size(); ++z)
  {
    const std::string header = std::string(z == 0 ? "1" : "10") + " " + hex(cell + 1) + " " + hex(cell + sample.cellZones[z].second) + " 1 ";
    std::string data;
    for (std::size_t c = cell; c < cell + sample.cellZones[z].second; ++c)
    {
      const int type = elementType(dimension, sample.cells[c].size());
      data += encoding == Encoding::Text ? std::to_string(type) + " " : bytes(static_cast<std::int32_t>(type));
    }
    out += dimension == 2 ? "(12 (" + header + std::to_string(elementType(2, sample.cells[cell].size())) + "))\n"
                          : section(encoding, 12, header + "0", data);
    cell += sample.cellZones[z].second;
  }
  for (int z = 0; z < 3; ++z)
  {
    out += "(45 (" + std::to_string(ids[z]) + " " + (z == 0 ? "interior " : "wall ") + names[z] + ")())\n";
  }
  out += "(45 (1 fluid " + sample.cellZones[0].first + ")())\n(45 (16 fluid " + sample.cellZones[1].first + ")())\n";
  return out;
}

// Whether the mesh's cells are the sample's, each as a cell of its type in VTK's order: the same
// faces, turned as VTK turns them (a positive volume: a tetrahedron's 0-1-2 turns about the normal
// towards 3, a pyramid's and a hexahedron's 0-1-2-3 towards 4, a wedge's 0-1-2 away from 3-4-5; 2D
// counter-clockwise).
bool cellsAreTheSamples(const SourceMesh& mesh, const Sample& sample)
{
  std::size_t cells = 0;
  for (const ElementBlock& block : mesh.blocks)
  {
    const std::size_t count = static_cast<std::size_t>(nodesPerCell(block.type));
    for (std::size_t e = 0; e < block.ids.size(); ++e)
    {
      const std::int64_t* nodes = block.nodes.data() + e * count;
      const Nodes& cell = sample.cells.at(static_cast<std::size_t>(block.ids[e] - 1));
      auto at = [&](int k) { return sample.nodes[static_cast<std::size_t>(nodes[k] - 1)]; };
      const double volume = block.type == CellType::Tetra ? tripleProduct(at(0), at(1), at(2), at(3))
        : block.type == CellType::Pyramid || block.type == CellType::Hexahedron ? tripleProduct(at(0), at(1), at(3), at(4))
        : block.type == CellType::Wedge ? -tripleProduct(at(0), at(1), at(2), at(3))
                                        : tripleProduct(at(0), at(1), at(2), Point{ at(0)[0], at(0)[1], 1 });
      if (cell.size() != count || block.type != typeOf(sample.dimension, count) ||
        faceSet(sample.dimension, nodes, count) != faceSet(sample.dimension, cell.data(), count) || !(volume > 0))
      {
        std::printf("cell %lld is not the sample's\n", static_cast<long long>(block.ids[e]));
        return false;
      }
      ++cells;
    }
  }
  return cells == sample.cells.size();
}

// The three files of a sample in dir: ASCII, single and double precision binary.
std::array<std::string, 3> threeFiles(const std::string& dir, const std::string& name, const Sample& sample)
{
  return { writeFile(dir + "/" + name + "-ascii.msh", fluentFile(sample, Encoding::Text)),
    writeFile(dir + "/" + name + "-single.msh", fluentFile(sample, Encoding::Single)),
    writeFile(dir + "/" + name + "-double.msh", fluentFile(sample, Encoding::Double)) };
}
} // namespace

TEST(AsciiMeshesRead)
{
  const std::string dir = folder("ascii");
  // 3D: a hexahedron and a wedge (zone "solid"), a pyramid and a tetrahedron (zone "cap")
  const Sample sample = solid();
  const fluent::MeshFile file = fluent::readFluent(writeFile(dir + "/solid.msh", fluentFile(sample, Encoding::Text)));
  const SourceMesh& mesh = file.mesh;
  CHECK(file.dimension == 3);
  CHECK(mesh.nodeIds == (Nodes{ 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12 }));
  for (std::size_t n = 0; n < sample.nodes.size(); ++n)
  {
    CHECK(position(mesh, static_cast<std::int64_t>(n + 1)) == sample.nodes[n]);
  }
  CHECK(file.nodeZones.size() == 2 && file.nodeZones[0].count == 8 && file.nodeZones[1].count == 4 &&
    file.nodeZones[0].precision == fluent::Precision::Text);
  CHECK(mesh.blocks.size() == 4);
  std::vector<std::string> names;
  for (const ElementBlock& block : mesh.blocks)
  {
    names.push_back(block.name);
  }
  CHECK(names == (std::vector<std::string>{ "hexahedral", "wedge", "pyramid", "tetrahedral" }));
  CHECK(cellsAreTheSamples(mesh, sample));
  // the hexahedron's first face in the file (the interior 5-8-7-6 under the pyramid, its c0) is its
  // VTK 0-1-2-3, 4-7 across the edges that leave it
  CHECK(!mesh.blocks.empty() && mesh.blocks[0].nodes == (Nodes{ 5, 8, 7, 6, 1, 4, 3, 2 }));
  // the cell zones element sets, the boundary face zones node sets, the interior one none
  CHECK(mesh.elementSets.size() == 2 && find(mesh.elementSets, "solid") && find(mesh.elementSets, "cap"));
  CHECK(find(mesh.elementSets, "solid") && find(mesh.elementSets, "solid")->ids == (Nodes{ 1, 2 }));
  CHECK(find(mesh.elementSets, "cap") && find(mesh.elementSets, "cap")->ids == (Nodes{ 3, 4 }));
  CHECK(mesh.nodeSets.size() == 2 && mesh.nodeSets[0].name == "bottom" && mesh.nodeSets[1].name == "skin");
  CHECK(find(mesh.nodeSets, "bottom") && find(mesh.nodeSets, "bottom")->ids == (Nodes{ 1, 2, 3, 4, 9, 10 }));
  CHECK(find(mesh.nodeSets, "skin") && find(mesh.nodeSets, "skin")->ids == (Nodes{ 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12 }));
  CHECK(mesh.warnings.empty());

  // 2D: two quadrilaterals and a triangle, counter-clockwise, z 0
  const Sample flat = plate();
  const fluent::MeshFile plateFile = fluent::readFluent(writeFile(dir + "/plate.msh", fluentFile(flat, Encoding::Text)));
  CHECK(plateFile.dimension == 2);
  CHECK(plateFile.mesh.xyz.size() == 21 && plateFile.mesh.xyz[20] == 0 && position(plateFile.mesh, 7) == (Point{ 3, 0.5, 0 }));
  CHECK(plateFile.mesh.blocks.size() == 2 && plateFile.mesh.blocks[0].name == "quadrilateral" && plateFile.mesh.blocks[1].name == "triangular");
  CHECK(cellsAreTheSamples(plateFile.mesh, flat));
  CHECK(find(plateFile.mesh.elementSets, "tip") && find(plateFile.mesh.elementSets, "tip")->ids == Nodes{ 3 });
  CHECK(find(plateFile.mesh.nodeSets, "bottom") && find(plateFile.mesh.nodeSets, "bottom")->ids == (Nodes{ 1, 2, 3 }));
  CHECK(plateFile.mesh.warnings.empty());

  // the layout: the node ids alone, and where their coordinates are
  const fluent::MeshFile layout = fluent::readFluentLayout(dir + "/solid.msh");
  CHECK(layout.mesh.nodeIds == mesh.nodeIds && layout.coordinates == file.coordinates && layout.mesh.xyz == mesh.xyz &&
    layout.mesh.blocks.empty() && layout.mesh.nodeSets.empty() && layout.mesh.elementSets.empty());
}

TEST(BinaryMeshesReadAsTheirText)
{
  // the coordinates are floats' (1.75, not 1.8): single precision reads them exactly too
  const std::string dir = folder("binary");
  for (const Sample& sample : { solid(), plate() })
  {
    const std::array<std::string, 3> files = threeFiles(dir, sample.dimension == 2 ? "plate" : "solid", sample);
    const fluent::MeshFile text = fluent::readFluent(files[0]);
    for (int f = 1; f < 3; ++f)
    {
      const fluent::MeshFile binary = fluent::readFluent(files[f]);
      CHECK(sameMesh(binary.mesh, text.mesh));
      CHECK(binary.mesh.warnings.empty());
      CHECK(binary.dimension == sample.dimension);
      CHECK(binary.nodeZones.size() == 2 && binary.nodeZones[1].precision == (f == 1 ? fluent::Precision::Single : fluent::Precision::Double));
      const fluent::MeshFile layout = fluent::readFluentLayout(files[f]);
      CHECK(layout.mesh.nodeIds == binary.mesh.nodeIds && layout.coordinates == binary.coordinates);
    }
  }
}

TEST(VariantKeepsEveryOtherByte)
{
  const std::string dir = folder("variant");
  for (const Sample& sample : { solid(), plate() })
  {
    const std::string name = sample.dimension == 2 ? "plate" : "solid";
    for (const std::string& source : threeFiles(dir, name, sample))
    {
      const fluent::MeshFile file = fluent::readFluent(source);
      const std::string stem = fs::path(source).stem().string();
      const std::size_t count = file.mesh.nodeIds.size();
      // the same coordinates: the same bytes
      file.writeVariant(dir + "/same/" + stem + ".msh", file.mesh.nodeIds.data(), file.mesh.xyz.data(), count, false);
      CHECK(readFile(dir + "/same/" + stem + ".msh") == readFile(source));
      // nodes 2 and 7 moved (2D: z too, which a 2D mesh does not hold), given in reverse order
      Nodes ids(file.mesh.nodeIds.rbegin(), file.mesh.nodeIds.rend());
      std::vector<double> xyz;
      for (std::size_t i = count; i-- > 0;)
      {
        xyz.insert(xyz.end(), file.mesh.xyz.begin() + 3 * i, file.mesh.xyz.begin() + 3 * i + 3);
      }
      const double moved2[3] = { 12, 0, -1e-17 }, moved7[3] = { 1.25, 1.0 / 3.0, sample.dimension == 2 ? 5.0 : 1.0 };
      std::copy(moved2, moved2 + 3, xyz.begin() + 3 * (count - 2));
      std::copy(moved7, moved7 + 3, xyz.begin() + 3 * (count - 7));
      const std::string target = dir + "/moved/" + stem + ".msh";
      file.writeVariant(target, ids.data(), xyz.data(), count, false);
      const std::string text = readFile(source), variant = readFile(target);
      const fluent::MeshFile again = fluent::readFluent(target);
      const Point at2 = position(again.mesh, 2), at7 = position(again.mesh, 7);
      if (file.nodeZones[0].precision == fluent::Precision::Text)
      {
        // only the changed numbers' texts change, to their shortest
        std::string expected = text;
        const bool flat = sample.dimension == 2;
        const std::string line2 = flat ? "1.0000000000e+00 0.0000000000e+00\n" : "1.0000000000e+00 0.0000000000e+00 0.0000000000e+00\n",
                          line7 = flat ? "3.0000000000e+00 5.0000000000e-01\n" : "1.0000000000e+00 1.0000000000e+00 1.0000000000e+00\n";
        expected.replace(expected.find(line7), line7.size(), flat ? "1.25 0.3333333333333333\n" : "1.25 0.3333333333333333 1.0000000000e+00\n");
        expected.replace(expected.find(line2), line2.size(), flat ? "12 0.0000000000e+00\n" : "12 0.0000000000e+00 -1e-17\n");
        CHECK(variant == expected);
      }
      else
      {
        // the same size, differing only in the moved numbers' bytes
        CHECK(testing::changedAtMost(text, variant, 4 * 8));
      }
      // read back exactly (single precision: as floats); a 2D mesh's z stays 0
      const bool single = file.nodeZones[0].precision == fluent::Precision::Single;
      for (int c = 0; c < 3; ++c)
      {
        const double expected2 = c == 2 && sample.dimension == 2 ? 0 : moved2[c], expected7 = c == 2 && sample.dimension == 2 ? 0 : moved7[c];
        CHECK(at2[c] == (single ? static_cast<float>(expected2) : expected2));
        CHECK(at7[c] == (single ? static_cast<float>(expected7) : expected7));
      }
      CHECK(single ? at7[1] != 1.0 / 3.0 : at7[1] == 1.0 / 3.0);
      CHECK(position(again.mesh, 3) == position(file.mesh, 3));
      SourceMesh unmoved = again.mesh;
      unmoved.xyz = file.mesh.xyz;
      CHECK(sameMesh(unmoved, file.mesh));
      // the layout alone writes the same variant
      const fluent::MeshFile layout = fluent::readFluentLayout(source);
      layout.writeVariant(dir + "/layout/" + stem + ".msh", ids.data(), xyz.data(), count, false);
      CHECK(readFile(dir + "/layout/" + stem + ".msh") == variant);
    }
  }
  // numbers on lines of their own choosing, the last closed by its list's parenthesis
  const fluent::MeshFile tight = fluent::readFluent(writeFile(dir + "/tight.msh", "(10 (1 1 2 1 3)(0 0\n0 1\t0 0))\n"));
  const double moved[6] = { 0, 0, 0, 1, 0, 2.5 };
  tight.writeVariant(dir + "/tight-moved.msh", tight.mesh.nodeIds.data(), moved, 2, false);
  CHECK(readFile(dir + "/tight-moved.msh") == "(10 (1 1 2 1 3)(0 0\n0 1\t0 2.5))\n");
}

TEST(VariantRefusesOtherDataAndNeverHalfWrites)
{
  const std::string dir = folder("refuse");
  for (const std::string& source : threeFiles(dir, "solid", solid()))
  {
    const fluent::MeshFile file = fluent::readFluent(source);
    const std::string name = fs::path(source).filename().string();
    // a coordinate beyond a float's range: refused where the file holds floats (nothing written:
    // checkVariantRefusals finds no dir/v/name), written where doubles
    std::vector<double> moved = file.mesh.xyz;
    moved[4] = 1e39;
    if (file.nodeZones[0].precision == fluent::Precision::Single)
    {
      CHECK(contains(testing::writeError(file, dir + "/v/" + name, file.mesh.nodeIds, moved),
        "node 2's coordinate 1e+39 is beyond the range of the single-precision numbers its zone holds"));
    }
    else
    {
      file.writeVariant(dir + "/wide/" + name, file.mesh.nodeIds.data(), moved.data(), moved.size() / 3, false);
      CHECK(position(fluent::readFluent(dir + "/wide/" + name).mesh, 2)[1] == 1e39);
    }
    testing::checkVariantRefusals(file, source, dir, "(0 \"edited\")\n");
  }
}

TEST(CaseFileKeepsItsSettings)
{
  // a case file: the mesh among settings (Scheme lists, strings with parentheses and quotes, a
  // zone's boundary conditions in its 39 section) and a binary section of another kind, whose
  // bytes hold parentheses: read as the mesh alone, written back byte for byte
  const std::string dir = folder("case");
  std::string binary;
  for (const std::int32_t value : { 1, 0x28, 0x29, 0x2929, 2 })
  {
    binary += bytes(value);
  }
  const std::string settings = "(1 \"Fluent (R) 3D, double precision\")\n(4 (60 0 0 1 2 4 4 4 8 8 8 4))\n(37 (\n(time/nstep 0)\n"
                               "(case-config ((rp-seg? . #t) (rp-axi? . #f)))\n(note \"a string with ) and ( and \\\" in it\")\n))\n"
                               "(2058 (1 2 3 4)(" +
    binary + ")\nEnd of Binary Section   2058)\n(39 (16 fluid cap 1)(\n(material . air)\n(sources? . #f)\n))\n";
  for (const Encoding encoding : { Encoding::Text, Encoding::Double })
  {
    std::string text = fluentFile(solid(), encoding);
    text.insert(text.find("(45 "), settings);
    const std::string name = encoding == Encoding::Text ? "ascii" : "binary";
    const std::string source = writeFile(dir + "/" + name + ".cas", text);
    const fluent::MeshFile file = fluent::readFluent(source);
    const fluent::MeshFile mesh = fluent::readFluent(writeFile(dir + "/" + name + ".msh", fluentFile(solid(), encoding)));
    CHECK(sameMesh(file.mesh, mesh.mesh));
    CHECK(file.mesh.warnings.empty());
    std::vector<double> xyz = file.mesh.xyz;
    xyz[3 * 11] = 1.625;
    file.writeVariant(dir + "/moved-" + name + ".cas", file.mesh.nodeIds.data(), xyz.data(), xyz.size() / 3, false);
    const std::string variant = readFile(dir + "/moved-" + name + ".cas");
    CHECK(contains(variant, settings));
    CHECK(position(fluent::readFluent(dir + "/moved-" + name + ".cas").mesh, 12)[0] == 1.625);
    if (encoding == Encoding::Text)
    {
      std::string expected = text;
      const std::string line = "1.5000000000e+00 5.0000000000e-01 1.7500000000e+00\n";
      expected.replace(expected.find(line), line.size(), "1.625 5.0000000000e-01 1.7500000000e+00\n");
      CHECK(variant == expected);
    }
  }
}

TEST(CellsThatCannotBeRebuiltAreLeftOut)
{
  // a hexahedron whose top is split in two triangles (7 faces: a polyhedron), and in an inactive
  // zone (type 20 hexadecimal: 32, the parents of adapted cells) a tetrahedron on one of them;
  // their nodes are read, the zones' element sets are empty, a variant moves every node
  const std::string dir = folder("left");
  const std::string source = writeFile(dir + "/left.msh",
    "(0 \"left out\")\n(2 3)\n(10 (1 1 9 1 3)(\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n0.5 0.5 2\n))\n" // lines 1-13
    "(12 (1 1 1 1 0)(\n7))\n"                                                                                            // 14-15
    "(12 (2 2 2 20 2))\n"                                                                                                // 16
    "(13 (3 1 1 2 0)(\n3 5 7 6 1 2\n))\n"
    "(13 (4 2 a 3 0)(\n4 1 2 3 4 1 0\n4 1 5 6 2 1 0\n4 2 6 7 3 1 0\n4 3 7 8 4 1 0\n4 4 8 5 1 1 0\n3 5 8 7 1 0\n3 5 9 6 2 0\n"
    "3 6 9 7 2 0\n3 5 7 9 2 0\n))\n"
    "(45 (1 fluid box)())\n(45 (2 fluid parent)())\n");
  const fluent::MeshFile file = fluent::readFluent(source);
  const SourceMesh& mesh = file.mesh;
  for (const std::string& warning : mesh.warnings)
  {
    std::printf("warning: %s\n", warning.c_str());
  }
  CHECK(mesh.nodeIds.size() == 9 && mesh.blocks.empty());
  CHECK(mesh.warnings.size() == 2);
  CHECK(mesh.warnings.size() == 2 && contains(mesh.warnings[0], "left.msh:14: cell zone box (1): 1 of its 1 cells are not tetrahedra, "
                                                                 "pyramids, wedges or hexahedra (polyhedra, cells split by hanging nodes"));
  CHECK(mesh.warnings.size() == 2 && contains(mesh.warnings[1], "left.msh:16: cell zone parent (2) is inactive (the parents of adapted "
                                                                 "cells): its 1 cells are left out (their nodes are read and move with the rest)"));
  CHECK(mesh.elementSets.size() == 2 && mesh.elementSets[0].ids.empty() && mesh.elementSets[1].ids.empty());
  CHECK(mesh.nodeSets.size() == 1 && mesh.nodeSets[0].name == "zone 4" && mesh.nodeSets[0].ids.size() == 9);
  std::vector<double> xyz = mesh.xyz;
  xyz[3 * 8 + 2] = 3;
  file.writeVariant(dir + "/moved.msh", mesh.nodeIds.data(), xyz.data(), 9, false);
  CHECK(position(fluent::readFluent(dir + "/moved.msh").mesh, 9) == (Point{ 0.5, 0.5, 3 }));
}

TEST(BadFilesNameTheFileAndTheLine)
{
  const std::string dir = folder("bad");
  // a tetrahedron: lines 1-7 its nodes, 8 its cell zone, 9-14 its faces
  const std::string nodes = "(2 3)\n(10 (1 1 4 1 3)(\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n))\n";
  const std::string cells = "(12 (1 1 1 1 2))\n";
  auto faces = [](const std::string& last) { return "(13 (2 1 4 3 3)(\n1 2 3 1 0\n1 4 2 1 0\n2 4 3 1 0\n" + last + "\n))\n"; };
  const std::string good = nodes + cells + faces("1 3 4 1 0");
  CHECK(readError(writeFile(dir + "/good.msh", good)).empty());
  auto error = [&](const std::string& name, const std::string& text) { return readError(writeFile(dir + "/" + name, text)); };
  CHECK(contains(error("hex.msh", nodes + cells + faces("1 3 4g 1 0")), "hex.msh:13: \"4g\" is not a node index (a hexadecimal number)"));
  CHECK(contains(error("real.msh", "(10 (1 1 2 1 3)(\n0 0 0\n1 0.0.0 0\n))\n"), "real.msh:3: node 2's coordinate \"0.0.0\" is not a finite number"));
  CHECK(contains(error("nan.msh", "(10 (1 1 2 1 3)(\n0 0 0\n1 nan 0\n))\n"), "nan.msh:3: node 2's coordinate \"nan\" is not a finite number"));
  CHECK(contains(error("inf.msh", "(10 (1 1 1 1 3)(\n0 1e999 0\n))\n"), "inf.msh:2: node 1's coordinate \"1e999\""));
  // cut short: inside the data, after them (the parentheses do not balance)
  CHECK(contains(error("cut.msh", "(10 (1 1 4 1 3)(\n0.000000 0.000000 0.000000\n1.000000 0.000000 0.000000\n"),
    "cut.msh:3: the file ends inside section 10, which starts at line 1 (the file is cut short, or its parentheses do not balance)"));
  CHECK(contains(error("open.msh", nodes + cells + "(13 (2 1 4 3 3)(\n1 2 3 1 0\n1 4 2 1 0\n2 4 3 1 0\n1 3 4 1 0\n)\n"),
    "open.msh:14: the file ends inside section 13, which starts at line 9"));
  CHECK(contains(error("close.msh", good + ")\n"), "close.msh:15: \")\" closes no section (the parentheses do not balance)"));
  CHECK(contains(error("outside.msh", good + "hello\n"), "outside.msh:15: text outside a section"));
  CHECK(contains(error("index.msh", "(x 3)\n"), "index.msh:1: \"(\" not followed by a section index"));
  CHECK(contains(error("header.msh", "(10 1 1 4 1 3)\n"), "header.msh:1: section 10 without its header (zone first last type [ND])"));
  CHECK(contains(error("short.msh", "(10 (1 1 4))\n"), "short.msh:1: a header of 3 numbers where (zone first last type [ND]) is expected"));
  // counts: the data's, the rest of the file's
  CHECK(contains(error("few.msh", "(10 (1 1 4 1 3)(\n0.00000 0.00000 0.00000\n1.00000 0.00000 0.00000\n0.00000 1.00000 0.00000\n))\n"),
    "few.msh:5: node zone 1 ends after 9 coordinates; its 4 nodes have 12"));
  CHECK(contains(error("many.msh", "(10 (1 1 1 1 3)(\n0 0 0\n1 0 0\n))\n"), "many.msh:3: more data than the header's 1 nodes' coordinates"));
  CHECK(contains(error("huge.msh", "(10 (1 1 ffffffffff 1 3)(\n0 0 0\n))\n"),
    "huge.msh:1: 1099511627775 nodes: more than the rest of the file holds"));
  CHECK(contains(error("range.msh", "(10 (1 5 2 1 3)(\n0 0 0\n))\n"), "range.msh:1: node zone 1: its indices 5 to 2 are not a range from 1 up"));
  CHECK(contains(error("dimension.msh", "(2 2)\n(10 (1 1 1 1 3)(\n0 0 0\n))\n"), "dimension.msh:2: dimension 3 in a mesh of dimension 2"));
  CHECK(contains(error("facetype.msh", nodes + "(13 (2 1 1 3 7)(\n1 2 3 1 0\n))\n"),
    "facetype.msh:8: face type 7 is none of 0 (mixed), 2 (line), 3 (triangle), 4 (quadrilateral), 5 (polygon)"));
  CHECK(contains(error("fewfaces.msh", nodes + cells + "(13 (2 1 4 3 3)(\n1  2  3  1  0\n1  4  2  1  0\n2  4  3  1  0\n))\n"),
    "fewfaces.msh:13: the data end where the header's counts want a node index"));
  // what the faces refer to, nodes defined twice
  CHECK(contains(error("node.msh", nodes + cells + faces("1 3 5 1 0")), "node.msh:13: face 4 refers to node 5, which no node zone holds"));
  CHECK(contains(error("cell.msh", nodes + cells + faces("1 3 4 2 0")), "cell.msh:13: face 4 refers to cell 2, which no cell zone holds"));
  CHECK(contains(error("twice.msh", nodes + "(10 (2 4 4 1 3)(\n1 1 1\n))\n"), "twice.msh:9: node 4 is defined twice"));
  CHECK(contains(error("overlap.msh", nodes + cells + "(12 (3 1 1 1 2))\n" + faces("1 3 4 1 0")), "overlap.msh:9: the cells of zone 3 and of zone 1 overlap"));
  CHECK(contains(error("name.msh", good + "(45 (a fluid box)())\n"), "name.msh:15: a zone's name is not given as (id type name), its id decimal"));
  CHECK(contains(error("nonodes.msh", "(0 \"no nodes\")\n(10 (0 1 4 0 3))\n"), "nonodes.msh: has no node zone"));
  CHECK(contains(error("none.msh", ""), "none.msh: has no node zone"));
  CHECK(contains(readError(dir + "/missing.msh"), "missing.msh: cannot be read"));
  // binary: the section and the byte
  const std::string header = "(3010 (1 1 2 1 3)(";
  const std::string end = ")\nEnd of Binary Section   3010)\n";
  std::string two;
  for (const double value : { 0.0, 0.0, 0.0, 1.0, 0.0, 0.0 })
  {
    two += bytes(value);
  }
  CHECK(readError(writeFile(dir + "/bgood.msh", header + two + end)).empty());
  CHECK(contains(error("bnan.msh", header + two.substr(0, 32) + bytes(std::numeric_limits<double>::quiet_NaN()) + two.substr(40) + end),
    "bnan.msh: section 3010, byte 42: node 2's coordinate nan is not a finite number"));
  CHECK(contains(error("bshort.msh", header + two.substr(0, 40)), "bshort.msh: section 3010, byte 17: 2 nodes: more than the rest of the file holds"));
  CHECK(contains(error("blong.msh", header + two + bytes(0.0) + end),
    "blong.msh: section 3010, byte 66: the binary data do not end where the header's 2 nodes' coordinates end"));
  CHECK(contains(error("bmarker.msh", header + two + ")\nEnd of Binary Section   2010)\n"),
    "bmarker.msh: section 3010, byte 92: not the end of binary section 3010 that the data lead to"));
  CHECK(contains(error("bcut.msh", header + two + ")\n"), "bcut.msh: section 3010, byte 68: the file ends inside section 3010, which starts at byte 0"));
  std::string face;
  for (const std::int32_t value : { 1, 2, -3, 1, 0 })
  {
    face += bytes(value);
  }
  CHECK(contains(error("bface.msh", header + two + end + "(2013 (2 1 1 3 3)(" + face + ")\nEnd of Binary Section   2013)\n"),
    "bface.msh: section 2013, byte 124: a node index -3 is negative"));
}

TEST(FluentAndGmshMeshesAreToldApart)
{
  CHECK(fluent::isFluent("(0 \"FOAM to Fluent Mesh File\")\n"));
  CHECK(fluent::isFluent("\n  (1 \"TGrid\")"));
  CHECK(fluent::isFluent("(2 3)\n"));
  CHECK(fluent::isFluent("(10 (0 1 372 0 3))"));
  CHECK(fluent::isFluent("(3010(1 1 2 1 3)"));
  CHECK(!fluent::isFluent("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n"));
  CHECK(!fluent::isFluent("*HEADING\n"));
  CHECK(!fluent::isFluent("(x 1)"));
  CHECK(!fluent::isFluent("(10"));
  CHECK(!fluent::isFluent(""));
  CHECK(!gmsh::isMsh("(0 \"FOAM to Fluent Mesh File\")\n"));
  CHECK(gmsh::isMsh("$MeshFormat\n4.1 0 8\n"));
  // each reader refuses the other's file
  const std::string dir = folder("apart");
  const std::string fluentPath = writeFile(dir + "/fluent.msh", fluentFile(plate(), Encoding::Text));
  const std::string gmshPath = writeFile(dir + "/gmsh.msh", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n1\n1 0 0 0\n$EndNodes\n");
  CHECK(contains(readError(gmshPath), "gmsh.msh:1: text outside a section"));
  CHECK(contains(testing::readError([&] { gmsh::readMsh(fluentPath); }), "does not start with $MeshFormat"));
}

TEST_MAIN
