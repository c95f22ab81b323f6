// Exodus II meshes without VTK, written here with the netCDF API as the Exodus library lays them
// out: classic, 64-bit offset, CDF5 and netCDF-4 files read alike; a variant changes the coordinate
// variables and nothing else (every other variable, attribute and dimension compared through the
// API); VTK's node orders; side sets' nodes; bad files give an error naming the file and the
// variable.
#include "../TestHarness.h"
#include "Common/TextFile.h"
#include "Exodus/ExodusMesh.h"
#include "FormatFiles.h"

#include <netcdf.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

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
using testing::sameSets;
using testing::writeFile;

const testing::TestFolders folder{ "exodus" };
const testing::ReadErrors readError{ exodus::readExodus };

void ok(int status, const std::string& what)
{
  if (status != NC_NOERR)
  {
    throw std::runtime_error(what + ": " + nc_strerror(status));
  }
}

// ---- Exodus files written with the netCDF API --------------------------------------------------

struct BlockSpec
{
  std::int64_t id;
  std::string name, type;
  std::size_t nodesEach;
  std::vector<int> connect; // node numbers from 1 (none: a null block)
};

struct SetSpec
{
  std::int64_t id;
  std::string name;
  std::vector<int> entries; // node numbers, or a side set's element numbers (none: a null set)
  std::vector<int> sides;   // a side set's
};

struct Spec
{
  int mode = NC_CLOBBER; // nc_create's: the format
  int dimensions = 3;
  bool floats = false;
  bool combined = false; // one "coord" variable, as older files
  std::vector<double> xyz; // 3 a node
  std::vector<int> nodeMap, elementMap; // none: the 1-based positions
  std::vector<BlockSpec> blocks;
  std::vector<SetSpec> nodeSets, sideSets;
  bool names = true; // eb_names, ns_names, ss_names (else none)
};

// Writes spec at path as the Exodus library would (ex_put_init, ex_put_coord, ex_put_block,
// ex_put_conn, ex_put_set, ex_put_names, ex_put_qa, a nodal variable with one time step).
std::string writeExodus(const std::string& path, const Spec& spec)
{
  fs::create_directories(fs::path(path).parent_path());
  int nc = -1;
  ok(nc_create(path.c_str(), spec.mode, &nc), path);
  std::vector<std::function<void()>> puts; // after nc_enddef
  auto dimension = [&](const std::string& name, std::size_t length) {
    int id = -1;
    ok(nc_def_dim(nc, name.c_str(), length, &id), name);
    return id;
  };
  auto variable = [&](const std::string& name, nc_type type, std::vector<int> dimensions) {
    int id = -1;
    ok(nc_def_var(nc, name.c_str(), type, static_cast<int>(dimensions.size()), dimensions.data(), &id), name);
    return id;
  };
  auto integers = [&](const std::string& name, const std::vector<int>& values, std::vector<int> dimensions) {
    const int id = variable(name, NC_INT, dimensions);
    puts.push_back([=] { ok(nc_put_var_int(nc, id, values.data()), name); });
    return id;
  };
  auto texts = [&](const std::string& name, const std::vector<std::string>& values, std::vector<int> dimensions, std::size_t width) {
    const int id = variable(name, NC_CHAR, dimensions);
    std::string padded(values.size() * width, '\0');
    for (std::size_t i = 0; i < values.size(); ++i)
    {
      padded.replace(i * width, values[i].size(), values[i]);
    }
    puts.push_back([=] { ok(nc_put_var_text(nc, id, padded.data()), name); });
  };
  const int wordSize = spec.floats ? 4 : 8, fileSize = 1, nameLength = 32;
  const float version = 8.03f;
  ok(nc_put_att_float(nc, NC_GLOBAL, "api_version", NC_FLOAT, 1, &version), "api_version");
  ok(nc_put_att_float(nc, NC_GLOBAL, "version", NC_FLOAT, 1, &version), "version");
  ok(nc_put_att_int(nc, NC_GLOBAL, "floating_point_word_size", NC_INT, 1, &wordSize), "word size");
  ok(nc_put_att_int(nc, NC_GLOBAL, "file_size", NC_INT, 1, &fileSize), "file_size");
  ok(nc_put_att_int(nc, NC_GLOBAL, "maximum_name_length", NC_INT, 1, &nameLength), "maximum_name_length");
  ok(nc_put_att_text(nc, NC_GLOBAL, "title", 11, "a test mesh"), "title");
  const int lenString = dimension("len_string", 33), lenName = dimension("len_name", 33), four = dimension("four", 4);
  const int time = dimension("time_step", NC_UNLIMITED);
  const int dims = dimension("num_dim", static_cast<std::size_t>(spec.dimensions));
  const std::size_t count = spec.xyz.size() / 3;
  const int nodes = dimension("num_nodes", count);
  std::size_t elements = 0;
  for (const BlockSpec& block : spec.blocks)
  {
    elements += block.connect.size() / block.nodesEach;
  }
  const int elems = elements > 0 ? dimension("num_elem", elements) : -1;
  const nc_type real = spec.floats ? NC_FLOAT : NC_DOUBLE;
  auto reals = [&](const std::string& name, const std::vector<double>& values, std::vector<int> dimensions) {
    const int id = variable(name, real, dimensions);
    puts.push_back([=] { ok(nc_put_var_double(nc, id, values.data()), name); });
  };
  // coordinates: x, y, z one after the other
  std::vector<double> coordinates;
  for (int c = 0; c < spec.dimensions; ++c)
  {
    for (std::size_t k = 0; k < count; ++k)
    {
      coordinates.push_back(spec.xyz[3 * k + c]);
    }
  }
  if (spec.combined)
  {
    reals("coord", coordinates, { dims, nodes });
  }
  else
  {
    for (int c = 0; c < spec.dimensions; ++c)
    {
      const auto first = coordinates.begin() + static_cast<std::ptrdiff_t>(c * count);
      reals(std::string("coord") + "xyz"[c], std::vector<double>(first, first + static_cast<std::ptrdiff_t>(count)), { nodes });
    }
  }
  texts("coor_names", { "x", "y", "z" }, { dims, lenName }, 33);
  if (!spec.nodeMap.empty())
  {
    integers("node_num_map", spec.nodeMap, { nodes });
  }
  if (!spec.elementMap.empty())
  {
    integers("elem_num_map", spec.elementMap, { elems });
  }
  // entities of a kind: their count, status, ids and names
  auto entities = [&](const char* countName, const char* prefix, const char* namesName, std::vector<std::int64_t> ids,
                    std::vector<int> status, std::vector<std::string> names) {
    const int number = dimension(countName, ids.size());
    integers(std::string(prefix) + "_status", status, { number });
    const int prop = integers(std::string(prefix) + "_prop1", std::vector<int>(ids.begin(), ids.end()), { number });
    ok(nc_put_att_text(nc, prop, "name", 2, "ID"), "ID");
    if (spec.names)
    {
      texts(namesName, names, { number, lenName }, 33);
    }
  };
  if (!spec.blocks.empty())
  {
    std::vector<std::int64_t> ids;
    std::vector<int> status;
    std::vector<std::string> names;
    for (const BlockSpec& block : spec.blocks)
    {
      ids.push_back(block.id);
      status.push_back(block.connect.empty() ? 0 : 1);
      names.push_back(block.name);
    }
    entities("num_el_blk", "eb", "eb_names", ids, status, names);
    for (std::size_t b = 0; b < spec.blocks.size(); ++b)
    {
      const BlockSpec& block = spec.blocks[b];
      const std::string k = std::to_string(b + 1);
      if (!block.connect.empty())
      {
        const int connect = integers("connect" + k, block.connect,
          { dimension("num_el_in_blk" + k, block.connect.size() / block.nodesEach), dimension("num_nod_per_el" + k, block.nodesEach) });
        ok(nc_put_att_text(nc, connect, "elem_type", block.type.size(), block.type.c_str()), "elem_type");
      }
    }
  }
  auto sets = [&](const std::vector<SetSpec>& specs, const char* countName, const char* prefix, const char* namesName) {
    std::vector<std::int64_t> ids;
    std::vector<int> status;
    std::vector<std::string> names;
    for (const SetSpec& set : specs)
    {
      ids.push_back(set.id);
      status.push_back(set.entries.empty() ? 0 : 1);
      names.push_back(set.name);
    }
    entities(countName, prefix, namesName, ids, status, names);
  };
  if (!spec.nodeSets.empty())
  {
    sets(spec.nodeSets, "num_node_sets", "ns", "ns_names");
    for (std::size_t s = 0; s < spec.nodeSets.size(); ++s)
    {
      const std::string k = std::to_string(s + 1);
      if (!spec.nodeSets[s].entries.empty())
      {
        integers("node_ns" + k, spec.nodeSets[s].entries, { dimension("num_nod_ns" + k, spec.nodeSets[s].entries.size()) });
      }
    }
  }
  if (!spec.sideSets.empty())
  {
    sets(spec.sideSets, "num_side_sets", "ss", "ss_names");
    for (std::size_t s = 0; s < spec.sideSets.size(); ++s)
    {
      const std::string k = std::to_string(s + 1);
      if (!spec.sideSets[s].entries.empty())
      {
        const int sides = dimension("num_side_ss" + k, spec.sideSets[s].entries.size());
        integers("elem_ss" + k, spec.sideSets[s].entries, { sides });
        integers("side_ss" + k, spec.sideSets[s].sides, { sides });
      }
    }
  }
  // results: a QA record, a nodal variable at one time step
  texts("qa_records", { "TestExodusMesh", "1.0", "01/02/2024", "12:00:00" }, { dimension("num_qa_rec", 1), four, lenString }, 33);
  texts("name_nod_var", { "temperature" }, { dimension("num_nod_var", 1), lenName }, 33);
  const int times = variable("time_whole", NC_DOUBLE, { time });
  const int values = variable("vals_nod_var1", real, { time, nodes });
  ok(nc_put_att_text(nc, values, "units", 1, "K"), "units");
  ok(nc_enddef(nc), "enddef");
  for (const auto& put : puts)
  {
    put();
  }
  const double when = 0.5;
  const std::size_t start[2] = { 0, 0 }, counts[2] = { 1, count };
  std::vector<double> temperature(count);
  for (std::size_t k = 0; k < count; ++k)
  {
    temperature[k] = 20 + 0.25 * static_cast<double>(k);
  }
  ok(nc_put_vara_double(nc, times, start, counts, &when), "time_whole");
  ok(nc_put_vara_double(nc, values, start, counts, temperature.data()), "vals_nod_var1");
  ok(nc_close(nc), "close");
  return path;
}

// The formats nc_create writes.
const std::pair<const char*, int> netcdfFormats[] = { { "classic", NC_CLOBBER }, { "offset64", NC_CLOBBER | NC_64BIT_OFFSET },
  { "cdf5", NC_CLOBBER | NC_64BIT_DATA }, { "netcdf4", NC_CLOBBER | NC_NETCDF4 } };

// Node number i's id in mesh(): 100 + 7 (i - 1) mod 24, not in order.
std::int64_t nodeId(int number)
{
  return 100 + (7 * (number - 1)) % 24;
}

// A hexahedron (nodes 1-8), a 10-node tetrahedron (9-18) and a wedge (19-24) side by side, its
// 1-2-3 turning counter-clockwise seen from 4-5-6 as Exodus's do; node set "clamp" (the
// hexahedron's bottom, node 2 twice); side set "load": the hexahedron's side 5 (bottom), the
// tetrahedron's side 1, the wedge's sides 4 (bottom) and 1.
Spec mesh(int mode)
{
  Spec spec;
  spec.mode = mode;
  spec.xyz = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1, // hexahedron
    2, 0, 0, 3, 0, 0, 2, 1, 0, 2, 0, 1, 2.5, 0, 0, 2.5, 0.5, 0, 2, 0.5, 0, 2, 0, 0.5, 2.5, 0, 0.5, 2, 0.5, 0.5, // tetrahedron
    4, 0, 0, 5, 0, 0, 4, 1, 0, 4, 0, 1, 5, 0, 1, 4, 1, 1 }; // wedge
  for (int i = 1; i <= 24; ++i)
  {
    spec.nodeMap.push_back(static_cast<int>(nodeId(i)));
  }
  spec.elementMap = { 31, 12, 7 };
  spec.blocks = { { 10, "solid", "HEX8", 8, { 1, 2, 3, 4, 5, 6, 7, 8 } },
    { 20, "tip", "TETRA10", 10, { 9, 10, 11, 12, 13, 14, 15, 16, 17, 18 } }, { 30, "", "WEDGE6", 6, { 19, 20, 21, 22, 23, 24 } } };
  spec.nodeSets = { { 5, "clamp", { 1, 2, 3, 4, 2 }, {} } };
  spec.sideSets = { { 7, "load", { 1, 2, 3, 3 }, { 5, 1, 4, 1 } } };
  return spec;
}

std::vector<std::int64_t> nodeIds(std::initializer_list<int> numbers)
{
  std::vector<std::int64_t> ids;
  for (const int number : numbers)
  {
    ids.push_back(nodeId(number));
  }
  return ids;
}

// The file through the netCDF API, as text: its dimensions, attributes and variables with their
// values' bytes (but the coordinates' values, unless withCoordinates).
std::string describe(const std::string& path, bool withCoordinates)
{
  int nc = -1, dimensions = 0, variables = 0, attributes = 0, unlimited = -1;
  ok(nc_open(path.c_str(), NC_NOWRITE, &nc), path);
  ok(nc_inq(nc, &dimensions, &variables, &attributes, &unlimited), path);
  std::string out;
  char name[NC_MAX_NAME + 1];
  std::vector<std::size_t> lengths(static_cast<std::size_t>(dimensions));
  for (int d = 0; d < dimensions; ++d)
  {
    ok(nc_inq_dim(nc, d, name, &lengths[d]), path);
    out += "dimension " + std::string(name) + " " + std::to_string(lengths[d]) + (d == unlimited ? " unlimited\n" : "\n");
  }
  auto describeAttributes = [&](int variable, int count) {
    for (int a = 0; a < count; ++a)
    {
      nc_type type = NC_NAT;
      std::size_t length = 0, size = 0;
      ok(nc_inq_attname(nc, variable, a, name), path);
      ok(nc_inq_att(nc, variable, name, &type, &length), name);
      ok(nc_inq_type(nc, type, nullptr, &size), name);
      std::string bytes(length * size, '\0');
      ok(nc_get_att(nc, variable, name, bytes.data()), name);
      out += " attribute " + std::string(name) + " of type " + std::to_string(type) + ": " + bytes + "\n";
    }
  };
  describeAttributes(NC_GLOBAL, attributes);
  for (int v = 0; v < variables; ++v)
  {
    nc_type type = NC_NAT;
    int count = 0, ids[NC_MAX_VAR_DIMS], variableAttributes = 0;
    std::size_t size = 0, values = 1;
    ok(nc_inq_var(nc, v, name, &type, &count, ids, &variableAttributes), path);
    ok(nc_inq_type(nc, type, nullptr, &size), name);
    const std::string variable = name;
    out += "variable " + variable + " of type " + std::to_string(type) + " on";
    for (int d = 0; d < count; ++d)
    {
      out += " " + std::to_string(ids[d]);
      values *= lengths[ids[d]];
    }
    out += "\n";
    describeAttributes(v, variableAttributes);
    const bool coordinates = variable == "coord" || variable == "coordx" || variable == "coordy" || variable == "coordz";
    if (values > 0 && (withCoordinates || !coordinates))
    {
      std::string bytes(values * size, '\0');
      ok(nc_get_var(nc, v, bytes.data()), variable);
      out += " values: " + bytes + "\n";
    }
  }
  ok(nc_close(nc), path);
  return out;
}

// A copy of source at path, edited in place through the netCDF API.
std::string edited(const std::string& source, const std::string& path, const std::function<void(int)>& edit)
{
  fs::copy_file(source, path, fs::copy_options::overwrite_existing);
  int nc = -1;
  ok(nc_open(path.c_str(), NC_WRITE, &nc), path);
  edit(nc);
  ok(nc_close(nc), path);
  return path;
}

int variableId(int nc, const char* name)
{
  int id = -1;
  ok(nc_inq_varid(nc, name, &id), name);
  return id;
}

// (p1 - p0) x (p2 - p0) . (p3 - p0) of a block's first element's nodes corners.
double tripleProduct(const SourceMesh& mesh, const ElementBlock& block, std::array<int, 4> corners)
{
  return testing::tripleProduct(position(mesh, block.nodes[corners[0]]), position(mesh, block.nodes[corners[1]]),
    position(mesh, block.nodes[corners[2]]), position(mesh, block.nodes[corners[3]]));
}
} // namespace

TEST(FourFormatsReadAlike)
{
  const std::string dir = folder("read");
  const exodus::MeshFile first = exodus::readExodus(writeExodus(dir + "/classic.exo", mesh(NC_CLOBBER)));
  const SourceMesh& read = first.mesh;
  CHECK(read.nodeIds == nodeIds({ 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24 }));
  const Spec spec = mesh(NC_CLOBBER);
  CHECK(read.xyz == spec.xyz);
  CHECK(read.blocks.size() == 3);
  if (read.blocks.size() == 3)
  {
    CHECK(read.blocks[0].name == "HEX8" && read.blocks[0].type == CellType::Hexahedron && read.blocks[0].ids == std::vector<std::int64_t>{ 31 });
    CHECK(read.blocks[0].nodes == nodeIds({ 1, 2, 3, 4, 5, 6, 7, 8 }));
    CHECK(read.blocks[1].name == "TETRA10" && read.blocks[1].type == CellType::QuadraticTetra && read.blocks[1].ids == std::vector<std::int64_t>{ 12 });
    CHECK(read.blocks[1].nodes == nodeIds({ 9, 10, 11, 12, 13, 14, 15, 16, 17, 18 }));
    // VTK's wedge turns the other way
    CHECK(read.blocks[2].name == "WEDGE6" && read.blocks[2].type == CellType::Wedge && read.blocks[2].ids == std::vector<std::int64_t>{ 7 });
    CHECK(read.blocks[2].nodes == nodeIds({ 19, 21, 20, 22, 24, 23 }));
  }
  // the node set, each node once; the side set's nodes in the nodes' order
  CHECK(read.nodeSets.size() == 2);
  CHECK(find(read.nodeSets, "clamp") && find(read.nodeSets, "clamp")->ids == nodeIds({ 1, 2, 3, 4 }));
  CHECK(find(read.nodeSets, "load") && find(read.nodeSets, "load")->ids == nodeIds({ 1, 2, 3, 4, 9, 10, 12, 13, 16, 17, 19, 20, 21, 22, 23 }));
  // the blocks as element sets, one without a name by its id
  CHECK(read.elementSets.size() == 3);
  CHECK(find(read.elementSets, "solid") && find(read.elementSets, "solid")->ids == std::vector<std::int64_t>{ 31 });
  CHECK(find(read.elementSets, "tip") && find(read.elementSets, "tip")->ids == std::vector<std::int64_t>{ 12 });
  CHECK(find(read.elementSets, "block 30") && find(read.elementSets, "block 30")->ids == std::vector<std::int64_t>{ 7 });
  CHECK(read.warnings.empty());
  CHECK(first.dimensions == 3 && !first.floats && first.coordinates == (std::vector<std::string>{ "coordx", "coordy", "coordz" }));
  for (const auto& [name, mode] : netcdfFormats)
  {
    const std::string path = writeExodus(dir + "/" + name + ".exo", mesh(mode));
    const exodus::MeshFile other = exodus::readExodus(path);
    CHECK(sameMesh(other.mesh, read) && other.mesh.warnings.empty());
    // the layout: the node ids alone
    const exodus::MeshFile layout = exodus::readExodusLayout(path);
    CHECK(layout.mesh.nodeIds == read.nodeIds && layout.mesh.xyz.empty() && layout.mesh.blocks.empty() && layout.mesh.nodeSets.empty());
    CHECK(layout.coordinates == first.coordinates && layout.hash == other.hash);
    CHECK(exodus::isExodus(readFile(path).substr(0, 8)));
  }
  CHECK(!exodus::isExodus("CDF\x03") && !exodus::isExodus("*HEADING\n") && !exodus::isExodus("$MeshFormat\n") && !exodus::isExodus(""));
}

TEST(VariantChangesOnlyTheCoordinates)
{
  const std::string dir = folder("variant");
  for (const auto& [name, mode] : netcdfFormats)
  {
    const std::string source = writeExodus(dir + "/" + name + ".exo", mesh(mode));
    const exodus::MeshFile file = exodus::readExodus(source);
    const std::size_t count = file.mesh.nodeIds.size();
    const bool classic = std::string(name) != "netcdf4";
    // the same coordinates: the same file (a classic one byte for byte)
    file.writeVariant(dir + "/same/" + name + ".exo", file.mesh.nodeIds.data(), file.mesh.xyz.data(), count, false);
    CHECK(describe(dir + "/same/" + name + ".exo", true) == describe(source, true));
    CHECK(!classic || readFile(dir + "/same/" + name + ".exo") == readFile(source));
    // nodes 2 and 24 moved, given in reverse order
    std::vector<std::int64_t> ids(file.mesh.nodeIds.rbegin(), file.mesh.nodeIds.rend());
    std::vector<double> xyz;
    for (std::size_t i = count; i-- > 0;)
    {
      xyz.insert(xyz.end(), file.mesh.xyz.begin() + 3 * i, file.mesh.xyz.begin() + 3 * i + 3);
    }
    const double moved2[3] = { 1.0 / 3.0, 0.25, -1e-17 }, moved24[3] = { 4.1, 1, 1 + 1e-15 };
    std::copy(moved2, moved2 + 3, xyz.begin() + 3 * (count - 2));
    std::copy(moved24, moved24 + 3, xyz.begin());
    const std::string target = dir + "/moved/" + name + ".exo";
    file.writeVariant(target, ids.data(), xyz.data(), count, false);
    // every dimension, attribute and variable but the coordinates as they were
    CHECK(describe(target, false) == describe(source, false));
    CHECK(describe(target, true) != describe(source, true));
    if (classic)
    {
      // the same size, differing only in the moved doubles' bytes
      const std::string text = readFile(source), variant = readFile(target);
      CHECK(testing::changedAtMost(text, variant, 6 * 8));
    }
    // the moved nodes read back exactly
    const exodus::MeshFile again = exodus::readExodus(target);
    const Point at2 = position(again.mesh, nodeId(2)), at24 = position(again.mesh, nodeId(24));
    CHECK(at2 == (Point{ moved2[0], moved2[1], moved2[2] }) && at24 == (Point{ moved24[0], moved24[1], moved24[2] }));
    CHECK(position(again.mesh, nodeId(3)) == position(file.mesh, nodeId(3)));
    SourceMesh unmoved = again.mesh;
    unmoved.xyz = file.mesh.xyz;
    CHECK(sameMesh(unmoved, file.mesh));
    // the layout alone writes the same variant
    exodus::readExodusLayout(source).writeVariant(dir + "/layout/" + name + ".exo", ids.data(), xyz.data(), count, false);
    CHECK(describe(dir + "/layout/" + name + ".exo", true) == describe(target, true));
    CHECK(!classic || readFile(dir + "/layout/" + name + ".exo") == readFile(target));
  }
}

TEST(FloatCoordinatesRoundToTheNearestFloat)
{
  const std::string dir = folder("floats");
  Spec spec = mesh(NC_CLOBBER);
  spec.floats = true;
  spec.xyz[0] = 0.1; // stored as the float nearest 0.1
  const std::string source = writeExodus(dir + "/floats.exo", spec);
  const exodus::MeshFile file = exodus::readExodus(source);
  CHECK(file.floats);
  CHECK(file.mesh.xyz[0] == static_cast<double>(0.1f) && file.mesh.xyz[0] != 0.1);
  const std::size_t count = file.mesh.nodeIds.size();
  std::vector<double> xyz = file.mesh.xyz;
  xyz[3] = 0.3;                                                // node 2's x
  xyz[4] = -static_cast<double>(std::numeric_limits<float>::max()); // node 2's y: still a float
  const std::string target = dir + "/moved.exo";
  file.writeVariant(target, file.mesh.nodeIds.data(), xyz.data(), count, false);
  const exodus::MeshFile again = exodus::readExodus(target);
  CHECK(again.mesh.xyz[3] == static_cast<double>(0.3f) && std::abs(again.mesh.xyz[3] - 0.3) <= 0.3 * std::ldexp(1.0, -24));
  CHECK(again.mesh.xyz[4] == xyz[4]);
  // the unmoved nodes exactly, and all else
  std::vector<double> rest = again.mesh.xyz;
  rest[3] = file.mesh.xyz[3];
  rest[4] = file.mesh.xyz[4];
  CHECK(rest == file.mesh.xyz);
  CHECK(describe(target, false) == describe(source, false));
  // beyond a float's range: refused, nothing written
  xyz[5] = 1e39;
  CHECK(contains(testing::readError([&] { file.writeVariant(dir + "/far.exo", file.mesh.nodeIds.data(), xyz.data(), count, false); }),
    "far.exo: node " + std::to_string(nodeId(2)) + "'s coordinate 1e+39 is beyond the floats"));
  CHECK(!fs::exists(dir + "/far.exo"));
}

TEST(VariantRefusesOtherDataAndNeverHalfWrites)
{
  const std::string dir = folder("refuse");
  for (const auto& [name, mode] : { netcdfFormats[0], netcdfFormats[3] })
  {
    const std::string source = writeExodus(dir + "/" + name + ".exo", mesh(mode));
    const exodus::MeshFile file = exodus::readExodus(source);
    // netCDF failing on the copy (a coordinate variable the file does not have): nothing written
    exodus::MeshFile wrong = file;
    wrong.coordinates[2] = "coordw";
    CHECK(contains(testing::writeError(wrong, dir + "/w/" + name + ".exo", file.mesh.nodeIds, file.mesh.xyz),
      name + std::string(".exo: coordw: the file has no such variable")));
    CHECK(!fs::exists(dir + "/w/" + name + ".exo"));
    // the refusals of every format; a variant of the same nodes is the source through the API
    testing::checkVariantRefusals(file, source, dir, "x", "",
      [](const std::string& target, const std::string& from) { return describe(target, true) == describe(from, true); });
  }
}

namespace
{
// One element of each type in a block of its own (ids 1, 2...), with nodes of its own where Exodus
// numbers them (exodus-element-types.md, PATRAN's numbering): the corners, then nodes at the
// middle of the corners between (a tetrahedron's midside nodes 4-9 on 0-1 1-2 2-0 0-3 1-3 2-3; a
// hexahedron's 8-19 on 0-1 1-2 2-3 3-0 0-4 1-5 2-6 3-7 4-5 5-6 6-7 7-4, 20 its centre, 21-26 the
// centres of the faces z=0 z=1 x=0 x=1 y=0 y=1; a wedge's 6-14 on 0-1 1-2 2-0 0-3 1-4 2-5 3-4 4-5
// 5-3, its 0-1-2 turning counter-clockwise seen from 3-4-5). No node_num_map: node i's id is i.
Spec orders()
{
  const std::vector<Point> tetra = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 } },
                           hex = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } },
                           wedge = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 0, 1, 1 } },
                           quad = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 } };
  const std::vector<std::vector<int>> tetraEdges = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 0, 3 }, { 1, 3 }, { 2, 3 } },
                                      hexEdges = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 },
                                        { 4, 5 }, { 5, 6 }, { 6, 7 }, { 7, 4 }, { 0, 1, 2, 3, 4, 5, 6, 7 }, { 0, 1, 2, 3 },
                                        { 4, 5, 6, 7 }, { 0, 3, 7, 4 }, { 1, 2, 6, 5 }, { 0, 1, 5, 4 }, { 2, 3, 7, 6 } },
                                      wedgeEdges = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 0, 3 }, { 1, 4 }, { 2, 5 }, { 3, 4 }, { 4, 5 },
                                        { 5, 3 } };
  Spec spec;
  auto add = [&](const std::string& type, const std::vector<Point>& corners, const std::vector<std::vector<int>>& between,
               std::size_t count) {
    // the corners stretched and moved apart, so that no two nodes of the mesh meet
    const double offset = 10.0 * static_cast<double>(spec.blocks.size());
    std::vector<Point> points;
    for (const Point& corner : corners)
    {
      points.push_back({ offset + corner[0] * 2, corner[1] * 3, corner[2] * 5 });
    }
    for (std::size_t m = 0; points.size() < count; ++m)
    {
      Point sum{ 0, 0, 0 };
      for (const int corner : between[m])
      {
        for (int c = 0; c < 3; ++c)
        {
          sum[c] += points[corner][c] / static_cast<double>(between[m].size());
        }
      }
      points.push_back(sum);
    }
    BlockSpec block{ static_cast<std::int64_t>(spec.blocks.size() + 1), "", type, count, {} };
    for (const Point& p : points)
    {
      spec.xyz.insert(spec.xyz.end(), p.begin(), p.end());
      block.connect.push_back(static_cast<int>(spec.xyz.size() / 3));
    }
    spec.blocks.push_back(block);
  };
  add("TETRA10", tetra, tetraEdges, 10);
  add("HEX20", hex, hexEdges, 20);
  add("hex27", hex, hexEdges, 27);
  add("WEDGE15", wedge, wedgeEdges, 15);
  add("WEDGE", wedge, {}, 6);
  add("TETRA4", tetra, {}, 4);
  add("HEX8", hex, {}, 8);
  add("SHELL4", quad, {}, 4);
  return spec;
}

} // namespace

TEST(NodeOrdersAreVtks)
{
  const std::string dir = folder("orders");
  Spec spec = orders();
  spec.names = false;
  const exodus::MeshFile file = exodus::readExodus(writeExodus(dir + "/orders.exo", spec));
  const SourceMesh& mesh = file.mesh;
  CHECK(mesh.warnings.empty());
  // no eb_names: the blocks by their ids
  CHECK(mesh.elementSets.size() == 8 && mesh.elementSets[0].name == "block 1" && mesh.elementSets[7].name == "block 8");
  CHECK(mesh.blocks.size() == 8);
  if (mesh.blocks.size() != 8)
  {
    return;
  }
  const ElementBlock &tetra10 = mesh.blocks[0], &hex20 = mesh.blocks[1], &hex27 = mesh.blocks[2], &wedge15 = mesh.blocks[3],
                     &wedge6 = mesh.blocks[4], &tetra4 = mesh.blocks[5], &hex8 = mesh.blocks[6], &shell4 = mesh.blocks[7];
  CHECK(tetra10.type == CellType::QuadraticTetra && hex20.type == CellType::QuadraticHexahedron);
  CHECK(hex27.type == CellType::TriQuadraticHexahedron && hex27.name == "hex27");
  CHECK(wedge15.type == CellType::QuadraticWedge && wedge6.type == CellType::Wedge && shell4.type == CellType::Quad);
  // VTK's edges (vtkQuadraticTetra, vtkQuadraticHexahedron, vtkQuadraticWedge)
  const std::vector<std::array<int, 2>> vtkTetraEdges = { { { 0, 1 } }, { { 1, 2 } }, { { 2, 0 } }, { { 0, 3 } }, { { 1, 3 } }, { { 2, 3 } } },
                                        vtkHexEdges = { { { 0, 1 } }, { { 1, 2 } }, { { 2, 3 } }, { { 3, 0 } }, { { 4, 5 } }, { { 5, 6 } },
                                          { { 6, 7 } }, { { 7, 4 } }, { { 0, 4 } }, { { 1, 5 } }, { { 2, 6 } }, { { 3, 7 } } },
                                        vtkWedgeEdges = { { { 0, 1 } }, { { 1, 2 } }, { { 2, 0 } }, { { 3, 4 } }, { { 4, 5 } }, { { 5, 3 } },
                                          { { 0, 3 } }, { { 1, 4 } }, { { 2, 5 } } };
  CHECK(midsideNodesOnTheirEdges(mesh, tetra10, 4, vtkTetraEdges));
  CHECK(midsideNodesOnTheirEdges(mesh, hex20, 8, vtkHexEdges));
  CHECK(midsideNodesOnTheirEdges(mesh, hex27, 8, vtkHexEdges));
  CHECK(midsideNodesOnTheirEdges(mesh, wedge15, 6, vtkWedgeEdges));
  // vtkTriQuadraticHexahedron's face centres 20-25: x = 0, x = 1, y = 0, y = 1, z = 0, z = 1; 26 the centre
  const Point low = position(mesh, hex27.nodes[0]), high = position(mesh, hex27.nodes[6]);
  const Point middle{ (low[0] + high[0]) / 2, (low[1] + high[1]) / 2, (low[2] + high[2]) / 2 };
  for (int f = 0; f < 6; ++f)
  {
    Point centre = middle;
    centre[f / 2] = f % 2 == 0 ? low[f / 2] : high[f / 2];
    CHECK(position(mesh, hex27.nodes[20 + f]) == centre);
  }
  CHECK(position(mesh, hex27.nodes[26]) == middle);
  // VTK's wedge turns 0-1-2 away from 3-4-5: Exodus's 0 2 1 3 5 4
  CHECK(wedge6.nodes == (std::vector<std::int64_t>{ 73, 75, 74, 76, 78, 77 }));
  CHECK(tripleProduct(mesh, wedge6, { 0, 1, 2, 3 }) < 0 && tripleProduct(mesh, wedge15, { 0, 1, 2, 3 }) < 0);
  CHECK(tripleProduct(mesh, tetra4, { 0, 1, 2, 3 }) > 0 && tripleProduct(mesh, tetra10, { 0, 1, 2, 3 }) > 0);
  CHECK(tripleProduct(mesh, hex8, { 0, 1, 3, 4 }) > 0 && tripleProduct(mesh, hex20, { 0, 1, 3, 4 }) > 0 &&
    tripleProduct(mesh, hex27, { 0, 1, 3, 4 }) > 0);
}

TEST(SideSetsHoldTheirSidesNodes)
{
  // every side of each 3D element, a side set each, holds the element's nodes (midside and face
  // nodes too) on that side's plane: Exodus's sides (exodus-element-types.md) of a hexahedron are
  // y=0, x=1, y=1, x=0, z=0, z=1; of a tetrahedron y=0, x+y+z=1, x=0, z=0; of a wedge y=0, x+y=1,
  // x=0, z=0, z=1; a shell's sides 1 and 2 are its faces, 3-6 its edges y=0, x=1, y=1, x=0
  struct Plane
  {
    double x, y, z, d; // x u + y v + z w = d, (u, v, w) the reference coordinates orders() stretched
  };
  const std::vector<Plane> hex = { { 0, 1, 0, 0 }, { 1, 0, 0, 1 }, { 0, 1, 0, 1 }, { 1, 0, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 1, 1 } },
                           tetra = { { 0, 1, 0, 0 }, { 1, 1, 1, 1 }, { 1, 0, 0, 0 }, { 0, 0, 1, 0 } },
                           wedge = { { 0, 1, 0, 0 }, { 1, 1, 0, 1 }, { 1, 0, 0, 0 }, { 0, 0, 1, 0 }, { 0, 0, 1, 1 } },
                           shell = { { 0, 0, 1, 0 }, { 0, 0, 1, 0 }, { 0, 1, 0, 0 }, { 1, 0, 0, 1 }, { 0, 1, 0, 1 }, { 1, 0, 0, 0 } };
  const std::vector<Plane>* planes[] = { &tetra, &hex, &hex, &wedge, &wedge, &tetra, &hex, &shell }; // orders()' blocks
  Spec spec = orders();
  for (int b = 0; b < 8; ++b)
  {
    for (std::size_t side = 1; side <= planes[b]->size(); ++side)
    {
      const int id = static_cast<int>(spec.sideSets.size() + 1);
      spec.sideSets.push_back({ id, "block " + std::to_string(b + 1) + " side " + std::to_string(side), { b + 1 }, { static_cast<int>(side) } });
    }
  }
  const std::string dir = folder("sides");
  const exodus::MeshFile file = exodus::readExodus(writeExodus(dir + "/sides.exo", spec));
  const SourceMesh& mesh = file.mesh;
  CHECK(mesh.warnings.empty() && mesh.nodeSets.size() == spec.sideSets.size() && mesh.blocks.size() == 8);
  if (mesh.nodeSets.size() != spec.sideSets.size() || mesh.blocks.size() != 8)
  {
    return;
  }
  std::size_t set = 0;
  for (int b = 0; b < 8; ++b)
  {
    for (const Plane& plane : *planes[b])
    {
      std::vector<std::int64_t> expected;
      for (const std::int64_t id : mesh.blocks[b].nodes)
      {
        const Point p = position(mesh, id);
        const double u = (p[0] - 10.0 * b) / 2, v = p[1] / 3, w = p[2] / 5;
        if (plane.x * u + plane.y * v + plane.z * w == plane.d)
        {
          expected.push_back(id);
        }
      }
      std::sort(expected.begin(), expected.end()); // ids are the nodes' positions + 1
      CHECK(mesh.nodeSets[set].name == spec.sideSets[set].name && mesh.nodeSets[set].ids == expected && expected.size() >= 2);
      if (mesh.nodeSets[set].ids != expected)
      {
        std::printf("%s: %zu nodes, %zu expected\n", mesh.nodeSets[set].name.c_str(), mesh.nodeSets[set].ids.size(), expected.size());
      }
      ++set;
    }
  }
}

TEST(TwoDimensionalMeshOfOldLayout)
{
  // a 2D mesh's one "coord" variable, no maps (the ids are the positions), names shared by a node
  // set and a side set, a set and blocks without names; a 2D mesh's sides are edges (a 6-node
  // triangle's side 3 is 3-1 and its midside node 6)
  const std::string dir = folder("twod");
  Spec spec;
  spec.dimensions = 2;
  spec.combined = true;
  spec.xyz = { 0, 0, 0, 2, 0, 0, 2, 2, 0, 0, 2, 0, 1, 0, 0, 2, 1, 0, 1, 2, 0, 0, 1, 0, // QUAD8
    3, 0, 0, 5, 0, 0, 3, 2, 0, 4, 0, 0, 4, 1, 0, 3, 1, 0 };                             // TRI6
  spec.blocks = { { 1, "", "QUAD8", 8, { 1, 2, 3, 4, 5, 6, 7, 8 } }, { 2, "", "TRI6", 6, { 9, 10, 11, 12, 13, 14 } } };
  spec.nodeSets = { { 3, "edge", { 1, 2, 5 }, {} }, { 9, "", { 9 }, {} } };
  spec.sideSets = { { 4, "edge", { 1, 2 }, { 2, 3 } } };
  const std::string source = writeExodus(dir + "/plate.exo", spec);
  const exodus::MeshFile file = exodus::readExodus(source);
  const SourceMesh& mesh = file.mesh;
  CHECK(file.dimensions == 2 && file.coordinates == std::vector<std::string>{ "coord" });
  CHECK(mesh.nodeIds == (std::vector<std::int64_t>{ 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14 }) && mesh.xyz == spec.xyz);
  CHECK(mesh.blocks.size() == 2 && mesh.blocks[0].type == CellType::QuadraticQuad && mesh.blocks[1].type == CellType::QuadraticTriangle);
  CHECK(mesh.blocks.size() == 2 && mesh.blocks[0].ids == std::vector<std::int64_t>{ 1 } && mesh.blocks[1].ids == std::vector<std::int64_t>{ 2 });
  CHECK(sameSets(mesh.elementSets, { { "block 1", { 1 } }, { "block 2", { 2 } } }));
  CHECK(sameSets(mesh.nodeSets, { { "edge (nodeset 3)", { 1, 2, 5 } }, { "nodeset 9", { 9 } }, { "edge (sideset 4)", { 2, 3, 6, 9, 11, 14 } } }));
  // the variant: x and y moved; a z not 0 refused
  std::vector<double> xyz = mesh.xyz;
  xyz[3 * 4 + 1] = -0.5;
  xyz[3 * 13] = 2.75;
  const std::string target = dir + "/moved.exo";
  file.writeVariant(target, mesh.nodeIds.data(), xyz.data(), mesh.nodeIds.size(), false);
  CHECK(exodus::readExodus(target).mesh.xyz == xyz);
  CHECK(describe(target, false) == describe(source, false));
  xyz[3 * 2 + 2] = 1e-9;
  CHECK(contains(testing::readError([&] { file.writeVariant(dir + "/z.exo", mesh.nodeIds.data(), xyz.data(), mesh.nodeIds.size(), false); }),
    "z.exo: node 3 is moved out of the mesh's 2D space (its coordinate 3 is 1e-09, not 0)"));
  CHECK(!fs::exists(dir + "/z.exo"));
}

TEST(UnsupportedTypesAreLeftOutWithAWarning)
{
  // a hexahedron (id 100), a null block, two 9-node hexahedra (no cell type: 200, 201), a
  // tetrahedron (300); a side set on the second 9-node one and on the tetrahedron; a null node set
  // and a null side set, left out
  const std::string dir = folder("unsupported");
  Spec spec;
  spec.xyz = { 0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1, 0.5, 0.5, 0.5, // 1-9
    2, 0, 0, 3, 0, 0, 2, 1, 0, 2, 0, 1 };                                                     // 10-13
  spec.elementMap = { 100, 200, 201, 300 };
  spec.blocks = { { 1, "brick", "HEX8", 8, { 1, 2, 3, 4, 5, 6, 7, 8 } }, { 2, "none", "TETRA4", 4, {} },
    { 3, "bubbles", "HEX9", 9, { 1, 2, 3, 4, 5, 6, 7, 8, 9, 1, 2, 3, 4, 5, 6, 7, 8, 9 } }, { 4, "tip", "TETRA4", 4, { 10, 11, 12, 13 } } };
  spec.sideSets = { { 1, "nothing", {}, {} }, { 2, "faces", { 3, 4 }, { 1, 4 } } };
  spec.nodeSets = { { 1, "nobody", {}, {} } };
  const exodus::MeshFile file = exodus::readExodus(writeExodus(dir + "/mixed.exo", spec));
  const SourceMesh& mesh = file.mesh;
  CHECK(mesh.blocks.size() == 2);
  CHECK(mesh.blocks.size() == 2 && mesh.blocks[0].ids == std::vector<std::int64_t>{ 100 } && mesh.blocks[1].ids == std::vector<std::int64_t>{ 300 });
  CHECK(sameSets(mesh.elementSets, { { "brick", { 100 } }, { "tip", { 300 } } }));
  // the tetrahedron's side 4 (1-3-2); the 9-node hexahedron's side left out
  CHECK(sameSets(mesh.nodeSets, { { "faces", { 10, 11, 12 } } }));
  for (const std::string& warning : mesh.warnings)
  {
    std::printf("warning: %s\n", warning.c_str());
  }
  CHECK(mesh.warnings.size() == 2);
  CHECK(mesh.warnings.size() == 2 && contains(mesh.warnings[0], "mixed.exo: connect3: element type \"HEX9\" with 9 nodes (block 3) is not supported: its 2 elements are left out"));
  CHECK(mesh.warnings.size() == 2 && contains(mesh.warnings[1], "mixed.exo: elem_ss2: 1 sides of sideset 2 are of elements of type \"HEX9\", whose sides are not read"));
  CHECK(mesh.nodeIds.size() == 13);
}

TEST(BadFilesNameTheFileAndTheVariable)
{
  const std::string dir = folder("bad");
  const std::string good = writeExodus(dir + "/good.exo", mesh(NC_CLOBBER));
  auto put = [](int nc, const char* name, std::vector<std::size_t> at, int value) {
    ok(nc_put_var1_int(nc, variableId(nc, name), at.data(), &value), name);
  };
  CHECK(contains(readError(writeFile(dir + "/text.exo", "*HEADING\n")), "text.exo: is not a netCDF file, or is damaged"));
  // cut short: in its header, in its data; a netCDF-4 file
  CHECK(contains(readError(writeFile(dir + "/cut.exo", readFile(good).substr(0, 200))),
    "cut.exo: is not a netCDF file, or is damaged (the file ends before its data does: is it cut short?)"));
  CHECK(contains(readError(writeFile(dir + "/cutdata.exo", readFile(good).substr(0, 2000))),
    "cutdata.exo: node_num_map: the file ends before its data does: is it cut short?"));
  const std::string netcdf4 = readFile(writeExodus(dir + "/netcdf4.exo", mesh(NC_CLOBBER | NC_NETCDF4)));
  CHECK(contains(readError(writeFile(dir + "/cut4.exo", netcdf4.substr(0, netcdf4.size() / 2))), "cut4.exo: is not a netCDF file, or is damaged"));
  CHECK(contains(readError(dir + "/none.exo"), "none.exo: cannot be read"));
  // netCDF, not Exodus
  int nc = -1, dimension = -1, variable = -1;
  const double values[3] = { 1, 2, 3 };
  ok(nc_create((dir + "/empty.exo").c_str(), NC_CLOBBER, &nc), "empty");
  ok(nc_def_dim(nc, "x", 3, &dimension), "x");
  ok(nc_def_var(nc, "temperature", NC_DOUBLE, 1, &dimension, &variable), "temperature");
  ok(nc_enddef(nc), "enddef");
  ok(nc_put_var_double(nc, variable, values), "temperature");
  ok(nc_close(nc), "empty");
  CHECK(contains(readError(dir + "/empty.exo"), "empty.exo: num_nodes: the file has no nodes"));
  CHECK(contains(readError(edited(good, dir + "/nocoordinates.exo",
                   [](int nc) {
                     ok(nc_redef(nc), "redef");
                     ok(nc_rename_var(nc, variableId(nc, "coordx"), "x"), "rename");
                   })),
    "nocoordinates.exo: coordx: the file has no coordinates (coordx or coord)"));
  CHECK(contains(readError(edited(good, dir + "/nan.exo",
                   [](int nc) {
                     const std::size_t at = 6;
                     const double nan = std::numeric_limits<double>::quiet_NaN();
                     ok(nc_put_var1_double(nc, variableId(nc, "coordy"), &at, &nan), "coordy");
                   })),
    "nan.exo: coordy: node " + std::to_string(nodeId(7)) + "'s coordinate nan is not a finite number"));
  CHECK(contains(readError(edited(good, dir + "/twice.exo", [&](int nc) { put(nc, "node_num_map", { 5 }, static_cast<int>(nodeId(3))); })),
    "twice.exo: node_num_map: node id " + std::to_string(nodeId(3)) + " comes twice"));
  CHECK(contains(readError(edited(good, dir + "/eltwice.exo", [&](int nc) { put(nc, "elem_num_map", { 2 }, 31); })),
    "eltwice.exo: elem_num_map: element id 31 comes twice"));
  CHECK(contains(readError(edited(good, dir + "/missing.exo", [&](int nc) { put(nc, "connect2", { 0, 7 }, 25); })),
    "missing.exo: connect2: element 12 refers to node number 25, not one of the file's 24 nodes"));
  CHECK(contains(readError(edited(good, dir + "/zero.exo", [&](int nc) { put(nc, "connect1", { 0, 0 }, 0); })),
    "zero.exo: connect1: element 31 refers to node number 0, not one of the file's 24 nodes"));
  CHECK(contains(readError(edited(good, dir + "/set.exo", [&](int nc) { put(nc, "node_ns1", { 4 }, -1); })),
    "set.exo: node_ns1: entry 5 refers to node number -1, not one of the file's 24 nodes"));
  CHECK(contains(readError(edited(good, dir + "/side.exo", [&](int nc) { put(nc, "side_ss1", { 0 }, 7); })),
    "side.exo: side_ss1: element 31 (HEX8) has no side 7 (it has 6)"));
  CHECK(contains(readError(edited(good, dir + "/sideelement.exo", [&](int nc) { put(nc, "elem_ss1", { 1 }, 4); })),
    "sideelement.exo: elem_ss1: side 2 refers to element number 4, not one of the file's 3 elements"));
}

// the mesh of three blocks with its node and side sets for test_save_data_default.py
TEST_MAIN_WRITING([](const std::string& path) { writeExodus(path, mesh(NC_CLOBBER)); })
