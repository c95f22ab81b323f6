#include "Exodus/ExodusMesh.h"

#include "Common/IdIndex.h"
#include "Common/TextFile.h"
#include "Common/VariantNodes.h"

#include <netcdf.h>
#include <netcdf_mem.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <numeric>
#include <string_view>
#include <utility>


namespace mlsformats
{
namespace exodus
{
namespace
{
// ---- the netCDF file ---------------------------------------------------------------------------

// An open netCDF file. Errors name the file (as name: a variant's target, not the copy opened)
// and the variable: "file: connect2: reason".
class NetCDF
{
public:
  // Opens the file's bytes, read only (what is read is what was hashed).
  NetCDF(const std::string& name, std::string& bytes)
    : Name(name)
    // a count of values no file of this size holds, even compressed: refused before it is allocated
    , Limit(64 * bytes.size() + (1u << 20))
  {
    const int status = nc_open_mem(name.c_str(), NC_NOWRITE, bytes.size(), bytes.data(), &this->Id);
    if (status != NC_NOERR)
    {
      throw FileError(name, 0, "is not a netCDF file, or is damaged (" + this->reason(status) + ")");
    }
  }

  // Opens the file at path to write in it.
  NetCDF(const std::string& name, const std::string& path)
    : Name(name)
    , Limit(std::numeric_limits<std::size_t>::max())
    , InMemory(false)
  {
    const int status = nc_open(path.c_str(), NC_WRITE, &this->Id);
    if (status != NC_NOERR)
    {
      throw FileError(name, 0, "cannot be opened by netCDF to be written (" + this->reason(status) + ")");
    }
  }

  NetCDF(const NetCDF&) = delete;
  NetCDF& operator=(const NetCDF&) = delete;

  ~NetCDF()
  {
    if (this->Id >= 0)
    {
      nc_close(this->Id);
    }
  }

  // Closes the file, its writes flushed.
  void close()
  {
    const int status = nc_close(this->Id);
    this->Id = -1;
    if (status != NC_NOERR)
    {
      throw FileError(this->Name, 0, "cannot be written (" + this->reason(status) + ")");
    }
  }

  [[noreturn]] void fail(const std::string& variable, const std::string& reason) const
  {
    throw FileError(this->Name, 0, variable + ": " + reason);
  }

  void check(int status, const std::string& variable) const
  {
    if (status != NC_NOERR)
    {
      this->fail(variable, this->reason(status));
    }
  }

  // The length of a dimension, 0 when the file has none of that name (Exodus leaves out the
  // dimensions of what has no entries).
  std::size_t dimension(const std::string& name) const
  {
    int id = -1;
    std::size_t length = 0;
    return nc_inq_dimid(this->Id, name.c_str(), &id) == NC_NOERR && nc_inq_dimlen(this->Id, id, &length) == NC_NOERR ? length : 0;
  }

  bool has(const std::string& variable) const
  {
    int id = -1;
    return nc_inq_varid(this->Id, variable.c_str(), &id) == NC_NOERR;
  }

  nc_type type(const std::string& variable) const
  {
    nc_type type = NC_NAT;
    this->check(nc_inq_vartype(this->Id, this->variable(variable), &type), variable);
    return type;
  }

  // A variable's text attribute, "" when it has none.
  std::string attribute(const std::string& variable, const char* name) const
  {
    int id = -1;
    nc_type type = NC_NAT;
    std::size_t length = 0;
    if (nc_inq_varid(this->Id, variable.c_str(), &id) != NC_NOERR || nc_inq_att(this->Id, id, name, &type, &length) != NC_NOERR ||
      type != NC_CHAR)
    {
      return "";
    }
    std::string text(length, '\0');
    this->check(nc_get_att_text(this->Id, id, name, text.data()), variable);
    return trimmed(text);
  }

  std::vector<std::int64_t> integers(const std::string& variable, std::size_t count) const
  {
    const int id = this->sized(variable, count);
    std::vector<long long> values(count);
    this->check(nc_get_var_longlong(this->Id, id, values.data()), variable);
    return std::vector<std::int64_t>(values.begin(), values.end());
  }

  std::vector<double> reals(const std::string& variable, std::size_t count) const
  {
    const int id = this->sized(variable, count);
    std::vector<double> values(count);
    this->check(nc_get_var_double(this->Id, id, values.data()), variable);
    return values;
  }

  void write(const std::string& variable, const double* values, std::size_t count) const
  {
    this->check(nc_put_var_double(this->Id, this->sized(variable, count), values), variable);
  }

  // Fails unless count values (of variable) are not beyond what the file can hold.
  void room(std::size_t count, const std::string& variable) const
  {
    if (count > this->Limit)
    {
      this->fail(variable, std::to_string(count) + " values: more than the file can hold (is it damaged?)");
    }
  }

  // Fails unless variable holds count values.
  void expect(const std::string& variable, std::size_t count) const
  {
    this->sized(variable, count);
  }

  // The count names of a names variable (eb_names: entities x len_name characters), each without
  // its trailing NULs and blanks; all "" when the file has no such variable.
  std::vector<std::string> names(const std::string& variable, std::size_t count) const
  {
    std::vector<std::string> out(count);
    if (!this->has(variable))
    {
      return out;
    }
    const std::vector<std::size_t> shape = this->shape(variable);
    if (shape.size() != 2 || shape[0] != count)
    {
      this->fail(variable, "is not " + std::to_string(count) + " names");
    }
    const int id = this->sized(variable, count * shape[1]);
    std::string text(count * shape[1], '\0');
    this->check(nc_get_var_text(this->Id, id, text.data()), variable);
    for (std::size_t i = 0; i < count; ++i)
    {
      out[i] = trimmed(text.substr(i * shape[1], shape[1]));
    }
    return out;
  }

private:
  std::string Name;
  std::size_t Limit;
  bool InMemory = true;
  int Id = -1;

  // What a netCDF status says; reading from memory, EPERM is netCDF asking for bytes beyond them.
  std::string reason(int status) const
  {
    return this->InMemory && status == EPERM ? "the file ends before its data does: is it cut short?" : nc_strerror(status);
  }

  static std::string trimmed(std::string text)
  {
    text.resize(std::min(text.find('\0'), text.size()));
    const std::size_t first = text.find_first_not_of(' '), last = text.find_last_not_of(' ');
    return first == std::string::npos ? std::string() : text.substr(first, last - first + 1);
  }

  int variable(const std::string& variable) const
  {
    int id = -1;
    if (nc_inq_varid(this->Id, variable.c_str(), &id) != NC_NOERR)
    {
      this->fail(variable, "the file has no such variable");
    }
    return id;
  }

  std::vector<std::size_t> shape(const std::string& variable) const
  {
    const int id = this->variable(variable);
    int count = 0;
    this->check(nc_inq_varndims(this->Id, id, &count), variable);
    std::vector<int> dimensions(static_cast<std::size_t>(count));
    this->check(nc_inq_vardimid(this->Id, id, dimensions.data()), variable);
    std::vector<std::size_t> lengths(dimensions.size());
    for (std::size_t d = 0; d < dimensions.size(); ++d)
    {
      this->check(nc_inq_dimlen(this->Id, dimensions[d], &lengths[d]), variable);
    }
    return lengths;
  }

  // The variable's id, once it is known to hold count values (and count is not beyond the file).
  int sized(const std::string& variable, std::size_t count) const
  {
    this->room(count, variable);
    std::size_t values = 1;
    for (const std::size_t length : this->shape(variable))
    {
      values = length != 0 && values > std::numeric_limits<std::size_t>::max() / length ? 0 : values * length;
    }
    if (values != count)
    {
      this->fail(variable, "holds " + std::to_string(values) + " values where " + std::to_string(count) + " are expected");
    }
    return this->variable(variable);
  }
};

// A number as an error message writes it: its shortest text.
std::string text(double value)
{
  std::string out;
  appendShortest(out, value);
  return out;
}

// ---- element types -----------------------------------------------------------------------------

// The element shapes (exodus-element-types.md), told apart as the Exodus library does
// (exi_get_block_param): by the first three letters of elem_type upper-cased ("HEX8",
// "hexahedron", "tet"; "TRISHELL" is a triangle).
enum class Shape
{
  None,
  Point,
  Line,
  Triangle,
  Quad,
  Shell,
  Tetra,
  Pyramid,
  Wedge,
  Hex
};

Shape shapeOf(std::string type)
{
  std::transform(type.begin(), type.end(), type.begin(), [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
  static const std::pair<const char*, Shape> prefixes[] = { { "CIR", Shape::Point }, { "SPH", Shape::Point },
    { "BAR", Shape::Line }, { "BEA", Shape::Line }, { "TRU", Shape::Line }, { "EDG", Shape::Line }, { "TRI", Shape::Triangle },
    { "QUA", Shape::Quad }, { "SHE", Shape::Shell }, { "TET", Shape::Tetra }, { "PYR", Shape::Pyramid }, { "WED", Shape::Wedge },
    { "HEX", Shape::Hex } };
  for (const auto& [prefix, shape] : prefixes)
  {
    if (type.compare(0, 3, prefix) == 0)
    {
      return shape;
    }
  }
  return Shape::None;
}

struct CellKind
{
  Shape shape;
  std::size_t nodes;
  CellType type;
  std::vector<int> order; // VTK's node i is Exodus's node order[i] (empty: the same)
};

// The cell type of an element of a shape with a number of nodes, or nullptr. Exodus numbers the
// nodes as PATRAN does (exodus-element-types.md), VTK as its cells (vtkQuadraticHexahedron.h,
// vtkTriQuadraticHexahedron.h, vtkQuadraticWedge.h, vtkWedge.h); the others (points, lines, the
// triangles, quadrilaterals and tetrahedra: corners, then the midside nodes edge by edge, then the
// centre; the pyramid and the hexahedron) number alike.
const CellKind* cellKind(Shape shape, std::size_t nodes)
{
  static const CellKind kinds[] = {
    { Shape::Point, 1, CellType::Vertex, {} },
    { Shape::Line, 2, CellType::Line, {} },
    { Shape::Line, 3, CellType::QuadraticEdge, {} },
    { Shape::Triangle, 3, CellType::Triangle, {} },
    { Shape::Triangle, 6, CellType::QuadraticTriangle, {} },
    { Shape::Quad, 4, CellType::Quad, {} },
    { Shape::Quad, 8, CellType::QuadraticQuad, {} },
    { Shape::Quad, 9, CellType::BiQuadraticQuad, {} },
    { Shape::Shell, 4, CellType::Quad, {} },
    { Shape::Shell, 8, CellType::QuadraticQuad, {} },
    { Shape::Shell, 9, CellType::BiQuadraticQuad, {} },
    { Shape::Tetra, 4, CellType::Tetra, {} },
    { Shape::Tetra, 10, CellType::QuadraticTetra, {} },
    { Shape::Pyramid, 5, CellType::Pyramid, {} },
    // Exodus's wedge turns 1-2-3 counter-clockwise seen from 4-5-6 (its side 4 is 1-3-2, sides
    // turning counter-clockwise seen from outside; so does the wedge of SEACAS's test mesh,
    // testwt's), VTK's the other way ((0,1,2)'s normal points away from (3,4,5): vtkWedge.h;
    // vtkCellValidator finds Exodus's order's faces "oriented incorrectly", vtkCellSizeFilter its
    // volume negative): turned as the Abaqus C3D6 and the Gmsh prism are, and as ParaView's IOSS
    // reader turns it (its older vtkExodusIIReader does not).
    { Shape::Wedge, 6, CellType::Wedge, { 0, 2, 1, 3, 5, 4 } },
    // the corners turned so (ElementJacobian's orientation of both wedges); Exodus's midside nodes
    // 6-14 are on 0-1 1-2 2-0 0-3 1-4 2-5 3-4 4-5 5-3, VTK's on 0-1 1-2 2-0 3-4 4-5 5-3 0-3 1-4 2-5
    // of the turned corners
    { Shape::Wedge, 15, CellType::QuadraticWedge, { 0, 2, 1, 3, 5, 4, 8, 7, 6, 14, 13, 12, 9, 11, 10 } },
    { Shape::Hex, 8, CellType::Hexahedron, {} },
    // Exodus's midside nodes 8-19 are on the edges 0-1 1-2 2-3 3-0, 0-4 1-5 2-6 3-7, 4-5 5-6 6-7
    // 7-4, VTK's on the bottom's, the top's, then the vertical ones (as vtkExodusIIReader swaps
    // them); the 27-node one's 20 is the centre and 21-26 the centres of the faces z=0 z=1 x=0 x=1
    // y=0 y=1 (sides 5 6 4 2 1 3), VTK's 20-25 those of x=0 x=1 y=0 y=1 z=0 z=1 and 26 the centre
    { Shape::Hex, 20, CellType::QuadraticHexahedron, { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 12, 13, 14, 15 } },
    { Shape::Hex, 27, CellType::TriQuadraticHexahedron,
      { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 12, 13, 14, 15, 23, 24, 25, 26, 21, 22, 20 } },
  };
  for (const CellKind& kind : kinds)
  {
    if (kind.shape == shape && kind.nodes == nodes)
    {
      return &kind;
    }
  }
  return nullptr;
}

using SideNodes = std::vector<std::vector<int>>;

// Each side's nodes (Exodus's numbers, from 1) of a shape's element with the most nodes read: an
// element with fewer has those of them it has (the tables of ex_get_side_set_node_list.c). A 2D
// mesh's triangles and the quadrilaterals have edges for sides; a 3D mesh's triangles and the
// shells their two faces, then their edges. Points and lines: nullptr.
const SideNodes* sideNodes(Shape shape, int dimensions)
{
  static const SideNodes triangleEdges = { { 1, 2, 4 }, { 2, 3, 5 }, { 3, 1, 6 } };
  static const SideNodes triangleShell = { { 1, 2, 3, 4, 5, 6 }, { 1, 3, 2, 6, 5, 4 }, { 1, 2, 4 }, { 2, 3, 5 }, { 3, 1, 6 } };
  static const SideNodes quadEdges = { { 1, 2, 5 }, { 2, 3, 6 }, { 3, 4, 7 }, { 4, 1, 8 } };
  static const SideNodes shell = { { 1, 2, 3, 4, 5, 6, 7, 8, 9 }, { 1, 4, 3, 2, 8, 7, 6, 5, 9 }, { 1, 2, 5 }, { 2, 3, 6 }, { 3, 4, 7 },
    { 4, 1, 8 } };
  static const SideNodes tetra = { { 1, 2, 4, 5, 9, 8 }, { 2, 3, 4, 6, 10, 9 }, { 1, 4, 3, 8, 10, 7 }, { 1, 3, 2, 7, 6, 5 } };
  static const SideNodes pyramid = { { 1, 2, 5 }, { 2, 3, 5 }, { 3, 4, 5 }, { 1, 5, 4 }, { 1, 4, 3, 2 } }; // 5 nodes
  static const SideNodes wedge = { { 1, 2, 5, 4, 7, 11, 13, 10 }, { 2, 3, 6, 5, 8, 12, 14, 11 }, { 1, 4, 6, 3, 10, 15, 12, 9 },
    { 1, 3, 2, 9, 8, 7 }, { 4, 5, 6, 13, 14, 15 } };
  static const SideNodes hex = { { 1, 2, 6, 5, 9, 14, 17, 13, 26 }, { 2, 3, 7, 6, 10, 15, 18, 14, 25 },
    { 3, 4, 8, 7, 11, 16, 19, 15, 27 }, { 1, 5, 8, 4, 13, 20, 16, 12, 24 }, { 1, 4, 3, 2, 12, 11, 10, 9, 22 },
    { 5, 6, 7, 8, 17, 18, 19, 20, 23 } };
  switch (shape)
  {
    case Shape::Triangle: return dimensions == 2 ? &triangleEdges : &triangleShell;
    case Shape::Quad: return &quadEdges;
    case Shape::Shell: return &shell;
    case Shape::Tetra: return &tetra;
    case Shape::Pyramid: return &pyramid;
    case Shape::Wedge: return &wedge;
    case Shape::Hex: return &hex;
    default: return nullptr;
  }
}

// ---- the reader --------------------------------------------------------------------------------

// A node set or an element set before its name is settled: the file's name ("" for none), and
// the label that tells it apart ("sideset 3").
struct PendingSet
{
  std::string name, label;
  std::vector<std::int64_t> ids;
};

// The sets named: by the file's name, or the label when it has none; a name that several sets
// share is told apart by the label ("walls (sideset 3)").
std::vector<NamedSet> named(std::vector<PendingSet>& sets)
{
  std::map<std::string, int> uses;
  for (const PendingSet& set : sets)
  {
    ++uses[set.name];
  }
  std::vector<NamedSet> out;
  for (PendingSet& set : sets)
  {
    const std::string name = set.name.empty() ? set.label : uses[set.name] > 1 ? set.name + " (" + set.label + ")" : set.name;
    out.push_back({ name, std::move(set.ids) });
  }
  return out;
}

// One element block of the file.
struct Block
{
  std::int64_t id;
  std::string name;       // eb_names'
  std::string type;       // elem_type
  std::string connect;    // its connectivity's variable: connect<k>, k its place among the blocks
  std::size_t first;      // its first element's position among the file's elements
  std::size_t count;      // elements
  std::size_t nodesEach;
  const CellKind* kind;              // nullptr: left out
  std::vector<std::size_t> positions; // nodesEach nodes' positions an element, Exodus's order
};

class Reader
{
public:
  Reader(const std::string& path, bool layoutOnly)
    : Bytes(readFile(path))
    , File(path, Bytes)
  {
    this->Out.path = path;
    this->Out.hash = contentHash(this->Bytes);
    this->nodes(layoutOnly);
    if (!layoutOnly)
    {
      this->blocks();
      std::vector<PendingSet> sets = this->nodeSets();
      this->sideSets(sets);
      this->Out.mesh.nodeSets = named(sets);
    }
  }

  MeshFile Out;

private:
  std::string Bytes; // the file's, which File reads
  NetCDF File;
  std::vector<Block> Blocks;            // those with elements, in the file's order
  std::vector<std::int64_t> ElementIds; // by position among the file's elements

  // The count ids of variable (a numbering map, the blocks' or sets' prop1), or 1, 2... when the
  // file has no such variable.
  std::vector<std::int64_t> numbering(const std::string& variable, std::size_t count) const
  {
    if (this->File.has(variable))
    {
      return this->File.integers(variable, count);
    }
    this->File.room(count, variable);
    std::vector<std::int64_t> ids(count);
    std::iota(ids.begin(), ids.end(), 1);
    return ids;
  }

  // The position of a node or an element from its number (from 1) read in variable, where what
  // (in variable) refers to it.
  std::size_t position(std::int64_t number, std::size_t count, const char* kind, const std::string& variable,
    const std::string& what) const
  {
    if (number < 1 || static_cast<std::uint64_t>(number) > count)
    {
      this->File.fail(variable, what + " refers to " + kind + " number " + std::to_string(number) + ", not one of the file's " +
          std::to_string(count) + " " + kind + "s");
    }
    return static_cast<std::size_t>(number - 1);
  }

  // ---- nodes -------------------------------------------------------------------------------------

  void nodes(bool layoutOnly)
  {
    MeshFile& out = this->Out;
    const std::size_t count = this->File.dimension("num_nodes");
    if (count == 0)
    {
      this->File.fail("num_nodes", "the file has no nodes (is it an Exodus II mesh?)");
    }
    const std::size_t dimensions = this->File.dimension("num_dim");
    if (dimensions < 1 || dimensions > 3)
    {
      this->File.fail("num_dim", "is " + std::to_string(dimensions) + ": 1, 2 or 3 dimensions are read");
    }
    out.dimensions = static_cast<int>(dimensions);
    if (this->File.has("coordx"))
    {
      out.coordinates.assign({ "coordx", "coordy", "coordz" });
      out.coordinates.resize(dimensions);
    }
    else if (this->File.has("coord"))
    {
      out.coordinates = { "coord" };
    }
    else
    {
      this->File.fail("coordx", "the file has no coordinates (coordx or coord): is it an Exodus II mesh?");
    }
    const std::size_t each = out.coordinates.size() == 1 ? dimensions * count : count; // "coord" holds them all
    const nc_type type = this->File.type(out.coordinates[0]);
    for (const std::string& variable : out.coordinates)
    {
      if (this->File.type(variable) != type || (type != NC_FLOAT && type != NC_DOUBLE))
      {
        this->File.fail(variable, "is not of doubles or floats as " + out.coordinates[0] + " is");
      }
      this->File.expect(variable, each);
    }
    out.floats = type == NC_FLOAT;
    out.mesh.nodeIds = this->numbering("node_num_map", count);
    const IdIndex index(out.mesh.nodeIds);
    if (index.duplicate != IdIndex::none)
    {
      this->File.fail("node_num_map", "node id " + std::to_string(out.mesh.nodeIds[index.duplicate]) + " comes twice");
    }
    if (layoutOnly)
    {
      return;
    }
    // dimension after dimension, as the file holds them
    std::vector<double> values;
    for (const std::string& variable : out.coordinates)
    {
      const std::vector<double> read = this->File.reals(variable, each);
      values.insert(values.end(), read.begin(), read.end());
    }
    out.mesh.xyz.assign(3 * count, 0.0);
    for (std::size_t c = 0; c < dimensions; ++c)
    {
      for (std::size_t k = 0; k < count; ++k)
      {
        const double value = values[c * count + k];
        if (!std::isfinite(value))
        {
          this->File.fail(out.coordinates[std::min(c, out.coordinates.size() - 1)],
            "node " + std::to_string(out.mesh.nodeIds[k]) + "'s coordinate " + text(value) + " is not a finite number");
        }
        out.mesh.xyz[3 * k + c] = value;
      }
    }
  }

  // ---- element blocks ------------------------------------------------------------------------------

  void blocks()
  {
    SourceMesh& mesh = this->Out.mesh;
    const std::size_t count = this->File.dimension("num_el_blk");
    const std::vector<std::int64_t> ids = this->numbering("eb_prop1", count);
    const std::vector<std::string> names = this->File.names("eb_names", count);
    std::size_t elements = 0;
    for (std::size_t b = 0; b < count; ++b)
    {
      const std::string k = std::to_string(b + 1);
      Block block{ ids[b], names[b], this->File.attribute("connect" + k, "elem_type"), "connect" + k, elements,
        this->File.dimension("num_el_in_blk" + k), this->File.dimension("num_nod_per_el" + k), nullptr, {} };
      if (block.count > 0) // else a null block
      {
        block.kind = cellKind(shapeOf(block.type), block.nodesEach);
        elements += block.count;
        this->Blocks.push_back(std::move(block));
      }
    }
    if (this->File.dimension("num_elem") != elements)
    {
      this->File.fail("num_elem", "is " + std::to_string(this->File.dimension("num_elem")) + "; the blocks hold " +
          std::to_string(elements) + " elements");
    }
    this->ElementIds = this->numbering("elem_num_map", elements);
    const IdIndex index(this->ElementIds);
    if (index.duplicate != IdIndex::none)
    {
      this->File.fail("elem_num_map", "element id " + std::to_string(this->ElementIds[index.duplicate]) + " comes twice");
    }
    std::vector<PendingSet> sets;
    for (Block& block : this->Blocks)
    {
      const auto first = this->ElementIds.begin() + static_cast<std::ptrdiff_t>(block.first);
      const std::vector<std::int64_t> blockIds(first, first + static_cast<std::ptrdiff_t>(block.count));
      if (block.kind == nullptr)
      {
        mesh.warnings.push_back(this->Out.path + ": " + block.connect + ": element type \"" + block.type + "\" with " +
          std::to_string(block.nodesEach) + " nodes (block " + std::to_string(block.id) + ") is not supported: its " +
          std::to_string(block.count) + " elements are left out (their nodes are read and move with the rest)");
        continue;
      }
      const std::vector<std::int64_t> numbers = this->File.integers(block.connect, block.count * block.nodesEach);
      block.positions.resize(numbers.size());
      for (std::size_t i = 0; i < numbers.size(); ++i)
      {
        block.positions[i] = this->position(numbers[i], mesh.nodeIds.size(), "node", block.connect,
          "element " + std::to_string(blockIds[i / block.nodesEach]));
      }
      ElementBlock cells{ block.type, block.kind->type, blockIds, {} };
      cells.nodes.reserve(numbers.size());
      const std::vector<int>& order = block.kind->order;
      for (std::size_t e = 0; e < block.count; ++e)
      {
        for (std::size_t i = 0; i < block.nodesEach; ++i)
        {
          cells.nodes.push_back(mesh.nodeIds[block.positions[e * block.nodesEach + (order.empty() ? i : order[i])]]);
        }
      }
      mesh.blocks.push_back(std::move(cells));
      sets.push_back({ block.name, "block " + std::to_string(block.id), blockIds });
    }
    mesh.elementSets = named(sets);
  }

  // ---- node sets and side sets ---------------------------------------------------------------------

  // The node ids at positions, in the file's order of the nodes, each once.
  std::vector<std::int64_t> nodeIds(std::vector<std::size_t>& positions) const
  {
    std::sort(positions.begin(), positions.end());
    positions.erase(std::unique(positions.begin(), positions.end()), positions.end());
    std::vector<std::int64_t> ids;
    ids.reserve(positions.size());
    for (const std::size_t position : positions)
    {
      ids.push_back(this->Out.mesh.nodeIds[position]);
    }
    return ids;
  }

  std::vector<PendingSet> nodeSets() const
  {
    const std::size_t count = this->File.dimension("num_node_sets");
    const std::vector<std::int64_t> ids = this->numbering("ns_prop1", count);
    const std::vector<std::string> names = this->File.names("ns_names", count);
    std::vector<PendingSet> sets;
    for (std::size_t s = 0; s < count; ++s)
    {
      const std::string k = std::to_string(s + 1), variable = "node_ns" + k;
      const std::size_t entries = this->File.dimension("num_nod_ns" + k);
      if (entries == 0)
      {
        continue; // a null set
      }
      const std::vector<std::int64_t> numbers = this->File.integers(variable, entries);
      std::vector<std::size_t> positions(entries);
      for (std::size_t i = 0; i < entries; ++i)
      {
        positions[i] = this->position(numbers[i], this->Out.mesh.nodeIds.size(), "node", variable, "entry " + std::to_string(i + 1));
      }
      sets.push_back({ names[s], "nodeset " + std::to_string(ids[s]), this->nodeIds(positions) });
    }
    return sets;
  }

  // Each side set: the nodes of its sides.
  void sideSets(std::vector<PendingSet>& sets)
  {
    const std::size_t count = this->File.dimension("num_side_sets");
    const std::vector<std::int64_t> ids = this->numbering("ss_prop1", count);
    const std::vector<std::string> names = this->File.names("ss_names", count);
    for (std::size_t s = 0; s < count; ++s)
    {
      const std::string k = std::to_string(s + 1), elementVariable = "elem_ss" + k, sideVariable = "side_ss" + k;
      const std::size_t sides = this->File.dimension("num_side_ss" + k);
      if (sides == 0)
      {
        continue; // a null set
      }
      const std::vector<std::int64_t> elements = this->File.integers(elementVariable, sides);
      const std::vector<std::int64_t> numbers = this->File.integers(sideVariable, sides);
      std::vector<std::size_t> positions;
      std::map<std::string, std::size_t> leftOut; // sides by element type
      for (std::size_t i = 0; i < sides; ++i)
      {
        const std::size_t element =
          this->position(elements[i], this->ElementIds.size(), "element", elementVariable, "side " + std::to_string(i + 1));
        const Block& block = *(std::upper_bound(this->Blocks.begin(), this->Blocks.end(), element,
                                 [](std::size_t at, const Block& b) { return at < b.first; }) - 1);
        const SideNodes* table = block.kind ? sideNodes(block.kind->shape, this->Out.dimensions) : nullptr;
        if (table == nullptr)
        {
          ++leftOut[block.type];
          continue;
        }
        if (numbers[i] < 1 || static_cast<std::size_t>(numbers[i]) > table->size())
        {
          this->File.fail(sideVariable, "element " + std::to_string(this->ElementIds[element]) + " (" + block.type + ") has no side " +
              std::to_string(numbers[i]) + " (it has " + std::to_string(table->size()) + ")");
        }
        const std::size_t* nodes = block.positions.data() + (element - block.first) * block.nodesEach;
        for (const int node : (*table)[static_cast<std::size_t>(numbers[i] - 1)])
        {
          if (static_cast<std::size_t>(node) <= block.nodesEach)
          {
            positions.push_back(nodes[node - 1]);
          }
        }
      }
      const std::string label = "sideset " + std::to_string(ids[s]);
      for (const auto& [type, left] : leftOut)
      {
        this->Out.mesh.warnings.push_back(this->Out.path + ": " + elementVariable + ": " + std::to_string(left) + " sides of " + label +
          " are of elements of type \"" + type + "\", whose sides are not read: their nodes are left out of its node set");
      }
      sets.push_back({ names[s], label, this->nodeIds(positions) });
    }
  }
};
} // namespace

MeshFile readExodus(const std::string& path)
{
  return std::move(Reader(path, false).Out);
}

MeshFile readExodusLayout(const std::string& path)
{
  return std::move(Reader(path, true).Out);
}

bool isExodus(const std::string& head)
{
  static const std::string_view signatures[] = { { "CDF\x01", 4 }, { "CDF\x02", 4 }, { "CDF\x05", 4 }, { "\x89HDF\r\n\x1a\n", 8 } };
  return std::any_of(std::begin(signatures), std::end(signatures),
    [&](std::string_view signature) { return std::string_view(head).substr(0, signature.size()) == signature; });
}

// ---- the variant -------------------------------------------------------------------------------

void MeshFile::writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
  bool overwrite) const
{
  VariantSource source = variantSource(target, this->path, this->hash, this->mesh.nodeIds, ids, xyz, count);
  const std::vector<std::size_t>& row = source.row;
  // the coordinates dimension after dimension, as the file holds them
  const std::size_t dimensions = static_cast<std::size_t>(this->dimensions);
  std::vector<double> values(dimensions * count);
  for (std::size_t k = 0; k < count; ++k)
  {
    const double* moved = xyz + 3 * row[k];
    for (std::size_t c = 0; c < dimensions; ++c)
    {
      if (this->floats && std::abs(moved[c]) > std::numeric_limits<float>::max())
      {
        throw FileError(target, 0, "node " + std::to_string(this->mesh.nodeIds[k]) + "'s coordinate " + text(moved[c]) +
            " is beyond the floats that " + this->path + " holds its coordinates in");
      }
      values[c * count + k] = moved[c];
    }
    for (std::size_t c = dimensions; c < 3; ++c)
    {
      if (moved[c] != 0)
      {
        throw FileError(target, 0, "node " + std::to_string(this->mesh.nodeIds[k]) + " is moved out of the mesh's " +
            std::to_string(dimensions) + "D space (its coordinate " + std::to_string(c + 1) + " is " + text(moved[c]) + ", not 0)");
      }
    }
  }
  // the source's bytes written aside, their coordinates rewritten there, then renamed into place
  AtomicWrite write(overwrite);
  NetCDF copy(target, write.add(target, source.file));
  const std::size_t each = this->coordinates.size() == 1 ? values.size() : count; // "coord" holds them all
  for (std::size_t c = 0; c < this->coordinates.size(); ++c)
  {
    copy.write(this->coordinates[c], values.data() + c * each, each);
  }
  copy.close();
  write.commit();
}
} // namespace exodus
} // namespace mlsformats
