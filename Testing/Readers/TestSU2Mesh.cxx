// SU2 meshes without VTK: 2D and 3D files read (points by index, NELEM='s cells, markers as node
// sets, several zones); a variant keeps every byte but the moved coordinates; VTK's node orders, the
// prism's as Gmsh writes it; bad files give an error naming the file and the line.
#include "../TestHarness.h"
#include "Common/TextFile.h"
#include "FormatFiles.h"
#include "SU2/SU2Mesh.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using namespace mlsformats;

namespace
{
using testing::contains;
using testing::find;
using testing::Point;
using testing::position;
using testing::tripleProduct;
using testing::writeError;
using testing::writeFile;

const testing::TestFolders folder{ "su2" };
const testing::ReadErrors readError{ su2::readSu2 };

// A 2D mesh as SU2's documentation writes one, with comments, tabs, indices on some lines only and
// numbers that are not their shortest text: two triangles and a quadrilateral, two markers.
const char* const plane = "%\n% a plane: two triangles and a quadrilateral\n%\nNDIME= 2\n"
                          "NPOIN= 6\n0.0 0.0 0\n1.0\t0.0\t1\n2 0 2\n0 1 3\n1 1e0 4\n2 1\n"
                          "NELEM= 3\n5 0 1 4 0\n5 0 4 3\n9\t1\t2\t5\t4\t2\n"
                          "NMARK= 2\nMARKER_TAG= lower\nMARKER_ELEMS= 2\n3 0 1\n3 1 2\nMARKER_TAG= upper wall\nMARKER_ELEMS= 2\n3 5 4\n3 4 3 1\n";

// A 3D mesh in the order Gmsh writes (NELEM= before NPOIN=): a hexahedron and a pyramid on it; NPOIN=
// gives the points a partition owns (the last is another's); an angle offset and an FFD box (as
// SU2_DEF writes them) are not the mesh's.
const char* const solid = "NDIME= 3\nAOA_OFFSET= 0.0\n"
                          "NELEM= 2\n12 0 1 2 3 4 5 6 7 0\n14 4 5 6 7 8 1\n"
                          "NPOIN= 10 9\n0 0 0 0\n1 0 0 1\n1 1 0 2\n0 1 0 3\n0 0 1 4\n1 0 1 5\n1 1 1 6\n0 1 1 7\n0.5 0.5 1.5 8\n2 2 2 9\n"
                          "NMARK= 3\nMARKER_TAG= bottom\nMARKER_ELEMS= 1\n9 0 3 2 1\n"
                          "MARKER_TAG= top\nMARKER_ELEMS= 4\n5 4 5 8\n5 5 6 8\n5 6 7 8\n5 7 4 8\n"
                          "MARKER_TAG= none\nMARKER_ELEMS= 0\n"
                          "FFD_NBOX= 1\nFFD_NLEVEL= 1\nFFD_TAG= box\nFFD_CORNER_POINTS= 2\n-0.1 -0.1 -0.1\n1.1 1.1 1.6\n"
                          "FFD_SURFACE_POINTS= 1\nbottom 0 0.1 0.1 0.1\n";

// Two zones of one triangle each (a fluid and a solid, say): each numbers its points from 0, and
// both have a marker "interface".
const char* const zones = "NZONE= 2\n\nIZONE= 1\nNDIME= 2\nNELEM= 2\n5 0 1 2\n5 0 2 3\nNPOIN= 4\n0 0\n1 0\n1 1\n0 1\n"
                          "NMARK= 2\nMARKER_TAG= interface\nMARKER_ELEMS= 1\n3 1 2\nMARKER_TAG= wall\nMARKER_ELEMS= 1\n3 0 1\n\n"
                          "IZONE= 2\nNDIME= 2\nNELEM= 1\n5 0 1 2\nNPOIN= 3\n1 0\n2 0\n1 1\n"
                          "NMARK= 2\nMARKER_TAG= interface\nMARKER_ELEMS= 1\n3 2 0\nMARKER_TAG= farfield\nMARKER_ELEMS= 1\n3 0 1\n";

// text with its first from replaced by to.
std::string replaced(std::string text, const std::string& from, const std::string& to)
{
  const std::size_t at = text.find(from);
  CHECK(at != std::string::npos);
  return at == std::string::npos ? text : text.replace(at, from.size(), to);
}

// Whether dir holds nothing but the files named (no variant, nothing written aside).
bool holdsOnly(const std::string& dir, std::vector<std::string> names)
{
  std::vector<std::string> found;
  for (const fs::directory_entry& entry : fs::directory_iterator(dir))
  {
    found.push_back(entry.path().filename().string());
  }
  std::sort(found.begin(), found.end());
  std::sort(names.begin(), names.end());
  return found == names;
}
} // namespace

TEST(Reads2DMesh)
{
  const std::string dir = folder("plane");
  const su2::MeshFile file = su2::readSu2(writeFile(dir + "/plane.su2", plane));
  const SourceMesh& mesh = file.mesh;
  // the points by their index, from 0; z is 0
  CHECK(mesh.nodeIds == (std::vector<std::int64_t>{ 0, 1, 2, 3, 4, 5 }));
  CHECK(mesh.xyz == (std::vector<double>{ 0, 0, 0, 1, 0, 0, 2, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0 }));
  CHECK(file.zones.size() == 1 && file.zones[0].number == 1 && file.zones[0].dimension == 2 && file.zones[0].firstNode == 0);
  // NELEM='s elements are the cells, by their index; the markers' are not
  CHECK(mesh.blocks.size() == 2);
  if (mesh.blocks.size() == 2)
  {
    CHECK(mesh.blocks[0].name == "triangle" && mesh.blocks[0].type == CellType::Triangle);
    CHECK(mesh.blocks[0].ids == (std::vector<std::int64_t>{ 0, 1 }) && mesh.blocks[0].nodes == (std::vector<std::int64_t>{ 0, 1, 4, 0, 4, 3 }));
    CHECK(mesh.blocks[1].name == "quadrilateral" && mesh.blocks[1].type == CellType::Quad);
    CHECK(mesh.blocks[1].ids == std::vector<std::int64_t>{ 2 } && mesh.blocks[1].nodes == (std::vector<std::int64_t>{ 1, 2, 5, 4 }));
  }
  // each marker a node set, its tag without blanks (as SU2 reads it)
  CHECK(mesh.nodeSets.size() == 2);
  CHECK(find(mesh.nodeSets, "lower") && find(mesh.nodeSets, "lower")->ids == (std::vector<std::int64_t>{ 0, 1, 2 }));
  CHECK(find(mesh.nodeSets, "upperwall") && find(mesh.nodeSets, "upperwall")->ids == (std::vector<std::int64_t>{ 3, 4, 5 }));
  CHECK(mesh.elementSets.empty() && mesh.warnings.empty());
  // the layout: the ids and where the coordinates are
  const su2::MeshFile layout = su2::readSu2Layout(dir + "/plane.su2");
  CHECK(layout.mesh.nodeIds == mesh.nodeIds && layout.coordinates == file.coordinates && layout.mesh.xyz == mesh.xyz &&
    layout.mesh.blocks.empty() && layout.mesh.nodeSets.empty());
  CHECK(su2::isSu2(plane) && su2::isSu2("NDIME= 3\n") && su2::isSu2("\r\n  % comment\r\nNDIME=2\r\n") && su2::isSu2("NZONE= 2\nIZONE= 1\n"));
  CHECK(!su2::isSu2("NPOIN= 3\n") && !su2::isSu2("% only a comment\n") && !su2::isSu2("$MeshFormat\n") && !su2::isSu2(""));
}

TEST(Reads3DMesh)
{
  const std::string dir = folder("solid");
  const su2::MeshFile file = su2::readSu2(writeFile(dir + "/solid.su2", solid));
  const SourceMesh& mesh = file.mesh;
  // the ten points, the one another partition owns too
  CHECK(mesh.nodeIds.size() == 10 && mesh.nodeIds[9] == 9 && mesh.xyz.size() == 30);
  CHECK(position(mesh, 8) == (Point{ 0.5, 0.5, 1.5 }) && position(mesh, 9) == (Point{ 2, 2, 2 }));
  CHECK(mesh.blocks.size() == 2);
  if (mesh.blocks.size() == 2)
  {
    CHECK(mesh.blocks[0].name == "hexahedron" && mesh.blocks[0].type == CellType::Hexahedron && mesh.blocks[0].ids == std::vector<std::int64_t>{ 0 });
    CHECK(mesh.blocks[0].nodes == (std::vector<std::int64_t>{ 0, 1, 2, 3, 4, 5, 6, 7 }));
    CHECK(mesh.blocks[1].name == "pyramid" && mesh.blocks[1].type == CellType::Pyramid && mesh.blocks[1].ids == std::vector<std::int64_t>{ 1 });
    CHECK(mesh.blocks[1].nodes == (std::vector<std::int64_t>{ 4, 5, 6, 7, 8 }));
  }
  CHECK(mesh.nodeSets.size() == 3);
  CHECK(find(mesh.nodeSets, "bottom") && find(mesh.nodeSets, "bottom")->ids == (std::vector<std::int64_t>{ 0, 1, 2, 3 }));
  CHECK(find(mesh.nodeSets, "top") && find(mesh.nodeSets, "top")->ids == (std::vector<std::int64_t>{ 4, 5, 6, 7, 8 }));
  CHECK(find(mesh.nodeSets, "none") && find(mesh.nodeSets, "none")->ids.empty());
  CHECK(mesh.elementSets.empty() && mesh.warnings.empty());
}

TEST(NodeOrdersAreVtks)
{
  // a prism, a hexahedron, a pyramid and a tetrahedron as Gmsh 4.8 writes them to .su2 (its lines and
  // its points' coordinates, renumbered): read as they are, they are VTK's (vtkCellValidator finds
  // them valid): the prism's 0-1-2 turns away from 3-4-5, the hexahedron's and the pyramid's base
  // 0-1-2-3 towards the top, the tetrahedron's 0-1-2 towards 3
  const std::string dir = folder("orders");
  const su2::MeshFile file = su2::readSu2(writeFile(dir + "/gmsh.su2",
    "NDIME= 3\nNELEM= 4\n13 0 1 2 3 4 5 0\n12 6 7 8 9 10 11 12 13 1\n14 14 15 16 17 18 2\n10 19 20 21 22 3\nNPOIN= 23\n"
    "1 0.4999999999986921 0 0\n0.6479166666669071 0.6437499999998398 0 1\n1 1 0 2\n1 0.4999999999986921 0.5 3\n"
    "0.6479166666669071 0.6437499999998398 0.5 4\n1 1 0.5 5\n1 0 0 6\n1.5 0 0 7\n1.5 0.4999999999986921 0 8\n1 0.4999999999986921 0 9\n"
    "1 0 0.5 10\n1.5 0 0.5 11\n1.5 0.4999999999986921 0.5 12\n1 0.4999999999986921 0.5 13\n0 0 1 14\n0.4999999999986921 0 1 15\n"
    "0.5000000000003758 0.5000000000003758 1 16\n0 0.5000000000020595 1 17\n0.249999999999767 0.2500000000006088 1.225000000000169 18\n"
    "1 0.2487199586491353 1.491556188445461 19\n0.7512800416906722 0 1.491556189205616 20\n0.7576802459286843 0 1.757680244063145 21\n"
    "0.4827009056079409 0.5172990943849747 1.517241298243557 22\nNMARK= 0\n"));
  const SourceMesh& mesh = file.mesh;
  CHECK(mesh.blocks.size() == 4 && mesh.warnings.empty());
  if (mesh.blocks.size() != 4)
  {
    return;
  }
  const ElementBlock &prism = mesh.blocks[0], &hexahedron = mesh.blocks[1], &pyramid = mesh.blocks[2], &tetra = mesh.blocks[3];
  CHECK(prism.type == CellType::Wedge && prism.name == "prism" && prism.nodes == (std::vector<std::int64_t>{ 0, 1, 2, 3, 4, 5 }));
  CHECK(hexahedron.type == CellType::Hexahedron && pyramid.type == CellType::Pyramid && tetra.type == CellType::Tetra);
  auto sign = [&](const ElementBlock& block, std::array<int, 4> corners) {
    return tripleProduct(position(mesh, block.nodes[corners[0]]), position(mesh, block.nodes[corners[1]]),
      position(mesh, block.nodes[corners[2]]), position(mesh, block.nodes[corners[3]]));
  };
  CHECK(sign(prism, { 0, 1, 2, 3 }) < 0 && sign(prism, { 3, 4, 5, 0 }) > 0);
  CHECK(sign(hexahedron, { 0, 1, 3, 4 }) > 0 && sign(hexahedron, { 4, 5, 7, 0 }) < 0);
  CHECK(sign(pyramid, { 0, 1, 3, 4 }) > 0 && sign(pyramid, { 2, 3, 1, 4 }) > 0);
  CHECK(sign(tetra, { 0, 1, 2, 3 }) > 0);
}

TEST(VariantKeepsEveryOtherByte)
{
  const std::string dir = folder("variant");
  // 2D, with "\r\n" and tabs: node 1's x and node 3's y move (node 3 has no index), node 2's z is
  // not written (a 2D file has none); the ids come in reverse order
  const std::string planeText = "NDIME= 2\r\nNPOIN= 4\r\n0.0 0.0 0\r\n1.0\t0.0\t1\r\n1 1e0 2\r\n0 1\r\nNELEM= 2\r\n5 0 1 2 0\r\n"
                                "5 0 2 3 1\r\nNMARK= 1\r\nMARKER_TAG= wall\r\nMARKER_ELEMS= 1\r\n3 0 1\r\n";
  const std::string source = writeFile(dir + "/plane.su2", planeText);
  const su2::MeshFile file = su2::readSu2(source);
  file.writeVariant(dir + "/same/plane.su2", file.mesh.nodeIds.data(), file.mesh.xyz.data(), 4, false);
  CHECK(readFile(dir + "/same/plane.su2") == planeText);
  const std::vector<std::int64_t> ids{ 3, 2, 1, 0 };
  const std::vector<double> xyz{ 0, 1.0 / 3.0, 0, 1, 1, 5, 1.25, 0, 0, 0, 0, 0 };
  file.writeVariant(dir + "/moved/plane.su2", ids.data(), xyz.data(), 4, false);
  const std::string expected =
    replaced(replaced(planeText, "1.0\t0.0\t1\r\n", "1.25\t0.0\t1\r\n"), "0 1\r\nNELEM", "0 0.3333333333333333\r\nNELEM");
  CHECK(readFile(dir + "/moved/plane.su2") == expected);
  CHECK(su2::readSu2(dir + "/moved/plane.su2").mesh.xyz == (std::vector<double>{ 0, 0, 0, 1.25, 0, 0, 1, 1, 0, 0, 1.0 / 3.0, 0 }));
  // the layout writes the same
  su2::readSu2Layout(source).writeVariant(dir + "/layout/plane.su2", ids.data(), xyz.data(), 4, false);
  CHECK(readFile(dir + "/layout/plane.su2") == expected);

  // 3D: the apex moves, and the last point by a tiny step; the index and the FFD box stay
  const su2::MeshFile solidFile = su2::readSu2(writeFile(dir + "/solid.su2", solid));
  std::vector<double> moved = solidFile.mesh.xyz;
  moved[3 * 8 + 2] = 2;
  moved[3 * 9] = 2 + 4.440892098500626e-16;
  solidFile.writeVariant(dir + "/moved/solid.su2", solidFile.mesh.nodeIds.data(), moved.data(), 10, false);
  const std::string solidExpected = replaced(replaced(solid, "0.5 0.5 1.5 8\n", "0.5 0.5 2 8\n"), "2 2 2 9\n", "2.0000000000000004 2 2 9\n");
  CHECK(readFile(dir + "/moved/solid.su2") == solidExpected);
  CHECK(su2::readSu2(dir + "/moved/solid.su2").mesh.xyz == moved);
}

TEST(VariantRefusals)
{
  const std::string dir = folder("refusals");
  const std::string source = writeFile(dir + "/plane.su2", plane);
  const su2::MeshFile file = su2::readSu2(source);
  // the source itself by a third spelling (the other refusals: checkVariantRefusals)
  CHECK(contains(writeError(file, dir + "/sub/../plane.su2", file.mesh.nodeIds, file.mesh.xyz, true), "is the source mesh"));
  CHECK(readFile(source) == plane);
  testing::checkVariantRefusals(file, source, dir, "% changed\n");
  // nothing written but the variant written on purpose (dir/v/plane.su2), nothing left aside
  CHECK(holdsOnly(dir, { "plane.su2", "v" }) && holdsOnly(dir + "/v", { "plane.su2" }));
}

TEST(ZonesNumberTheirPointsOnward)
{
  const std::string dir = folder("zones");
  const std::string source = writeFile(dir + "/zones.su2", zones);
  const su2::MeshFile file = su2::readSu2(source);
  const SourceMesh& mesh = file.mesh;
  // zone 2's points and elements go on from zone 1's
  CHECK(mesh.nodeIds == (std::vector<std::int64_t>{ 0, 1, 2, 3, 4, 5, 6 }));
  CHECK(file.zones.size() == 2 && file.zones[1].number == 2 && file.zones[1].firstNode == 4);
  CHECK(mesh.blocks.size() == 1 && mesh.blocks[0].ids == (std::vector<std::int64_t>{ 0, 1, 2 }) &&
    mesh.blocks[0].nodes == (std::vector<std::int64_t>{ 0, 1, 2, 0, 2, 3, 4, 5, 6 }));
  // a tag of both zones is told apart by its zone; each zone is a set
  std::vector<std::string> names;
  for (const NamedSet& set : mesh.nodeSets)
  {
    names.push_back(set.name);
  }
  CHECK(names == (std::vector<std::string>{ "interface (zone 1)", "wall", "interface (zone 2)", "farfield", "zone 1", "zone 2" }));
  CHECK(find(mesh.nodeSets, "interface (zone 1)") && find(mesh.nodeSets, "interface (zone 1)")->ids == (std::vector<std::int64_t>{ 1, 2 }));
  CHECK(find(mesh.nodeSets, "interface (zone 2)") && find(mesh.nodeSets, "interface (zone 2)")->ids == (std::vector<std::int64_t>{ 4, 6 }));
  CHECK(find(mesh.nodeSets, "zone 2") && find(mesh.nodeSets, "zone 2")->ids == (std::vector<std::int64_t>{ 4, 5, 6 }));
  CHECK(mesh.elementSets.size() == 2 && mesh.elementSets[0].name == "zone 1" && mesh.elementSets[0].ids == (std::vector<std::int64_t>{ 0, 1 }) &&
    mesh.elementSets[1].ids == std::vector<std::int64_t>{ 2 });
  // zone 2's point 1 moves
  std::vector<double> moved = mesh.xyz;
  moved[3 * 5] = 2.5;
  file.writeVariant(dir + "/moved/zones.su2", mesh.nodeIds.data(), moved.data(), 7, false);
  CHECK(readFile(dir + "/moved/zones.su2") == replaced(zones, "2 0\n1 1\nNMARK", "2.5 0\n1 1\nNMARK"));
  // zones that do not add up
  const std::string zone2 = "IZONE= 2\nNDIME= 2\nNELEM= 0\nNPOIN= 0\n";
  CHECK(contains(readError(writeFile(dir + "/nonzone.su2", "IZONE= 1\nNDIME= 2\n")), "nonzone.su2:1: IZONE= without NZONE= at the start of the file"));
  CHECK(contains(readError(writeFile(dir + "/three.su2", std::string("NZONE= 3\n") + (zones + 8))),
    "three.su2:1: NZONE= 3 announces 3 zones; the file has 2 (IZONE=)"));
  CHECK(contains(readError(writeFile(dir + "/before.su2", "NZONE= 2\nNDIME= 2\nNPOIN= 0\n")), "before.su2:2: NDIME= before the first IZONE= of a file of NZONE= 2"));
  CHECK(contains(readError(writeFile(dir + "/range.su2", "NZONE= 2\nIZONE= 3\nNDIME= 2\n")), "range.su2:2: IZONE= 3 is not a zone of NZONE= 2 (1 to 2)"));
  CHECK(contains(readError(writeFile(dir + "/twice.su2", "NZONE= 2\n" + zone2 + zone2)), "twice.su2:6: a second IZONE= 2"));
  CHECK(contains(readError(writeFile(dir + "/lacks.su2", "NZONE= 2\n" + zone2 + "IZONE= 1\nNDIME= 2\nNELEM= 0\n")),
    "lacks.su2:6: zone 1 has no NPOIN="));
}

TEST(UnknownElementTypesAreToldNotDropped)
{
  // polygons (VTK's 7) are not SU2's: left out with a warning naming the line of the first, as is
  // a marker's vertex; the others are read
  const std::string dir = folder("unknown");
  const su2::MeshFile file = su2::readSu2(writeFile(dir + "/unknown.su2",
    "NDIME= 2\nNPOIN= 4\n0 0\n1 0\n1 1\n0 1\nNELEM= 4\n5 0 1 2\n7 4 0 1 2 3\n7 3 0 1 2\n9 0 1 2 3\n"
    "NMARK= 1\nMARKER_TAG= wall\nMARKER_ELEMS= 2\n1 3\n3 0 1\n"));
  const SourceMesh& mesh = file.mesh;
  for (const std::string& warning : mesh.warnings)
  {
    std::printf("warning: %s\n", warning.c_str());
  }
  CHECK(mesh.warnings.size() == 2);
  CHECK(mesh.warnings.size() == 2 && contains(mesh.warnings[0], "unknown.su2:9: element type 7 (NELEM=) is not one of SU2's (3, 5, 9, 10, 12, 13, 14): its 2 elements are left out"));
  CHECK(mesh.warnings.size() == 2 && contains(mesh.warnings[1], "unknown.su2:15: element type 1 (marker wall) is not one of SU2's"));
  CHECK(mesh.blocks.size() == 2 && mesh.blocks[0].ids == std::vector<std::int64_t>{ 0 } && mesh.blocks[1].ids == std::vector<std::int64_t>{ 3 });
  CHECK(mesh.nodeIds.size() == 4 && mesh.nodeSets.size() == 1 && mesh.nodeSets[0].ids == (std::vector<std::int64_t>{ 0, 1 }));
}

TEST(BadFilesNameTheFileAndTheLine)
{
  const std::string dir = folder("bad");
  auto bad = [&](const std::string& name, const std::string& text) { return readError(writeFile(dir + "/" + name, text)); };
  const std::string square = "NDIME= 2\nNPOIN= 4\n0 0\n1 0\n1 1\n0 1\n";
  // numbers
  CHECK(contains(bad("number.su2", "NDIME= 2\nNPOIN= 2\n0 0\n1.0.0 0\nNELEM= 0\n"), "number.su2:4: point 1's coordinate \"1.0.0\" is not a finite number"));
  CHECK(contains(bad("nan.su2", "NDIME= 2\nNPOIN= 1\nnan 0\nNELEM= 0\n"), "nan.su2:3: point 0's coordinate \"nan\" is not a finite number"));
  CHECK(contains(bad("inf.su2", "NDIME= 3\nNPOIN= 1\n0 1e999 0\nNELEM= 0\n"), "inf.su2:3: point 0's coordinate \"1e999\" is not a finite number"));
  CHECK(contains(bad("index.su2", "NDIME= 2\nNPOIN= 1\n0 0 0.5\nNELEM= 0\n"), "index.su2:3: \"0.5\" after the 2 coordinates of point 0 is not an index (NDIME= 2)"));
  CHECK(contains(bad("fields.su2", "NDIME= 3\nNPOIN= 1\n0 0\nNELEM= 0\n"), "fields.su2:3: point 0 is \"0 0\"; a point of NDIME= 3 is \"x y z [index]\""));
  CHECK(contains(bad("type.su2", square + "NELEM= 1\nx 0 1 2\n"), "type.su2:8: \"x\" is not an element type"));
  CHECK(contains(bad("count.su2", square + "NELEM= 1\n5 0 1\n"), "count.su2:8: a line of 3 fields where a triangle's 4 or 5 are expected"));
  CHECK(contains(bad("negative.su2", square + "NELEM= 1\n5 0 -1 2\n"), "negative.su2:8: point index -1 is negative"));
  CHECK(contains(bad("dimension.su2", "NDIME= 4\n"), "dimension.su2:1: NDIME= 4 is neither 2 nor 3"));
  CHECK(contains(bad("owned.su2", "NDIME= 2\nNPOIN= 1 2\n0 0\n"), "owned.su2:2: NPOIN= 1 2: more owned points than points"));
  // counts and the lines they announce: fewer, more, beyond the file
  CHECK(contains(bad("cut.su2", "NDIME= 2\nNPOIN= 3\n0.00 0.00\n1.00 0.00\n"), "cut.su2:4: the file ends after 2 of the 3 points that NPOIN= announces (it is cut short)"));
  CHECK(contains(bad("short.su2", "NDIME= 2\nNPOIN= 3\n0 0\n1 0\nNELEM= 0\n"),
    "short.su2:5: \"NELEM= 0\" where point 2 of the 3 points that NPOIN= announces is expected"));
  CHECK(contains(bad("blank.su2", "NDIME= 2\nNPOIN= 2\n0 0\n\n1 0\nNELEM= 0\n"), "blank.su2:4: a blank line where point 1 of the 2 points"));
  CHECK(contains(bad("long.su2", "NDIME= 2\nNPOIN= 1\n0 0\n1 0\nNELEM= 0\n"),
    "long.su2:4: \"1 0\" is outside any section (are there more lines than the count before them announces?)"));
  CHECK(contains(bad("huge.su2", "NDIME= 2\nNPOIN= 999999999999\n0 0\n"), "huge.su2:2: 999999999999 points: more than the rest of the file holds"));
  CHECK(contains(bad("hugeelements.su2", square + "NELEM= 99999999999999\n5 0 1 2\n"),
    "hugeelements.su2:7: 99999999999999 elements: more than the rest of the file holds"));
  CHECK(contains(bad("markers.su2", square + "NELEM= 0\nNMARK= 2\nMARKER_TAG= a\nMARKER_ELEMS= 0\n"),
    "markers.su2:8: NMARK= 2 announces 2 markers; the zone has 1"));
  CHECK(contains(bad("tag.su2", square + "NELEM= 0\nNMARK= 2\nMARKER_TAG= a\nMARKER_TAG= b\n"),
    "tag.su2:10: MARKER_TAG= where MARKER_ELEMS= of the marker a is expected"));
  // a missing point, found once the points are read (Gmsh writes them after the elements)
  CHECK(contains(bad("missing.su2", "NDIME= 2\nNELEM= 2\n5 0 1 2\n5 0 2 9\nNPOIN= 4\n0 0\n1 0\n1 1\n0 1\n"),
    "missing.su2:4: an element refers to point 9; NPOIN= 4 defines points 0 to 3"));
  CHECK(contains(bad("markerpoint.su2", square + "NELEM= 0\nNMARK= 1\nMARKER_TAG= a\nMARKER_ELEMS= 1\n3 3 4\n"),
    "markerpoint.su2:11: an element refers to point 4; NPOIN= 4 defines points 0 to 3"));
  // sections missing, twice, out of order
  CHECK(contains(bad("nopoints.su2", "NDIME= 2\nNELEM= 0\n"), "nopoints.su2: has no NPOIN="));
  CHECK(contains(bad("noelements.su2", square), "noelements.su2: has no NELEM="));
  CHECK(contains(bad("before.su2", "NPOIN= 1\n0 0\n"), "before.su2:1: NPOIN= before NDIME="));
  CHECK(contains(bad("second.su2", square + "NPOIN= 0\n"), "second.su2:7: a second NPOIN= in one zone"));
  CHECK(contains(bad("notsu2.su2", "*HEADING\n"), "notsu2.su2:1: \"*HEADING\" is outside any section"));
  CHECK(contains(bad("empty.su2", "% nothing\n"), "empty.su2: has no NDIME=, NPOIN= or NELEM=: not an SU2 mesh"));
  CHECK(contains(readError(dir + "/none.su2"), "none.su2: cannot be read"));
}

TEST_MAIN
