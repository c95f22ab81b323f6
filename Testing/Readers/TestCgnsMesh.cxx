// CGNS files without VTK, written here with the CGNS library: unstructured and structured zones of
// two bases read (sections, boundary sections, BCs and their families as sets); a variant of an HDF5
// or an ADF file differs from its source only in the moved coordinates' bytes (elements, BCs,
// families, flow solutions read back alike); single precision rounds; no variant of linked
// coordinates; VTK's node orders; bad files give an error naming the file and what.
#include "../TestHarness.h"
#include "CGNS/CgnsMesh.h"
#include "Common/TextFile.h"
#include "FormatFiles.h"

#include <algorithm>
#include <array>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#ifdef MLSFORMATS_VTK_CGNS
#include <vtk_cgns.h>
#include VTK_CGNS(cgnslib.h)
#else
#include <cgnslib.h>
#endif

namespace fs = std::filesystem;
using namespace mlsformats;

namespace
{
using testing::contains;
using testing::find;
using testing::Point;
using testing::position;
using testing::sameTopology;
using testing::tripleProduct;
using testing::writeError;
using testing::writeFile;

const testing::TestFolders folder{ "cgns" };
const testing::ReadErrors readError{ cgns::readCgns };

// Stops the tests at a CGNS library error while writing a test file: the test cannot go on.
void ok(int status)
{
  if (status != CG_OK)
  {
    std::printf("CGNS library: %s\n", cg_get_error());
    std::fflush(stdout);
    std::abort();
  }
}

// A zone's coordinates written in the data type (RealSingle: the nearest floats).
void writeCoordinates(int fn, int b, int z, const std::vector<Point>& points, CGNS_ENUMT(DataType_t) type, int axes = 3)
{
  const char* const names[] = { "CoordinateX", "CoordinateY", "CoordinateZ" };
  for (int c = 0; c < axes; ++c)
  {
    std::vector<double> doubles;
    std::vector<float> floats;
    for (const Point& p : points)
    {
      doubles.push_back(p[c]);
      floats.push_back(static_cast<float>(p[c]));
    }
    int index = 0;
    ok(cg_coord_write(fn, b, z, type, names[c],
      type == CGNS_ENUMV(RealSingle) ? static_cast<const void*>(floats.data()) : doubles.data(), &index));
  }
}

// A BC, its grid location and its family (none if "").
void writeBoco(int fn, int b, int z, const char* name, CGNS_ENUMT(PointSetType_t) pointSet, const std::vector<cgsize_t>& points,
  std::size_t dims, CGNS_ENUMT(GridLocation_t) location, const char* family)
{
  int bc = 0;
  ok(cg_boco_write(fn, b, z, name, CGNS_ENUMV(BCWall), pointSet, static_cast<cgsize_t>(points.size() / dims), points.data(), &bc));
  ok(cg_boco_gridlocation_write(fn, b, z, bc, location));
  if (*family)
  {
    ok(cg_goto(fn, b, "Zone_t", z, "ZoneBC_t", 1, "BC_t", bc, "end"));
    ok(cg_famname_write(family));
  }
}

// The nodes of the unstructured zone "block": a unit cube (1-8) and the apex of a tetrahedron on its
// top (9).
const std::vector<Point> blockPoints = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 },
  { 0, 1, 1 }, { 0.5, 0.5, 2 } };

// Two bases in an HDF5 or an ADF file. "Base": the unstructured zone "block" (a HEXA_8, a TETRA_4, the boundary section
// "wall" of two QUAD_4: the bottom and the front; the BC "inlet", a point list of the x = 0 face in
// the family "inflow", and "bottom", the face element 3 in the family "walls"; a flow solution of
// pressures; the families, a descriptor). "Second": the structured zone "grid" of 3x3x2 points
// (x = i, y = j, z = 10 + k) with the BC "outlet", the points of i = 3, and "top", the faces of
// k = 2 in the family "walls".
std::string writeTwoBases(const std::string& path, CGNS_ENUMT(DataType_t) type = CGNS_ENUMV(RealDouble), int fileType = CG_FILE_HDF5)
{
  int fn = 0, b = 0, z = 0, s = 0, index = 0;
  ok(cg_set_file_type(fileType));
  ok(cg_open(path.c_str(), CG_MODE_WRITE, &fn));
  ok(cg_set_file_type(CG_FILE_NONE));
  ok(cg_base_write(fn, "Base", 3, 3, &b));
  ok(cg_family_write(fn, b, "inflow", &index));
  ok(cg_family_write(fn, b, "walls", &index));
  ok(cg_goto(fn, b, "end"));
  ok(cg_descriptor_write("history", "written by TestCgnsMesh"));
  cgsize_t blockSize[3] = { 9, 2, 0 };
  ok(cg_zone_write(fn, b, "block", blockSize, CGNS_ENUMV(Unstructured), &z));
  writeCoordinates(fn, b, z, blockPoints, type);
  const std::vector<cgsize_t> hexa = { 1, 2, 3, 4, 5, 6, 7, 8 }, tetra = { 5, 6, 7, 9 }, wall = { 1, 4, 3, 2, 1, 2, 6, 5 };
  ok(cg_section_write(fn, b, z, "Hexa", CGNS_ENUMV(HEXA_8), 1, 1, 0, hexa.data(), &s));
  ok(cg_section_write(fn, b, z, "Tetra", CGNS_ENUMV(TETRA_4), 2, 2, 0, tetra.data(), &s));
  ok(cg_section_write(fn, b, z, "wall", CGNS_ENUMV(QUAD_4), 3, 4, 0, wall.data(), &s));
  writeBoco(fn, b, z, "inlet", CGNS_ENUMV(PointList), { 1, 4, 8, 5 }, 1, CGNS_ENUMV(Vertex), "inflow");
  writeBoco(fn, b, z, "bottom", CGNS_ENUMV(PointRange), { 3, 3 }, 1, CGNS_ENUMV(FaceCenter), "walls");
  std::vector<double> pressure;
  for (int n = 1; n <= 9; ++n)
  {
    pressure.push_back(1.5 * n);
  }
  ok(cg_sol_write(fn, b, z, "Solution", CGNS_ENUMV(Vertex), &s));
  ok(cg_field_write(fn, b, z, s, CGNS_ENUMV(RealDouble), "Pressure", pressure.data(), &index));
  ok(cg_base_write(fn, "Second", 3, 3, &b));
  ok(cg_family_write(fn, b, "walls", &index));
  cgsize_t gridSize[9] = { 3, 3, 2, 2, 2, 1, 0, 0, 0 };
  ok(cg_zone_write(fn, b, "grid", gridSize, CGNS_ENUMV(Structured), &z));
  std::vector<Point> grid;
  for (int k = 0; k < 2; ++k)
  {
    for (int j = 0; j < 3; ++j)
    {
      for (int i = 0; i < 3; ++i)
      {
        grid.push_back({ double(i), double(j), 10.0 + k });
      }
    }
  }
  writeCoordinates(fn, b, z, grid, type);
  writeBoco(fn, b, z, "outlet", CGNS_ENUMV(PointRange), { 3, 1, 1, 3, 3, 2 }, 3, CGNS_ENUMV(Vertex), "");
  writeBoco(fn, b, z, "top", CGNS_ENUMV(PointRange), { 1, 1, 2, 2, 2, 2 }, 3, CGNS_ENUMV(KFaceCenter), "walls");
  ok(cg_close(fn));
  return path;
}

// What the library reads of a file besides its coordinates: its version, each zone's sections
// (name, type, range, connectivity), BCs (name, point set, location, points, family), flow
// solutions' fields and the base's families and descriptors, as text.
std::string contents(const std::string& path)
{
  int fn = 0, bases = 0;
  float version = 0;
  ok(cg_open(path.c_str(), CG_MODE_READ, &fn));
  ok(cg_version(fn, &version));
  std::string out = "version " + std::to_string(version) + "\n";
  ok(cg_nbases(fn, &bases));
  for (int b = 1; b <= bases; ++b)
  {
    char name[33], text[33];
    int cellDim = 0, physDim = 0, families = 0, zones = 0, descriptors = 0;
    ok(cg_base_read(fn, b, name, &cellDim, &physDim));
    ok(cg_nfamilies(fn, b, &families));
    out += "base " + std::string(name) + " families " + std::to_string(families) + "\n";
    ok(cg_goto(fn, b, "end"));
    ok(cg_ndescriptors(&descriptors));
    for (int d = 1; d <= descriptors; ++d)
    {
      char* descriptor = nullptr;
      ok(cg_descriptor_read(d, text, &descriptor));
      out += std::string(text) + ": " + descriptor + "\n";
      cg_free(descriptor);
    }
    ok(cg_nzones(fn, b, &zones));
    for (int z = 1; z <= zones; ++z)
    {
      cgsize_t size[9];
      int sections = 0, bocos = 0, solutions = 0, indexDim = 0;
      ok(cg_zone_read(fn, b, z, name, size));
      ok(cg_index_dim(fn, b, z, &indexDim));
      out += "zone " + std::string(name) + "\n";
      ok(cg_nsections(fn, b, z, &sections));
      for (int s = 1; s <= sections; ++s)
      {
        CGNS_ENUMT(ElementType_t) type;
        cgsize_t start = 0, end = 0, size = 0;
        int boundary = 0, parents = 0;
        ok(cg_section_read(fn, b, z, s, name, &type, &start, &end, &boundary, &parents));
        ok(cg_ElementDataSize(fn, b, z, s, &size));
        std::vector<cgsize_t> nodes(size);
        ok(cg_elements_read(fn, b, z, s, nodes.data(), nullptr));
        out += " section " + std::string(name) + " " + cg_ElementTypeName(type) + " " + std::to_string(start) + "-" +
          std::to_string(end) + ":";
        for (const cgsize_t node : nodes)
        {
          out += " " + std::to_string(node);
        }
        out += "\n";
      }
      ok(cg_nbocos(fn, b, z, &bocos));
      for (int bc = 1; bc <= bocos; ++bc)
      {
        CGNS_ENUMT(BCType_t) type;
        CGNS_ENUMT(PointSetType_t) pointSet;
        CGNS_ENUMT(GridLocation_t) location;
        CGNS_ENUMT(DataType_t) normalType;
        cgsize_t count = 0, normals = 0;
        int normalIndex[3], datasets = 0;
        char family[1024] = {};
        ok(cg_boco_info(fn, b, z, bc, name, &type, &pointSet, &count, normalIndex, &normals, &normalType, &datasets));
        ok(cg_boco_gridlocation_read(fn, b, z, bc, &location));
        std::vector<cgsize_t> points(count * indexDim);
        ok(cg_boco_read(fn, b, z, bc, points.data(), nullptr));
        ok(cg_goto(fn, b, "Zone_t", z, "ZoneBC_t", 1, "BC_t", bc, "end"));
        cg_famname_read(family);
        out += " bc " + std::string(name) + " " + cg_PointSetTypeName(pointSet) + " " + cg_GridLocationName(location) + " " + family + ":";
        for (const cgsize_t point : points)
        {
          out += " " + std::to_string(point);
        }
        out += "\n";
      }
      ok(cg_nsols(fn, b, z, &solutions));
      for (int s = 1; s <= solutions; ++s)
      {
        CGNS_ENUMT(GridLocation_t) location;
        int fields = 0;
        ok(cg_sol_info(fn, b, z, s, name, &location));
        ok(cg_nfields(fn, b, z, s, &fields));
        for (int f = 1; f <= fields; ++f)
        {
          CGNS_ENUMT(DataType_t) type;
          ok(cg_field_info(fn, b, z, s, f, &type, text));
          std::vector<double> values(size[0]);
          cgsize_t low = 1, high = size[0];
          ok(cg_field_read(fn, b, z, s, text, CGNS_ENUMV(RealDouble), &low, &high, values.data()));
          out += " solution " + std::string(name) + " " + text + ":";
          for (const double value : values)
          {
            out += " " + std::to_string(value);
          }
          out += "\n";
        }
      }
    }
  }
  ok(cg_close(fn));
  return out;
}
} // namespace

TEST(TwoBasesReadAsOneMesh)
{
  const std::string dir = folder("read");
  const std::string path = writeTwoBases(dir + "/two.cgns");
  const cgns::MeshFile file = cgns::readCgns(path);
  const SourceMesh& mesh = file.mesh;
  for (const std::string& warning : mesh.warnings)
  {
    std::printf("warning: %s\n", warning.c_str());
  }
  CHECK(mesh.warnings.empty());
  // the block's nodes 1-9, the grid's 10-27 (i fastest)
  std::vector<std::int64_t> ids(27);
  for (std::int64_t n = 0; n < 27; ++n)
  {
    ids[n] = n + 1;
  }
  CHECK(mesh.nodeIds == ids);
  CHECK(mesh.xyz.size() == 81 && position(mesh, 9) == (Point{ 0.5, 0.5, 2 }) && position(mesh, 10) == (Point{ 0, 0, 10 }) &&
    position(mesh, 11) == (Point{ 1, 0, 10 }) && position(mesh, 13) == (Point{ 0, 1, 10 }) && position(mesh, 27) == (Point{ 2, 2, 11 }));
  // the cells: the block's hexahedron (1) and tetrahedron (2); its quadrangles 3-4 are not; the
  // grid's hexahedra from 5, after the block's highest element number
  CHECK(mesh.blocks.size() == 3);
  if (mesh.blocks.size() == 3)
  {
    CHECK(mesh.blocks[0].name == "HEXA_8" && mesh.blocks[0].type == CellType::Hexahedron &&
      mesh.blocks[0].ids == std::vector<std::int64_t>{ 1 });
    CHECK(mesh.blocks[0].nodes == (std::vector<std::int64_t>{ 1, 2, 3, 4, 5, 6, 7, 8 }));
    CHECK(mesh.blocks[1].name == "TETRA_4" && mesh.blocks[1].type == CellType::Tetra &&
      mesh.blocks[1].ids == std::vector<std::int64_t>{ 2 });
    CHECK(mesh.blocks[1].nodes == (std::vector<std::int64_t>{ 5, 6, 7, 9 }));
    CHECK(mesh.blocks[2].name == "structured hexahedron" && mesh.blocks[2].type == CellType::Hexahedron);
    CHECK(mesh.blocks[2].ids == (std::vector<std::int64_t>{ 5, 6, 7, 8 }));
    // cell (i, j, k) = (1, 1, 0): its points (1,1,0) (2,1,0) (2,2,0) (1,2,0), then k = 1
    CHECK(std::vector<std::int64_t>(mesh.blocks[2].nodes.begin() + 24, mesh.blocks[2].nodes.end()) ==
      (std::vector<std::int64_t>{ 14, 15, 18, 17, 23, 24, 27, 26 }));
  }
  // the boundary section, each BC and each family a node set; the zones element sets
  std::vector<std::string> names;
  for (const NamedSet& set : mesh.nodeSets)
  {
    names.push_back(set.name);
  }
  CHECK(names == (std::vector<std::string>{ "wall", "inlet", "family/inflow", "bottom", "family/walls", "outlet", "top" }));
  auto nodes = [&](const std::string& name) {
    return find(mesh.nodeSets, name) ? find(mesh.nodeSets, name)->ids : std::vector<std::int64_t>();
  };
  CHECK(nodes("wall") == (std::vector<std::int64_t>{ 1, 2, 3, 4, 5, 6 }));
  CHECK(nodes("inlet") == (std::vector<std::int64_t>{ 1, 4, 5, 8 }) && nodes("family/inflow") == nodes("inlet"));
  CHECK(nodes("bottom") == (std::vector<std::int64_t>{ 1, 2, 3, 4 }));
  CHECK(nodes("outlet") == (std::vector<std::int64_t>{ 12, 15, 18, 21, 24, 27 }));
  CHECK(nodes("top") == (std::vector<std::int64_t>{ 19, 20, 21, 22, 23, 24, 25, 26, 27 }));
  std::vector<std::int64_t> walls = { 1, 2, 3, 4 };
  walls.insert(walls.end(), { 19, 20, 21, 22, 23, 24, 25, 26, 27 });
  CHECK(nodes("family/walls") == walls);
  CHECK(mesh.elementSets.size() == 2 && find(mesh.elementSets, "block") && find(mesh.elementSets, "grid"));
  CHECK(find(mesh.elementSets, "block") && find(mesh.elementSets, "block")->ids == (std::vector<std::int64_t>{ 1, 2 }));
  CHECK(find(mesh.elementSets, "grid") && find(mesh.elementSets, "grid")->ids == (std::vector<std::int64_t>{ 5, 6, 7, 8 }));
  // the zones as a variant writes them
  CHECK(file.zones.size() == 2);
  if (file.zones.size() == 2)
  {
    const cgns::Zone &block = file.zones[0], &grid = file.zones[1];
    CHECK(block.base == "Base" && block.name == "block" && block.grid == "GridCoordinates" && block.nodes == 9 && block.offset == 0);
    CHECK(grid.base == "Second" && grid.name == "grid" && grid.nodes == 18 && grid.offset == 9);
    CHECK(grid.coordinates == (std::vector<std::string>{ "CoordinateX", "CoordinateY", "CoordinateZ" }));
    CHECK(grid.single == (std::vector<bool>{ false, false, false }));
  }
  // the layout: the node ids and the zones alone
  const cgns::MeshFile layout = cgns::readCgnsLayout(path);
  CHECK(layout.mesh.nodeIds == mesh.nodeIds && layout.mesh.xyz.empty() && layout.mesh.blocks.empty() && layout.mesh.nodeSets.empty());
  CHECK(layout.zones.size() == 2 && layout.hash == file.hash);
  CHECK(cgns::isCgns(readFile(path).substr(0, 64)) && cgns::isCgns("\300\250\243\251ADF Database Version A02011>") &&
    !cgns::isCgns("*HEADING\n") && !cgns::isCgns("\x89HDF"));
}

TEST(VariantChangesOnlyTheMovedCoordinates)
{
  const std::string dir = folder("variant");
  for (const int fileType : { CG_FILE_HDF5, CG_FILE_ADF })
  {
    const std::string name = fileType == CG_FILE_ADF ? "adf" : "hdf5";
    const std::string source = writeTwoBases(dir + "/" + name + ".cgns", CGNS_ENUMV(RealDouble), fileType);
    if (fileType == CG_FILE_ADF)
    {
      // a source last modified long ago (the header's "AdF1" date, which the library sets as it
      // writes): its variants keep that date, whenever they are written
      std::string bytes = readFile(source);
      const std::size_t date = bytes.find("AdF1");
      CHECK(date != std::string::npos && date < 256);
      bytes.replace(date + 4, 28, "Thu Jan  1 00:00:00 1970    ");
      writeFile(source, bytes);
    }
    const cgns::MeshFile file = cgns::readCgns(source);
    const std::size_t count = file.mesh.nodeIds.size();
    // the same coordinates: the same bytes
    file.writeVariant(dir + "/same/" + name + ".cgns", file.mesh.nodeIds.data(), file.mesh.xyz.data(), count, false);
    CHECK(readFile(dir + "/same/" + name + ".cgns") == readFile(source));
    // node 9 (the block's apex) and node 27 (the grid's last) moved, the nodes given in reverse order
    std::vector<std::int64_t> ids(file.mesh.nodeIds.rbegin(), file.mesh.nodeIds.rend());
    std::vector<double> xyz;
    for (std::size_t i = count; i-- > 0;)
    {
      xyz.insert(xyz.end(), file.mesh.xyz.begin() + 3 * i, file.mesh.xyz.begin() + 3 * i + 3);
    }
    const Point moved9 = { 0.5, 0.25, 1.0 / 3.0 }, moved27 = { 2.1, 2, 11.000000000000002 };
    std::copy(moved9.begin(), moved9.end(), xyz.begin() + 3 * (count - 9));
    std::copy(moved27.begin(), moved27.end(), xyz.begin());
    const std::string target = dir + "/moved/" + name + ".cgns";
    file.writeVariant(target, ids.data(), xyz.data(), count, false);
    // the same size; the bytes that differ are the moved values' (4 doubles: node 9's y and z, node
    // 27's x and z)
    const std::string before = readFile(source), after = readFile(target);
    CHECK(testing::changedAtMost(before, after, 4 * 8));
    // read back: the moved nodes where they were put, exactly; the others and the rest as they were
    const cgns::MeshFile again = cgns::readCgns(target);
    CHECK(position(again.mesh, 9) == moved9 && position(again.mesh, 27) == moved27);
    for (std::int64_t id = 1; id <= 26; ++id)
    {
      CHECK(id == 9 || position(again.mesh, id) == position(file.mesh, id));
    }
    CHECK(sameTopology(again.mesh, file.mesh) && again.mesh.warnings.empty());
    const std::string text = contents(source);
    std::printf("%s", text.c_str());
    CHECK(contents(target) == text);
    CHECK(contains(text, "solution Solution Pressure: 1.500000 3.000000") &&
      contains(text, "bc top PointRange KFaceCenter walls: 1 1 2 2 2 2"));
    // the layout alone writes the same variant
    const cgns::MeshFile layout = cgns::readCgnsLayout(source);
    layout.writeVariant(dir + "/layout/" + name + ".cgns", ids.data(), xyz.data(), count, false);
    CHECK(readFile(dir + "/layout/" + name + ".cgns") == after);
  }
}

TEST(SinglePrecisionCoordinatesRound)
{
  const std::string dir = folder("single");
  const std::string source = writeTwoBases(dir + "/single.cgns", CGNS_ENUMV(RealSingle));
  const cgns::MeshFile file = cgns::readCgns(source);
  CHECK(!file.zones.empty() && file.zones[0].single == (std::vector<bool>{ true, true, true }));
  const std::size_t count = file.mesh.nodeIds.size();
  // a value that is not a float is written as the nearest float: 0.1 reads back as 0.1f
  std::vector<double> xyz = file.mesh.xyz;
  xyz[3 * 8] = 0.1;
  xyz[3 * 8 + 1] = 1e-50;
  const std::string target = dir + "/moved.cgns";
  file.writeVariant(target, file.mesh.nodeIds.data(), xyz.data(), count, false);
  const cgns::MeshFile again = cgns::readCgns(target);
  CHECK(position(again.mesh, 9) == (Point{ double(0.1f), 0, 2 }));
  CHECK(std::abs(position(again.mesh, 9)[0] - 0.1) < 0.1 * 6e-8);
  for (std::int64_t id = 1; id <= 27; ++id)
  {
    CHECK(id == 9 || position(again.mesh, id) == position(file.mesh, id));
  }
  CHECK(readFile(target).size() == readFile(source).size());
  // beyond the float range: refused, nothing written
  xyz[3 * 8 + 2] = 1e39;
  CHECK(contains(writeError(file, dir + "/huge.cgns", file.mesh.nodeIds, xyz),
    "huge.cgns: node 9's coordinate 1e+39 is beyond the range of /Base/block/GridCoordinates/CoordinateZ (single precision)"));
  xyz[3 * 8 + 2] = -FLT_MAX;
  file.writeVariant(dir + "/largest.cgns", file.mesh.nodeIds.data(), xyz.data(), count, false);
  CHECK(position(cgns::readCgns(dir + "/largest.cgns").mesh, 9)[2] == -FLT_MAX);
  CHECK(!fs::exists(dir + "/huge.cgns"));
}

TEST(VariantRefusesOtherDataAndNeverHalfWrites)
{
  const std::string dir = folder("refuse");
  const std::string source = writeTwoBases(dir + "/two.cgns");
  const cgns::MeshFile file = cgns::readCgns(source);
  const std::vector<std::int64_t>& ids = file.mesh.nodeIds;
  const std::vector<double>& xyz = file.mesh.xyz;
  // the refusals of every format
  testing::checkVariantRefusals(file, source, dir, "x");
  // coordinates linked to another file: read, and no variant written (nor the other file changed)
  const std::string elsewhere = writeTwoBases(dir + "/elsewhere.cgns"), linked = writeTwoBases(dir + "/linked.cgns");
  int fn = 0;
  ok(cg_open(linked.c_str(), CG_MODE_MODIFY, &fn));
  ok(cg_goto(fn, 1, "Zone_t", 1, "end"));
  ok(cg_delete_node("GridCoordinates"));
  ok(cg_link_write("GridCoordinates", elsewhere.c_str(), "/Base/block/GridCoordinates"));
  ok(cg_close(fn));
  const cgns::MeshFile link = cgns::readCgns(linked);
  CHECK(link.mesh.xyz == xyz);
  const std::string before = readFile(elsewhere);
  CHECK(contains(writeError(link, dir + "/l/linked.cgns", ids, std::vector<double>(xyz.size(), 0.5)),
    "linked.cgns: /Base/block/GridCoordinates/CoordinateX: is linked to another file"));
  CHECK(!fs::exists(dir + "/l/linked.cgns") && readFile(elsewhere) == before);
  CHECK(testing::nothingWrittenAside(dir));
}

TEST(TwoDimensionalZoneKeepsZ)
{
  // a 2D base: the quadrangle and the triangle are the cells, the boundary bars a node set; the
  // nodes have z = 0, and a variant that moves one off it is refused
  const std::string dir = folder("plane");
  const std::string source = dir + "/plane.cgns";
  int fn = 0, b = 0, z = 0, s = 0;
  ok(cg_open(source.c_str(), CG_MODE_WRITE, &fn));
  ok(cg_base_write(fn, "Plane", 2, 2, &b));
  cgsize_t size[3] = { 5, 2, 0 };
  ok(cg_zone_write(fn, b, "plate", size, CGNS_ENUMV(Unstructured), &z));
  writeCoordinates(fn, b, z, { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 2, 0.5, 0 } }, CGNS_ENUMV(RealDouble), 2);
  const std::vector<cgsize_t> quad = { 1, 2, 3, 4 }, tri = { 2, 5, 3 }, bars = { 1, 2, 2, 5 };
  ok(cg_section_write(fn, b, z, "quads", CGNS_ENUMV(QUAD_4), 1, 1, 0, quad.data(), &s));
  ok(cg_section_write(fn, b, z, "triangles", CGNS_ENUMV(TRI_3), 2, 2, 0, tri.data(), &s));
  ok(cg_section_write(fn, b, z, "lower edge", CGNS_ENUMV(BAR_2), 3, 4, 0, bars.data(), &s));
  ok(cg_close(fn));
  const cgns::MeshFile file = cgns::readCgns(source);
  const SourceMesh& mesh = file.mesh;
  CHECK(mesh.xyz == (std::vector<double>{ 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 2, 0.5, 0 }));
  CHECK(mesh.blocks.size() == 2 && mesh.blocks[0].type == CellType::Quad && mesh.blocks[1].type == CellType::Triangle);
  CHECK(mesh.blocks.size() == 2 && mesh.blocks[1].ids == std::vector<std::int64_t>{ 2 } &&
    mesh.blocks[1].nodes == (std::vector<std::int64_t>{ 2, 5, 3 }));
  CHECK(mesh.nodeSets.size() == 1 && mesh.nodeSets[0].name == "lower edge" &&
    mesh.nodeSets[0].ids == (std::vector<std::int64_t>{ 1, 2, 5 }));
  CHECK(!file.zones.empty() && file.zones[0].coordinates == (std::vector<std::string>{ "CoordinateX", "CoordinateY" }));
  std::vector<double> xyz = mesh.xyz;
  xyz[3 * 4] = 2.5;
  file.writeVariant(dir + "/moved.cgns", mesh.nodeIds.data(), xyz.data(), 5, false);
  CHECK(cgns::readCgns(dir + "/moved.cgns").mesh.xyz == xyz);
  xyz[3 * 4 + 2] = 1e-3;
  CHECK(contains(writeError(file, dir + "/off.cgns", mesh.nodeIds, xyz),
    "off.cgns: node 5 has z = 0.001, but /Plane/plate/GridCoordinates has no CoordinateZ (the zone is 2D)"));
  CHECK(!fs::exists(dir + "/off.cgns"));
}

TEST(NodeOrdersAreVtks)
{
  // one element of each type with midside nodes, and the linear ones, their nodes where the SIDS put
  // them: a TETRA_10's midside nodes 4-9 on its edges 0-1 1-2 2-0 0-3 1-3 2-3, a PYRA_13's 5-12 on
  // 0-1 1-2 2-3 3-0 0-4 1-4 2-4 3-4, a PENTA_15's 6-14 on 0-1 1-2 2-0 0-3 1-4 2-5 3-4 4-5 5-3, a
  // HEXA_20's 8-19 on 0-1 1-2 2-3 3-0 0-4 1-5 2-6 3-7 4-5 5-6 6-7 7-4 and HEXA_27's 20-26 at the
  // centres of the faces 0123 0154 1265 2376 0473 4567 and of the volume; a PENTA's 0-1-2 turns
  // counter-clockwise seen from 3-4-5 (as CGNS's own elemtest.c puts one). A MIXED section splits
  // by type (its triangle is a boundary element); PYRA_14, PENTA_18 and NGON_n are left out.
  const std::string dir = folder("orders");
  const std::vector<Point> tetra = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } },
                           pyramid = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0.5, 0.5, 1 } },
                           penta = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 0, 1, 1 } },
                           hexa = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 },
                             { 0, 1, 1 } };
  const std::vector<std::vector<int>> tetraEdges = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 0, 3 }, { 1, 3 }, { 2, 3 } },
                                      pyramidEdges = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 0, 4 }, { 1, 4 }, { 2, 4 }, { 3, 4 },
                                        { 0, 1, 2, 3 } },
                                      pentaEdges = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 0, 3 }, { 1, 4 }, { 2, 5 }, { 3, 4 }, { 4, 5 },
                                        { 5, 3 }, { 0, 1, 4, 3 }, { 1, 2, 5, 4 }, { 2, 0, 3, 5 } },
                                      hexaEdges = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 },
                                        { 4, 5 }, { 5, 6 }, { 6, 7 }, { 7, 4 }, { 0, 1, 2, 3 }, { 0, 1, 5, 4 }, { 1, 2, 6, 5 },
                                        { 2, 3, 7, 6 }, { 0, 4, 7, 3 }, { 4, 5, 6, 7 }, { 0, 1, 2, 3, 4, 5, 6, 7 } };
  // each element's nodes after the others', its corners moved apart from the others'
  std::vector<Point> points;
  auto add = [&](const std::vector<Point>& corners, const std::vector<std::vector<int>>& between, std::size_t count) {
    std::vector<cgsize_t> nodes;
    const double shift = 10.0 * points.size();
    for (std::size_t i = 0; i < count; ++i)
    {
      Point p{ 0, 0, 0 };
      const std::vector<int> at = i < corners.size() ? std::vector<int>{ int(i) } : between[i - corners.size()];
      for (const int corner : at)
      {
        for (int c = 0; c < 3; ++c)
        {
          p[c] += (corners[corner][c] * (c + 2) + (c == 0 ? shift : 0)) / at.size();
        }
      }
      points.push_back(p);
      nodes.push_back(static_cast<cgsize_t>(points.size()));
    }
    return nodes;
  };
  struct Element
  {
    const char* name;
    CGNS_ENUMT(ElementType_t) type;
    std::vector<cgsize_t> nodes;
  };
  const std::vector<Element> elements = { { "tetra10", CGNS_ENUMV(TETRA_10), add(tetra, tetraEdges, 10) },
    { "pyra13", CGNS_ENUMV(PYRA_13), add(pyramid, pyramidEdges, 13) }, { "penta15", CGNS_ENUMV(PENTA_15), add(penta, pentaEdges, 15) },
    { "hexa20", CGNS_ENUMV(HEXA_20), add(hexa, hexaEdges, 20) }, { "hexa27", CGNS_ENUMV(HEXA_27), add(hexa, hexaEdges, 27) },
    { "tetra4", CGNS_ENUMV(TETRA_4), add(tetra, {}, 4) }, { "pyra5", CGNS_ENUMV(PYRA_5), add(pyramid, {}, 5) },
    { "penta6", CGNS_ENUMV(PENTA_6), add(penta, {}, 6) }, { "hexa8", CGNS_ENUMV(HEXA_8), add(hexa, {}, 8) },
    { "pyra14", CGNS_ENUMV(PYRA_14), add(pyramid, pyramidEdges, 14) }, { "penta18", CGNS_ENUMV(PENTA_18), add(penta, pentaEdges, 18) } };
  const std::vector<cgsize_t> mixedPenta = add(penta, {}, 6), mixedHexa = add(hexa, {}, 8), mixedTriangle = add(tetra, {}, 3);
  const std::string source = dir + "/orders.cgns";
  int fn = 0, b = 0, z = 0, s = 0;
  ok(cg_open(source.c_str(), CG_MODE_WRITE, &fn));
  ok(cg_base_write(fn, "Base", 3, 3, &b));
  cgsize_t size[3] = { static_cast<cgsize_t>(points.size()), 14, 0 };
  ok(cg_zone_write(fn, b, "orders", size, CGNS_ENUMV(Unstructured), &z));
  writeCoordinates(fn, b, z, points, CGNS_ENUMV(RealDouble));
  cgsize_t number = 0;
  for (const Element& element : elements)
  {
    ++number;
    ok(cg_section_write(fn, b, z, element.name, element.type, number, number, 0, element.nodes.data(), &s));
  }
  std::vector<cgsize_t> mixed, offsets = { 0 };
  for (const auto& [type, nodes] : { std::make_pair(CGNS_ENUMV(PENTA_6), mixedPenta), std::make_pair(CGNS_ENUMV(HEXA_8), mixedHexa),
         std::make_pair(CGNS_ENUMV(TRI_3), mixedTriangle), std::make_pair(CGNS_ENUMV(PENTA_6), mixedPenta) })
  {
    mixed.push_back(type);
    mixed.insert(mixed.end(), nodes.begin(), nodes.end());
    offsets.push_back(static_cast<cgsize_t>(mixed.size()));
  }
  ok(cg_poly_section_write(fn, b, z, "mixed", CGNS_ENUMV(MIXED), number + 1, number + 4, 0, mixed.data(), offsets.data(), &s));
  const std::vector<cgsize_t> faces = { 1, 2, 3, 2, 3, 4 }, faceOffsets = { 0, 3, 6 };
  ok(cg_poly_section_write(fn, b, z, "faces", CGNS_ENUMV(NGON_n), number + 5, number + 6, 0, faces.data(), faceOffsets.data(), &s));
  ok(cg_close(fn));

  const cgns::MeshFile file = cgns::readCgns(source);
  const SourceMesh& mesh = file.mesh;
  for (const std::string& warning : mesh.warnings)
  {
    std::printf("warning: %s\n", warning.c_str());
  }
  CHECK(mesh.warnings.size() == 3);
  CHECK(mesh.warnings.size() == 3 &&
    contains(mesh.warnings[0], "orders.cgns: /Base/orders/pyra14: element type PYRA_14 is not supported: its 1 elements are left out"));
  CHECK(mesh.warnings.size() == 3 && contains(mesh.warnings[1], "/Base/orders/penta18: element type PENTA_18 is not supported"));
  CHECK(mesh.warnings.size() == 3 &&
    contains(mesh.warnings[2], "/Base/orders/faces: element type NGON_n is not supported: its 2 elements are left out"));
  CHECK(mesh.blocks.size() == 11);
  if (mesh.blocks.size() != 11)
  {
    return;
  }
  const ElementBlock &tetra10 = mesh.blocks[0], &pyra13 = mesh.blocks[1], &penta15 = mesh.blocks[2], &hexa20 = mesh.blocks[3],
                     &hexa27 = mesh.blocks[4], &tetra4 = mesh.blocks[5], &pyra5 = mesh.blocks[6], &penta6 = mesh.blocks[7],
                     &hexa8 = mesh.blocks[8], &mixedWedges = mesh.blocks[9], &mixedHexahedra = mesh.blocks[10];
  CHECK(tetra10.type == CellType::QuadraticTetra && tetra10.name == "TETRA_10");
  CHECK(pyra13.type == CellType::QuadraticPyramid && penta15.type == CellType::QuadraticWedge &&
    hexa20.type == CellType::QuadraticHexahedron);
  CHECK(hexa27.type == CellType::TriQuadraticHexahedron && penta6.type == CellType::Wedge && pyra5.type == CellType::Pyramid);
  CHECK(mixedWedges.type == CellType::Wedge && mixedWedges.ids == (std::vector<std::int64_t>{ 12, 15 }));
  CHECK(mixedHexahedra.type == CellType::Hexahedron && mixedHexahedra.ids == std::vector<std::int64_t>{ 13 });
  CHECK(mesh.nodeSets.size() == 1 && mesh.nodeSets[0].name == "mixed" &&
    mesh.nodeSets[0].ids == std::vector<std::int64_t>(mixedTriangle.begin(), mixedTriangle.end()));
  CHECK(find(mesh.elementSets, "orders") && find(mesh.elementSets, "orders")->ids.size() == 12);
  // VTK's edges and face centres (vtkQuadraticTetra, vtkQuadraticPyramid, vtkQuadraticWedge,
  // vtkQuadraticHexahedron; vtkTriQuadraticHexahedron's faces x=0 x=1 y=0 y=1 z=0 z=1)
  auto onTheirEdges = [&](const ElementBlock& block, int corners, const std::vector<std::vector<int>>& edges) {
    const std::int64_t* nodes = block.nodes.data();
    for (std::size_t i = 0; i < edges.size(); ++i)
    {
      Point middle{ 0, 0, 0 };
      for (const int corner : edges[i])
      {
        const Point p = position(mesh, nodes[corner]);
        for (int c = 0; c < 3; ++c)
        {
          middle[c] += p[c] / edges[i].size();
        }
      }
      if (position(mesh, nodes[corners + i]) != middle)
      {
        std::printf("%s: node %zu is not where VTK puts it\n", block.name.c_str(), corners + i);
        return false;
      }
    }
    return true;
  };
  const std::vector<std::vector<int>> vtkHexaEdges = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 4, 5 }, { 5, 6 }, { 6, 7 }, { 7, 4 },
    { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 }, { 0, 4, 7, 3 }, { 1, 2, 6, 5 }, { 0, 1, 5, 4 }, { 3, 2, 6, 7 }, { 0, 1, 2, 3 }, { 4, 5, 6, 7 },
    { 0, 1, 2, 3, 4, 5, 6, 7 } };
  CHECK(onTheirEdges(tetra10, 4, { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 0, 3 }, { 1, 3 }, { 2, 3 } }));
  CHECK(onTheirEdges(pyra13, 5, { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 0, 4 }, { 1, 4 }, { 2, 4 }, { 3, 4 } }));
  CHECK(onTheirEdges(penta15, 6, { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 3, 4 }, { 4, 5 }, { 5, 3 }, { 0, 3 }, { 1, 4 }, { 2, 5 } }));
  CHECK(onTheirEdges(hexa20, 8, std::vector<std::vector<int>>(vtkHexaEdges.begin(), vtkHexaEdges.begin() + 12)));
  CHECK(onTheirEdges(hexa27, 8, vtkHexaEdges));
  // VTK's wedge turns 0-1-2 away from 3-4-5: CGNS's 0 2 1 3 5 4
  CHECK(penta6.nodes == (std::vector<std::int64_t>{ elements[7].nodes[0], elements[7].nodes[2], elements[7].nodes[1], elements[7].nodes[3],
                          elements[7].nodes[5], elements[7].nodes[4] }));
  auto sign = [&](const ElementBlock& block, std::array<int, 4> corners) {
    return tripleProduct(position(mesh, block.nodes[corners[0]]), position(mesh, block.nodes[corners[1]]),
      position(mesh, block.nodes[corners[2]]), position(mesh, block.nodes[corners[3]]));
  };
  CHECK(sign(penta6, { 0, 1, 2, 3 }) < 0 && sign(penta15, { 0, 1, 2, 3 }) < 0 && sign(mixedWedges, { 0, 1, 2, 3 }) < 0);
  CHECK(sign(tetra4, { 0, 1, 2, 3 }) > 0 && sign(tetra10, { 0, 1, 2, 3 }) > 0);
  CHECK(sign(pyra5, { 0, 1, 2, 4 }) > 0 && sign(pyra13, { 0, 1, 2, 4 }) > 0);
  CHECK(sign(hexa8, { 0, 1, 3, 4 }) > 0 && sign(hexa20, { 0, 1, 3, 4 }) > 0 && sign(hexa27, { 0, 1, 3, 4 }) > 0 &&
    sign(mixedHexahedra, { 0, 1, 3, 4 }) > 0);
}

TEST(BadFilesNameTheFileAndWhat)
{
  const std::string dir = folder("bad");
  // one unstructured zone of a tetrahedron, made bad by change(fn, b, z) in the file opened again
  auto tetra = [&](const std::string& name, const std::vector<Point>& points, const std::vector<cgsize_t>& nodes,
                 const std::function<void(int, int, int)>& change) {
    const std::string path = dir + "/" + name;
    int fn = 0, b = 0, z = 0, s = 0;
    ok(cg_open(path.c_str(), CG_MODE_WRITE, &fn));
    ok(cg_base_write(fn, "Base", 3, 3, &b));
    cgsize_t size[3] = { static_cast<cgsize_t>(points.size()), 1, 0 };
    ok(cg_zone_write(fn, b, "solid", size, CGNS_ENUMV(Unstructured), &z));
    if (!points.empty())
    {
      writeCoordinates(fn, b, z, points, CGNS_ENUMV(RealDouble));
    }
    ok(cg_section_write(fn, b, z, "cells", CGNS_ENUMV(TETRA_4), 1, 1, 0, nodes.data(), &s));
    ok(cg_close(fn));
    ok(cg_open(path.c_str(), CG_MODE_MODIFY, &fn));
    change(fn, b, z);
    ok(cg_close(fn));
    return path;
  };
  const std::vector<Point> corners = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } };
  const auto none = [](int, int, int) {};
  CHECK(tetra("good.cgns", corners, { 1, 2, 3, 4 }, none) == dir + "/good.cgns" && readError(dir + "/good.cgns").empty());
  CHECK(contains(readError(tetra("missing.cgns", corners, { 1, 2, 3, 9 }, none)),
    "missing.cgns: /Base/solid/cells: element 1 refers to node 9; the zone has 4 nodes"));
  CHECK(contains(readError(tetra("nan.cgns", { { 0, 0, 0 }, { 1, std::nan(""), 0 }, { 0, 1, 0 }, { 0, 0, 1 } }, { 1, 2, 3, 4 }, none)),
    "nan.cgns: /Base/solid/GridCoordinates/CoordinateY: node 2's value is not a finite number"));
  CHECK(contains(readError(tetra("nocoordinates.cgns", { { 0, 0, 0 } }, { 1, 1, 1, 1 }, [](int fn, int b, int z) {
    ok(cg_goto(fn, b, "Zone_t", z, "end"));
    ok(cg_delete_node("GridCoordinates"));
  })),
    "nocoordinates.cgns: /Base/solid: has no grid coordinates"));
  CHECK(contains(readError(tetra("polar.cgns", corners, { 1, 2, 3, 4 }, [](int fn, int b, int z) {
    ok(cg_goto(fn, b, "Zone_t", z, "GridCoordinates_t", 1, "end"));
    ok(cg_delete_node("CoordinateX"));
  })),
    "polar.cgns: /Base/solid/GridCoordinates: has no CoordinateX (only Cartesian coordinates are supported)"));
  CHECK(contains(readError(tetra("bcnode.cgns", corners, { 1, 2, 3, 4 }, [](int fn, int b, int z) {
    writeBoco(fn, b, z, "inlet", CGNS_ENUMV(PointList), { 1, 7 }, 1, CGNS_ENUMV(Vertex), "");
  })),
    "bcnode.cgns: /Base/solid/ZoneBC/inlet: refers to node 7; the zone has 4 nodes"));
  CHECK(contains(readError(tetra("bcface.cgns", corners, { 1, 2, 3, 4 }, [](int fn, int b, int z) {
    writeBoco(fn, b, z, "wall", CGNS_ENUMV(PointRange), { 1, 2 }, 1, CGNS_ENUMV(FaceCenter), "");
  })),
    "bcface.cgns: /Base/solid/ZoneBC/wall: refers to element 2, which no section of the zone holds"));
  // a structured zone's BC beyond its points
  {
    const std::string path = dir + "/range.cgns";
    int fn = 0, b = 0, z = 0;
    ok(cg_open(path.c_str(), CG_MODE_WRITE, &fn));
    ok(cg_base_write(fn, "Base", 3, 3, &b));
    cgsize_t size[9] = { 2, 2, 2, 1, 1, 1, 0, 0, 0 };
    ok(cg_zone_write(fn, b, "box", size, CGNS_ENUMV(Structured), &z));
    writeCoordinates(fn, b, z, std::vector<Point>(8, Point{ 0, 0, 0 }), CGNS_ENUMV(RealDouble));
    writeBoco(fn, b, z, "side", CGNS_ENUMV(PointRange), { 1, 1, 1, 1, 2, 2 }, 3, CGNS_ENUMV(IFaceCenter), "");
    ok(cg_close(fn));
    CHECK(contains(readError(path), "range.cgns: /Base/box/ZoneBC/side: refers to nodes beyond the zone's 2 points along j"));
  }
  // no zones; not CGNS; not readable
  {
    int fn = 0, b = 0;
    ok(cg_open((dir + "/empty.cgns").c_str(), CG_MODE_WRITE, &fn));
    ok(cg_base_write(fn, "Base", 3, 3, &b));
    ok(cg_close(fn));
    CHECK(contains(readError(dir + "/empty.cgns"), "empty.cgns: has no zones"));
  }
  CHECK(contains(readError(writeFile(dir + "/text.cgns", "*HEADING\n")), "text.cgns: is not a CGNS file (neither HDF5 nor ADF)"));
  CHECK(contains(readError(writeFile(dir + "/cut.cgns", readFile(dir + "/good.cgns").substr(0, 700))),
    "cut.cgns: cannot be read by the CGNS library"));
  CHECK(contains(readError(dir + "/none.cgns"), "none.cgns: cannot be read"));
}

// the two bases' file for test_save_data_default.py (Save Data of its deformation in pvpython)
TEST_MAIN_WRITING([](const std::string& path) { writeTwoBases(path); })
