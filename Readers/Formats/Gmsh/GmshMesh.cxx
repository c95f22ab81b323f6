#include "Gmsh/GmshMesh.h"

#include "Common/IdIndex.h"
#include "Common/Pieces.h"
#include "Common/TextCursor.h"
#include "Common/TextFile.h"
#include "Common/VariantNodes.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <optional>
#include <string_view>

namespace fs = std::filesystem;

namespace mlsformats
{
namespace gmsh
{
namespace
{
// ---- element types ---------------------------------------------------------------------------

enum class Family
{
  None,
  Point,
  Line,
  Triangle,
  Quadrangle,
  Tetrahedron,
  Pyramid,
  Prism,
  Hexahedron,
  Trihedron
};

struct ElementType
{
  Family family;
  int nodes;
};

// Gmsh's element types by number (GmshDefines.h) with their node counts (MElement::getInfoMSH):
// a binary file's elements are skipped by their count, those without a cell type too.
ElementType elementType(std::int64_t number)
{
  constexpr Family Pnt = Family::Point, Lin = Family::Line, Tri = Family::Triangle, Qua = Family::Quadrangle,
                   Tet = Family::Tetrahedron, Pyr = Family::Pyramid, Pri = Family::Prism, Hex = Family::Hexahedron;
  static const ElementType types[] = { { Family::None, 0 }, // 0: none
    { Lin, 2 }, { Tri, 3 }, { Qua, 4 }, { Tet, 4 }, { Hex, 8 }, { Pri, 6 }, { Pyr, 5 }, { Lin, 3 }, { Tri, 6 }, { Qua, 9 },  // 1-10
    { Tet, 10 }, { Hex, 27 }, { Pri, 18 }, { Pyr, 14 }, { Pnt, 1 }, { Qua, 8 }, { Hex, 20 }, { Pri, 15 }, { Pyr, 13 },     // 11-19
    { Tri, 9 }, { Tri, 10 }, { Tri, 12 }, { Tri, 15 }, { Tri, 15 }, { Tri, 21 }, { Lin, 4 }, { Lin, 5 }, { Lin, 6 },      // 20-28
    { Tet, 20 }, { Tet, 35 }, { Tet, 56 }, { Tet, 22 }, { Tet, 28 }, { Family::None, 0 }, { Family::None, 0 },            // 29-35
    { Qua, 16 }, { Qua, 25 }, { Qua, 36 }, { Qua, 12 }, { Qua, 16 }, { Qua, 20 }, { Tri, 28 }, { Tri, 36 }, { Tri, 45 },  // 36-44
    { Tri, 55 }, { Tri, 66 }, { Qua, 49 }, { Qua, 64 }, { Qua, 81 }, { Qua, 100 }, { Qua, 121 }, { Tri, 18 },             // 45-52
    { Tri, 21 }, { Tri, 24 }, { Tri, 27 }, { Tri, 30 }, { Qua, 24 }, { Qua, 28 }, { Qua, 32 }, { Qua, 36 }, { Qua, 40 },  // 53-61
    { Lin, 7 }, { Lin, 8 }, { Lin, 9 }, { Lin, 10 }, { Lin, 11 }, { Family::None, 0 }, { Family::None, 0 },               // 62-68
    { Family::None, 0 }, { Family::None, 0 }, { Tet, 84 }, { Tet, 120 }, { Tet, 165 }, { Tet, 220 }, { Tet, 286 },         // 69-75
    { Family::None, 0 }, { Family::None, 0 }, { Family::None, 0 }, { Tet, 34 }, { Tet, 40 }, { Tet, 46 }, { Tet, 52 },    // 76-82
    { Tet, 58 }, { Lin, 1 }, { Tri, 1 }, { Qua, 1 }, { Tet, 1 }, { Hex, 1 }, { Pri, 1 }, { Pri, 40 }, { Pri, 75 },        // 83-91
    { Hex, 64 }, { Hex, 125 }, { Hex, 216 }, { Hex, 343 }, { Hex, 512 }, { Hex, 729 }, { Hex, 1000 }, { Hex, 32 },        // 92-99
    { Hex, 44 }, { Hex, 56 }, { Hex, 68 }, { Hex, 80 }, { Hex, 92 }, { Hex, 104 }, { Pri, 126 }, { Pri, 196 },            // 100-107
    { Pri, 288 }, { Pri, 405 }, { Pri, 550 }, { Pri, 24 }, { Pri, 33 }, { Pri, 42 }, { Pri, 51 }, { Pri, 60 },            // 108-115
    { Pri, 69 }, { Pri, 78 }, { Pyr, 30 }, { Pyr, 55 }, { Pyr, 91 }, { Pyr, 140 }, { Pyr, 204 }, { Pyr, 285 },            // 116-123
    { Pyr, 385 }, { Pyr, 21 }, { Pyr, 29 }, { Pyr, 37 }, { Pyr, 45 }, { Pyr, 53 }, { Pyr, 61 }, { Pyr, 69 }, { Pyr, 1 },  // 124-132
    { Pnt, 1 }, { Lin, 2 }, { Tri, 3 }, { Tet, 4 }, { Tet, 16 }, { Family::None, 0 }, { Family::None, 0 },                // 133-139
    { Family::Trihedron, 4 } };                                                                                            // 140
  return number > 0 && number < static_cast<std::int64_t>(std::size(types)) ? types[number] : types[0];
}

int dimension(Family family)
{
  switch (family)
  {
    case Family::None: return -1;
    case Family::Point: return 0;
    case Family::Line: return 1;
    case Family::Triangle:
    case Family::Quadrangle: return 2;
    default: return 3;
  }
}

// As Gmsh names a type, in lower case: "tetrahedron 10", "point".
std::string typeName(const ElementType& type)
{
  static const char* const names[] = { "", "point", "line", "triangle", "quadrilateral", "tetrahedron", "pyramid", "prism",
    "hexahedron", "trihedron" };
  const std::string name = names[static_cast<int>(type.family)];
  return type.family == Family::Point ? name : name + " " + std::to_string(type.nodes);
}

struct CellKind
{
  CellType type;
  std::vector<int> order; // VTK's node i is Gmsh's node order[i] (empty: the same)
};

// The cell type of a Gmsh element type, or false. Gmsh's node numbers are its reference manual's
// ("Node ordering"; MTetrahedron.h, MHexahedron.h, MPrism.h), VTK's its cells' (vtkQuadraticTetra.h,
// vtkQuadraticHexahedron.h, vtkTriQuadraticHexahedron.h, vtkQuadraticWedge.h). The others (line,
// triangle, quadrangle, tetrahedron, hexahedron, pyramid, point, and the quadratic line, triangle and
// quadrangles: corners, then the midside nodes edge by edge, then the centre) number alike.
bool cellKind(std::int64_t type, CellKind& kind)
{
  kind.order.clear();
  switch (type)
  {
    case 1: kind.type = CellType::Line; return true;
    case 2: kind.type = CellType::Triangle; return true;
    case 3: kind.type = CellType::Quad; return true;
    case 4: kind.type = CellType::Tetra; return true;
    case 5: kind.type = CellType::Hexahedron; return true;
    case 7: kind.type = CellType::Pyramid; return true;
    case 8: kind.type = CellType::QuadraticEdge; return true;
    case 9: kind.type = CellType::QuadraticTriangle; return true;
    case 10: kind.type = CellType::BiQuadraticQuad; return true;
    case 15: kind.type = CellType::Vertex; return true;
    case 16: kind.type = CellType::QuadraticQuad; return true;
    // Gmsh's prism turns 0-1-2 counter-clockwise seen from 3-4-5 (its reference prism), VTK's wedge
    // the other way ((0,1,2)'s normal points away from (3,4,5): vtkWedge.h, vtkCellValidator), as
    // an Abaqus C3D6's: turned as Gmsh's VTK writer turns it
    case 6: kind.type = CellType::Wedge; kind.order = { 0, 2, 1, 3, 5, 4 }; return true;
    // Gmsh's nodes 8 and 9 are on the edges 2-3 and 1-3, VTK's on 1-3 and 2-3
    case 11: kind.type = CellType::QuadraticTetra; kind.order = { 0, 1, 2, 3, 4, 5, 6, 7, 9, 8 }; return true;
    // Gmsh's edges 8-19 are 0-1 0-3 0-4 1-2 1-5 2-3 2-6 3-7 4-5 4-7 5-6 6-7, VTK's 0-1 1-2 2-3 3-0
    // 4-5 5-6 6-7 7-4 0-4 1-5 2-6 3-7; the 27-node one's face centres 20-25 are Gmsh's z=0 y=0 x=0
    // x=1 y=1 z=1 (faces 0321 0154 0473 1265 2376 4567), VTK's x=0 x=1 y=0 y=1 z=0 z=1
    case 17:
      kind.type = CellType::QuadraticHexahedron;
      kind.order = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15 };
      return true;
    case 12:
      kind.type = CellType::TriQuadraticHexahedron;
      kind.order = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 11, 13, 9, 16, 18, 19, 17, 10, 12, 14, 15, 22, 23, 21, 24, 20, 25, 26 };
      return true;
    // the prism turned as the 6-node one, its edges 6-14 being Gmsh's 0-1 0-2 0-3 1-2 1-4 2-5 3-4 3-5
    // 4-5 and VTK's 0-1 1-2 2-0 3-4 4-5 5-3 0-3 1-4 2-5 of the turned corners
    case 18:
      kind.type = CellType::QuadraticWedge;
      kind.order = { 0, 2, 1, 3, 5, 4, 7, 9, 6, 13, 14, 12, 8, 11, 10 };
      return true;
    default: return false;
  }
}

// ---- the reader --------------------------------------------------------------------------------

// The physical groups an element is in: their dimension and tags (sorted).
struct Owner
{
  int dim;
  std::vector<int> physicals;
};

// The elements of one Gmsh type, in file order.
struct TypeGroup
{
  std::int64_t type = 0;
  int dim = -1;      // -1: unknown (a type that is not Gmsh's, in MSH 2.2)
  int nodesEach = 0; // the count of the type, or of the first element of an unknown type
  bool cell = false;
  std::vector<std::int64_t> ids, nodes;
  std::vector<std::uint32_t> owners;  // an element's (in Reader::Owners)
  std::vector<std::uint64_t> offsets; // where an element is in the file
};

class Reader : TextCursor
{
public:
  Reader(const std::string& path, bool layoutOnly)
    : TextCursor(path)
    , LayoutOnly(layoutOnly)
  {
    this->Out.path = path;
    this->Out.hash = contentHash(this->Text);
    this->Owners.push_back({ -1, {} }); // 0: in no physical group
    this->meshFormat();
    std::string_view line;
    while (this->nextLine(line))
    {
      // Gmsh ignores the lines between sections
      if (line.empty() || line[0] != '$')
      {
        continue;
      }
      this->Section = std::string(trim(line));
      if (this->Section.compare(0, 4, "$End") == 0)
      {
        this->fail(this->Section + " without its $" + this->Section.substr(4));
      }
      if (this->Section == "$MeshFormat")
      {
        this->fail("a second $MeshFormat");
      }
      else if (this->Section == "$PhysicalNames")
      {
        this->physicalNames();
      }
      else if (this->Section == "$Entities" || this->Section == "$PartitionedEntities")
      {
        this->entities(this->Section == "$PartitionedEntities");
      }
      else if (this->Section == "$Nodes")
      {
        this->nodes();
      }
      else if (this->Section == "$Elements")
      {
        this->elements();
      }
      else
      {
        this->skipSection();
      }
    }
    if (!this->Nodes)
    {
      throw FileError(path, 0, "has no $Nodes section");
    }
    if (!layoutOnly)
    {
      this->finish();
    }
  }

  MshFile Out;

private:
  bool LayoutOnly;
  bool Binary = false;
  bool Version2 = false; // MSH 2.2 (else 4.1)
  std::string Section;
  std::string_view Record; // the line read last
  std::vector<std::string_view> Fields;
  std::vector<std::int64_t> Pending; // an element's nodes

  std::map<std::pair<int, int>, std::string> Names;            // $PhysicalNames: (dim, tag) to name
  std::map<std::pair<int, int>, std::vector<int>> Entities;    // (dim, tag) to physical tags
  std::optional<IdIndex> Nodes;                                 // once $Nodes is read
  bool ElementsRead = false;
  std::vector<Owner> Owners;
  std::map<std::pair<int, std::vector<int>>, std::uint32_t> OwnerIndex;
  std::vector<TypeGroup> Groups;
  std::map<std::int64_t, std::size_t> GroupOfType;

  // ---- errors ----------------------------------------------------------------------------------

  // "file:line" of the byte at offset; a binary file's: "file: $Section, byte offset".
  std::string where(std::size_t offset) const
  {
    return this->Binary ? this->Out.path + ": " + this->Section + ", byte " + std::to_string(offset)
                        : this->Out.path + ":" + std::to_string(this->lineOf(offset));
  }

  // a binary file's errors name the section and the byte
  FileError errorAt(std::size_t offset, const std::string& reason) const override
  {
    return this->Binary ? FileError(this->Out.path, 0, this->Section + ", byte " + std::to_string(offset) + ": " + reason)
                        : TextCursor::errorAt(offset, reason);
  }

  [[noreturn]] void truncated() const
  {
    this->failAt(this->Text.size(), "the file ends inside " + this->Section + " (it is cut short)");
  }

  // ---- text --------------------------------------------------------------------------------------

  // The next line that is not blank, inside the section's data.
  std::string_view record()
  {
    do
    {
      if (!this->nextLine(this->Record))
      {
        this->truncated();
      }
    } while (trim(this->Record).empty());
    if (this->Record[0] == '$')
    {
      this->fail(std::string(trim(this->Record)) + " where " + this->Section + " has more data by its counts");
    }
    return this->Record;
  }

  // The next data line's fields (between blanks), into Fields.
  void fields()
  {
    splitBlanks(this->record(), this->Fields);
  }

  // The next data line's fields, which must be count.
  void fields(std::size_t count, const char* form)
  {
    this->fields();
    if (this->Fields.size() != count)
    {
      this->fail(std::string("a line of ") + std::to_string(this->Fields.size()) + " fields where " + form + " is expected");
    }
  }

  std::int64_t integer(std::string_view field, const std::string& what) const
  {
    std::int64_t value = 0;
    if (!parseInteger(field.data(), field.data() + field.size(), value))
    {
      this->fail("\"" + std::string(field) + "\" is not " + what);
    }
    return value;
  }

  std::uint64_t count(std::string_view field, const std::string& what) const
  {
    const std::int64_t value = this->integer(field, what);
    if (value < 0)
    {
      this->fail(what + " " + std::to_string(value) + " is negative");
    }
    return static_cast<std::uint64_t>(value);
  }

  std::int64_t tag(std::string_view field, const std::string& what) const
  {
    const std::int64_t value = this->integer(field, what);
    if (value <= 0)
    {
      this->fail(what + " " + std::to_string(value) + " is not positive");
    }
    return value;
  }

  int dimensionField(std::string_view field) const
  {
    const std::int64_t dim = this->integer(field, "a dimension");
    if (dim < 0 || dim > 3)
    {
      this->fail("dimension " + std::to_string(dim) + " is not 0, 1, 2 or 3");
    }
    return static_cast<int>(dim);
  }

  double real(std::string_view field, std::int64_t node) const
  {
    double value = 0;
    if (!parseReal(field.data(), field.data() + field.size(), value))
    {
      this->fail("node " + std::to_string(node) + "'s coordinate \"" + std::string(field) + "\" is not a finite number");
    }
    return value;
  }

  // Skips to the line "$End<name>" of the section.
  void skipSection()
  {
    const std::string end = "$End" + this->Section.substr(1);
    std::string_view line;
    do
    {
      if (!this->nextLine(line))
      {
        this->truncated();
      }
    } while (trim(line) != end);
  }

  // The section's data read: the next line that is not blank is its end.
  void endSection()
  {
    std::string_view line;
    do
    {
      if (!this->nextLine(line))
      {
        this->truncated();
      }
    } while (trim(line).empty());
    const std::string end = "$End" + this->Section.substr(1);
    if (trim(line) != end)
    {
      this->fail("not " + end + ", where the counts of " + this->Section + " end");
    }
  }

  // ---- binary ------------------------------------------------------------------------------------

  template <class T>
  T take()
  {
    if (this->Text.size() - this->At < sizeof(T))
    {
      this->truncated();
    }
    T value;
    std::memcpy(&value, this->Text.data() + this->At, sizeof(T));
    this->At += sizeof(T);
    return value;
  }

  void skip(std::uint64_t bytes)
  {
    if (this->Text.size() - this->At < bytes)
    {
      this->truncated();
    }
    this->At += static_cast<std::size_t>(bytes);
  }

  std::uint64_t takeCount(const std::string& what)
  {
    if (this->Version2)
    {
      const std::int32_t value = this->take<std::int32_t>();
      if (value < 0)
      {
        this->fail(what + " " + std::to_string(value) + " is negative");
      }
      return static_cast<std::uint64_t>(value);
    }
    return this->take<std::uint64_t>();
  }

  // A tag: MSH 2.2's an int, 4.1's a size_t.
  std::int64_t takeTag(const std::string& what)
  {
    const std::uint64_t value = this->Version2 ? static_cast<std::uint64_t>(this->take<std::int32_t>()) : this->take<std::uint64_t>();
    if (value == 0 || value > static_cast<std::uint64_t>(std::numeric_limits<std::int64_t>::max()))
    {
      this->fail(what + " " + std::to_string(static_cast<std::int64_t>(value)) + " is not positive");
    }
    return static_cast<std::int64_t>(value);
  }

  // ---- sections ----------------------------------------------------------------------------------

  void meshFormat()
  {
    std::string_view line;
    if (!this->nextLine(line) || trim(line) != "$MeshFormat")
    {
      throw FileError(this->Out.path, 1, "does not start with $MeshFormat: not a Gmsh mesh");
    }
    this->Section = "$MeshFormat";
    this->fields(3, "\"version file-type data-size\"");
    const std::string version(this->Fields[0]);
    if (version != "2.2" && version != "4.1")
    {
      this->fail("MSH version " + version + " is not supported (2.2 and 4.1 are)");
    }
    this->Version2 = version == "2.2";
    const std::int64_t fileType = this->integer(this->Fields[1], "a file type (0 ASCII, 1 binary)");
    if (fileType != 0 && fileType != 1)
    {
      this->fail("file type " + std::to_string(fileType) + " is neither 0 (ASCII) nor 1 (binary)");
    }
    const std::int64_t dataSize = this->integer(this->Fields[2], "a data size");
    if (fileType == 1 && dataSize != 8)
    {
      this->fail("data size " + std::to_string(dataSize) + " is not supported (8 is)");
    }
    this->Binary = fileType == 1;
    this->Out.binary = this->Binary;
    if (this->Binary)
    {
      this->Mark = this->At;
      if (this->take<std::int32_t>() != 1)
      {
        this->fail("the integer 1 does not read as 1: the file was written with another byte order than this machine's");
      }
    }
    this->endSection();
  }

  void physicalNames()
  {
    this->fields(1, "the number of names");
    const std::uint64_t count = this->count(this->Fields[0], "a number of names");
    this->room(count, 6, "physical names");
    for (std::uint64_t i = 0; i < count; ++i)
    {
      this->fields();
      if (this->Fields.size() < 3)
      {
        this->fail("a physical name's line is: dimension tag \"name\"");
      }
      const int dim = this->dimensionField(this->Fields[0]);
      const std::int64_t tag = this->integer(this->Fields[1], "a physical tag");
      std::string_view name = trim(this->Record.substr(static_cast<std::size_t>(this->Fields[2].data() - this->Record.data())));
      if (name.size() >= 2 && name.front() == '"' && name.back() == '"')
      {
        name = name.substr(1, name.size() - 2);
      }
      this->Names[{ dim, static_cast<int>(std::abs(tag)) }] = std::string(name);
    }
    this->endSection();
  }

  // MSH 4.1: each entity's physical tags (its bounding box and boundary are skipped); those of a
  // partitioned mesh's entities (partitioned: $PartitionedEntities, which first lists the numbers of
  // partitions and the ghost entities, and gives each entity its parent and partitions).
  void entities(bool partitioned)
  {
    if (this->Version2)
    {
      this->fail(this->Section + " in an MSH 2.2 file");
    }
    if (this->ElementsRead)
    {
      this->fail(this->Section + " after $Elements");
    }
    std::uint64_t counts[4];
    if (this->Binary)
    {
      this->Mark = this->At;
      if (partitioned)
      {
        this->skip(8); // the number of partitions
        const std::uint64_t ghosts = this->take<std::uint64_t>();
        this->room(ghosts, 8, "ghost entities");
        this->skip(8 * ghosts);
      }
      for (std::uint64_t& count : counts)
      {
        count = this->take<std::uint64_t>();
      }
    }
    else
    {
      if (partitioned)
      {
        this->fields(1, "the number of partitions");
        this->fields(1, "the number of ghost entities");
        const std::uint64_t ghosts = this->count(this->Fields[0], "a number of ghost entities");
        this->room(ghosts, 4, "ghost entities");
        for (std::uint64_t g = 0; g < ghosts; ++g)
        {
          this->fields(2, "\"tag partition\"");
        }
      }
      this->fields(4, "the numbers of points, curves, surfaces and volumes");
      for (int dim = 0; dim < 4; ++dim)
      {
        counts[dim] = this->count(this->Fields[dim], "a number of entities");
      }
    }
    for (int dim = 0; dim < 4; ++dim)
    {
      const std::size_t reals = dim == 0 ? 3 : 6; // a point's coordinates, a bounding box
      this->room(counts[dim], this->Binary ? 4 + 8 * reals + 8 : 2 * reals + 4, "entities of dimension " + std::to_string(dim));
      for (std::uint64_t i = 0; i < counts[dim]; ++i)
      {
        std::int64_t tag = 0;
        std::vector<int> physicals;
        if (this->Binary)
        {
          this->Mark = this->At;
          tag = this->take<std::int32_t>();
          if (partitioned)
          {
            this->skip(8); // the parent's dimension and tag
            const std::uint64_t partitions = this->take<std::uint64_t>();
            this->room(partitions, 4, "partitions");
            this->skip(4 * partitions);
          }
          this->skip(8 * reals);
          const std::uint64_t count = this->take<std::uint64_t>();
          this->room(count, 4, "physical tags");
          for (std::uint64_t k = 0; k < count; ++k)
          {
            physicals.push_back(std::abs(this->take<std::int32_t>()));
          }
          if (dim > 0)
          {
            const std::uint64_t bounding = this->take<std::uint64_t>();
            this->room(bounding, 4, "bounding entities");
            this->skip(4 * bounding);
          }
        }
        else
        {
          // tag [parent-dimension parent-tag partitions partition...] reals physicals physical...
          // [bounding-entities entity...]
          this->fields();
          const std::size_t size = this->Fields.size();
          std::uint64_t at = 1;
          if (partitioned)
          {
            at = size > 3 ? 4 + this->count(this->Fields[3], "a number of partitions") : size;
          }
          at += reals;
          const std::uint64_t count = size > at ? this->count(this->Fields[at], "a number of physical tags") : 0;
          const std::uint64_t bounding = dim > 0 && size > at + 1 + count
            ? this->count(this->Fields[at + 1 + count], "a number of bounding entities") : 0;
          if (size != at + 1 + count + (dim > 0 ? 1 + bounding : 0))
          {
            this->fail("an entity line of " + std::to_string(size) + " fields, which its counts do not fit");
          }
          tag = this->integer(this->Fields[0], "an entity tag");
          for (std::uint64_t k = 0; k < count; ++k)
          {
            physicals.push_back(static_cast<int>(std::abs(this->integer(this->Fields[at + 1 + k], "a physical tag"))));
          }
        }
        if (!physicals.empty())
        {
          this->Entities[{ dim, static_cast<int>(tag) }] = physicals;
        }
      }
    }
    this->endSection();
  }

  // ---- nodes -------------------------------------------------------------------------------------

  void node(std::int64_t id, std::size_t coordinates)
  {
    this->Out.mesh.nodeIds.push_back(id);
    this->Out.coordinates.push_back(coordinates);
  }

  // An ASCII node's coordinates, Fields[first..]: x y z and its parametric ones.
  void asciiCoordinates(std::int64_t id, std::size_t first)
  {
    this->node(id, static_cast<std::size_t>(this->Fields[first].data() - this->Text.data()));
    this->Out.nodesEnd = static_cast<std::size_t>(this->Fields[first + 2].data() + this->Fields[first + 2].size() - this->Text.data());
    for (std::size_t c = first; c < this->Fields.size(); ++c)
    {
      const double value = this->real(this->Fields[c], id);
      if (c < first + 3)
      {
        this->Out.mesh.xyz.push_back(value);
      }
    }
  }

  void binaryCoordinates(std::int64_t id, std::size_t offset)
  {
    this->node(id, offset);
    this->Out.nodesEnd = offset + 24;
    for (int c = 0; c < 3; ++c)
    {
      double value;
      std::memcpy(&value, this->Text.data() + offset + 8 * c, 8);
      if (!std::isfinite(value))
      {
        this->failAt(offset, "node " + std::to_string(id) + "'s coordinate " + std::to_string(value) + " is not a finite number");
      }
      this->Out.mesh.xyz.push_back(value);
    }
  }

  void nodes()
  {
    if (this->Nodes)
    {
      this->fail("a second $Nodes");
    }
    std::vector<std::int64_t>& ids = this->Out.mesh.nodeIds;
    std::uint64_t total = 0, blocks = 0;
    if (this->Version2)
    {
      this->fields(1, "the number of nodes");
      total = this->count(this->Fields[0], "a number of nodes");
    }
    else if (!this->Binary)
    {
      this->fields(4, "\"blocks nodes min-tag max-tag\"");
      blocks = this->count(this->Fields[0], "a number of blocks");
      total = this->count(this->Fields[1], "a number of nodes");
    }
    else
    {
      this->Mark = this->At;
      blocks = this->take<std::uint64_t>();
      total = this->take<std::uint64_t>();
      this->skip(16); // min and max tags
    }
    this->room(total, this->Binary ? (this->Version2 ? 28 : 32) : 8, "nodes");
    this->room(blocks, this->Binary ? 20 : 8, "node blocks");
    ids.reserve(total);
    this->Out.coordinates.reserve(total);
    this->Out.mesh.xyz.reserve(3 * total);
    // MSH 2.2: "tag x y z" each; 4.1: blocks
    for (std::uint64_t i = 0; i < total && this->Version2; ++i)
    {
      if (this->Binary)
      {
        this->Mark = this->At;
        const std::int64_t id = this->takeTag("node tag");
        this->skip(24);
        this->binaryCoordinates(id, this->At - 24);
      }
      else
      {
        this->fields(4, "\"tag x y z\"");
        this->asciiCoordinates(this->tag(this->Fields[0], "a node tag"), 1);
      }
    }
    for (std::uint64_t b = 0; b < blocks; ++b)
    {
      this->nodeBlock();
    }
    if (ids.size() != total)
    {
      this->fail("the blocks of $Nodes hold " + std::to_string(ids.size()) + " nodes, its header says " + std::to_string(total));
    }
    this->endSection();
    this->Nodes.emplace(ids);
    if (this->Nodes->duplicate != IdIndex::none)
    {
      this->failAt(this->Out.coordinates[this->Nodes->duplicate], "node " + std::to_string(ids[this->Nodes->duplicate]) + " is defined twice");
    }
  }

  // MSH 4.1: a block's tags, then its coordinates (x y z, and u v w of a parametric one's entity).
  void nodeBlock()
  {
    int dim = 0;
    std::int64_t parametric = 0;
    std::uint64_t count = 0;
    if (this->Binary)
    {
      this->Mark = this->At;
      dim = this->take<std::int32_t>();
      this->skip(4); // the entity's tag
      parametric = this->take<std::int32_t>();
      count = this->take<std::uint64_t>();
      if (dim < 0 || dim > 3)
      {
        this->fail("dimension " + std::to_string(dim) + " is not 0, 1, 2 or 3");
      }
    }
    else
    {
      this->fields(4, "\"entity-dimension entity-tag parametric nodes\"");
      dim = this->dimensionField(this->Fields[0]);
      parametric = this->integer(this->Fields[2], "parametric (0 or 1)");
      count = this->count(this->Fields[3], "a number of nodes");
    }
    if (parametric != 0 && parametric != 1)
    {
      this->fail("parametric " + std::to_string(parametric) + " is neither 0 nor 1");
    }
    const std::size_t reals = 3 + (parametric ? dim : 0);
    this->room(count, this->Binary ? 8 + 8 * reals : 2 + 2 * reals, "nodes in a block");
    std::vector<std::int64_t> tags(count);
    for (std::int64_t& tag : tags)
    {
      if (this->Binary)
      {
        tag = this->takeTag("node tag");
      }
      else
      {
        this->fields(1, "a node tag");
        tag = this->tag(this->Fields[0], "a node tag");
      }
    }
    for (const std::int64_t tag : tags)
    {
      if (this->Binary)
      {
        this->Mark = this->At;
        this->skip(8 * reals);
        this->binaryCoordinates(tag, this->Mark);
      }
      else
      {
        this->fields();
        if (this->Fields.size() != reals)
        {
          this->fail("node " + std::to_string(tag) + " has " + std::to_string(this->Fields.size()) + " coordinates; its block's have " +
            std::to_string(reals));
        }
        this->asciiCoordinates(tag, 0);
      }
    }
  }

  // ---- elements ----------------------------------------------------------------------------------

  std::uint32_t owner(int dim, std::vector<int> physicals)
  {
    std::sort(physicals.begin(), physicals.end());
    physicals.erase(std::unique(physicals.begin(), physicals.end()), physicals.end());
    physicals.erase(std::remove(physicals.begin(), physicals.end(), 0), physicals.end());
    if (dim < 0 || physicals.empty())
    {
      return 0;
    }
    const auto [found, added] = this->OwnerIndex.emplace(std::make_pair(dim, physicals), static_cast<std::uint32_t>(this->Owners.size()));
    if (added)
    {
      this->Owners.push_back({ dim, physicals });
    }
    return found->second;
  }

  TypeGroup& group(std::int64_t type, int dim)
  {
    const auto [found, added] = this->GroupOfType.emplace(type, this->Groups.size());
    if (added)
    {
      const ElementType known = elementType(type);
      TypeGroup group;
      group.type = type;
      group.dim = known.family == Family::None ? dim : dimension(known.family);
      group.nodesEach = known.family == Family::None ? static_cast<int>(this->Pending.size()) : known.nodes;
      this->Groups.push_back(std::move(group));
    }
    return this->Groups[found->second];
  }

  // Stores the element of Pending's nodes, which must exist.
  void element(std::int64_t type, int dim, std::int64_t id, std::uint32_t owner)
  {
    TypeGroup& group = this->group(type, dim);
    if (this->Pending.size() != static_cast<std::size_t>(group.nodesEach))
    {
      this->fail("element " + std::to_string(id) + " has " + std::to_string(this->Pending.size()) + " nodes; " +
        (elementType(type).family == Family::None ? "the first of its type " + std::to_string(type) + " has "
                                                  : "a " + typeName(elementType(type)) + " has ") +
        std::to_string(group.nodesEach));
    }
    for (const std::int64_t node : this->Pending)
    {
      if (this->Nodes->find(node) == IdIndex::none)
      {
        this->fail("element " + std::to_string(id) + " refers to node " + std::to_string(node) + ", which $Nodes does not define");
      }
    }
    group.ids.push_back(id);
    group.nodes.insert(group.nodes.end(), this->Pending.begin(), this->Pending.end());
    group.owners.push_back(owner);
    group.offsets.push_back(this->Mark);
  }

  void elements()
  {
    if (!this->Nodes)
    {
      this->fail("$Elements before $Nodes");
    }
    if (this->ElementsRead)
    {
      this->fail("a second $Elements");
    }
    this->ElementsRead = true;
    if (this->Version2)
    {
      this->fields(1, "the number of elements");
      const std::uint64_t total = this->count(this->Fields[0], "a number of elements");
      this->room(total, 8, "elements");
      if (this->Binary)
      {
        this->binaryElements2(total);
      }
      else
      {
        this->asciiElements2(total);
      }
    }
    else
    {
      this->elements4();
    }
    this->endSection();
  }

  // MSH 2.2: an element's line is "tag type number-of-tags tags... nodes...", its tags the
  // physical group's, the elementary entity's and partitions.
  void asciiElements2(std::uint64_t total)
  {
    std::int64_t lastType = 0, lastElementary = 0;
    for (std::uint64_t i = 0; i < total; ++i)
    {
      if (this->LayoutOnly)
      {
        this->record();
        continue;
      }
      this->fields();
      if (this->Fields.size() < 3)
      {
        this->fail("an element's line is \"tag type number-of-tags tags... nodes...\"");
      }
      const std::int64_t id = this->tag(this->Fields[0], "an element tag");
      const std::int64_t type = this->integer(this->Fields[1], "an element type");
      const std::uint64_t tags = this->count(this->Fields[2], "a number of tags");
      if (this->Fields.size() < 3 + tags)
      {
        this->fail("element " + std::to_string(id) + " has fewer fields than its " + std::to_string(tags) + " tags");
      }
      const std::int64_t physical = tags > 0 ? this->integer(this->Fields[3], "a physical tag") : 0;
      const std::int64_t elementary = tags > 1 ? this->integer(this->Fields[4], "an elementary tag") : 0;
      this->Pending.clear();
      for (std::size_t k = 3 + tags; k < this->Fields.size(); ++k)
      {
        this->Pending.push_back(this->tag(this->Fields[k], "a node tag"));
      }
      this->element2(type, id, physical, elementary, lastType, lastElementary);
    }
  }

  // MSH 2.2 binary: blocks of a header (type, elements, tags) and the elements' ints.
  void binaryElements2(std::uint64_t total)
  {
    std::int64_t lastType = 0, lastElementary = 0;
    for (std::uint64_t read = 0; read < total;)
    {
      this->Mark = this->At;
      const std::int32_t type = this->take<std::int32_t>();
      const std::uint64_t count = this->takeCount("a number of elements");
      const std::uint64_t tags = this->takeCount("a number of tags");
      const ElementType known = elementType(type);
      if (known.family == Family::None)
      {
        this->fail("element type " + std::to_string(type) + " is not one of Gmsh's: its elements cannot be skipped");
      }
      const std::uint64_t ints = 1 + tags + known.nodes;
      this->room(count, 4 * ints, "elements in a block");
      if (count > total - read)
      {
        this->fail("a block of " + std::to_string(count) + " elements: more than the " + std::to_string(total) + " of $Elements");
      }
      read += count;
      if (this->LayoutOnly)
      {
        this->skip(4 * ints * count);
        continue;
      }
      for (std::uint64_t e = 0; e < count; ++e)
      {
        this->Mark = this->At;
        const std::int64_t id = this->takeTag("element tag");
        std::int64_t physical = 0, elementary = 0;
        for (std::uint64_t k = 0; k < tags; ++k)
        {
          const std::int32_t value = this->take<std::int32_t>();
          physical = k == 0 ? value : physical;
          elementary = k == 1 ? value : elementary;
        }
        this->Pending.clear();
        for (int k = 0; k < known.nodes; ++k)
        {
          this->Pending.push_back(this->takeTag("node tag"));
        }
        this->element2(type, id, physical, elementary, lastType, lastElementary);
      }
    }
  }

  // An MSH 2.2 element; the one before it again (the same type, entity and nodes) is that element
  // in one more physical group.
  void element2(std::int64_t type, std::int64_t id, std::int64_t physical, std::int64_t elementary, std::int64_t& lastType,
    std::int64_t& lastElementary)
  {
    const int dim = dimension(elementType(type).family);
    const auto last = this->GroupOfType.find(type);
    if (type == lastType && elementary == lastElementary && last != this->GroupOfType.end())
    {
      TypeGroup& group = this->Groups[last->second];
      const std::size_t size = this->Pending.size();
      if (size == static_cast<std::size_t>(group.nodesEach) && std::equal(this->Pending.begin(), this->Pending.end(), group.nodes.end() - size))
      {
        std::vector<int> physicals = this->Owners[group.owners.back()].physicals;
        physicals.push_back(static_cast<int>(std::abs(physical)));
        group.owners.back() = this->owner(dim, physicals);
        return;
      }
    }
    this->element(type, dim, id, this->owner(dim, { static_cast<int>(std::abs(physical)) }));
    lastType = type;
    lastElementary = elementary;
  }

  // MSH 4.1: blocks of an entity's elements of one type, each "tag nodes...".
  void elements4()
  {
    std::uint64_t blocks = 0, total = 0;
    if (this->Binary)
    {
      this->Mark = this->At;
      blocks = this->take<std::uint64_t>();
      total = this->take<std::uint64_t>();
      this->skip(16); // min and max tags
    }
    else
    {
      this->fields(4, "\"blocks elements min-tag max-tag\"");
      blocks = this->count(this->Fields[0], "a number of blocks");
      total = this->count(this->Fields[1], "a number of elements");
    }
    this->room(blocks, this->Binary ? 20 : 8, "element blocks");
    this->room(total, this->Binary ? 16 : 4, "elements");
    std::uint64_t read = 0;
    for (std::uint64_t b = 0; b < blocks; ++b)
    {
      int dim = 0;
      std::int64_t entity = 0, type = 0;
      std::uint64_t count = 0;
      if (this->Binary)
      {
        this->Mark = this->At;
        dim = this->take<std::int32_t>();
        entity = this->take<std::int32_t>();
        type = this->take<std::int32_t>();
        count = this->take<std::uint64_t>();
        if (dim < 0 || dim > 3)
        {
          this->fail("dimension " + std::to_string(dim) + " is not 0, 1, 2 or 3");
        }
      }
      else
      {
        this->fields(4, "\"entity-dimension entity-tag type elements\"");
        dim = this->dimensionField(this->Fields[0]);
        entity = this->integer(this->Fields[1], "an entity tag");
        type = this->integer(this->Fields[2], "an element type");
        count = this->count(this->Fields[3], "a number of elements");
      }
      const ElementType known = elementType(type);
      if (this->Binary && known.family == Family::None)
      {
        this->fail("element type " + std::to_string(type) + " is not one of Gmsh's: its elements cannot be skipped");
      }
      this->room(count, this->Binary ? 8 * (1 + known.nodes) : 2, "elements in a block");
      read += count;
      if (this->LayoutOnly && this->Binary)
      {
        this->skip(8 * (1 + known.nodes) * count);
        continue;
      }
      if (this->LayoutOnly)
      {
        for (std::uint64_t e = 0; e < count; ++e)
        {
          this->record();
        }
        continue;
      }
      const auto physicals = this->Entities.find({ dim, static_cast<int>(entity) });
      const std::uint32_t owner = physicals == this->Entities.end() ? 0 : this->owner(dim, physicals->second);
      for (std::uint64_t e = 0; e < count; ++e)
      {
        std::int64_t id = 0;
        this->Pending.clear();
        if (this->Binary)
        {
          this->Mark = this->At;
          id = this->takeTag("element tag");
          for (int k = 0; k < known.nodes; ++k)
          {
            this->Pending.push_back(this->takeTag("node tag"));
          }
        }
        else
        {
          this->fields();
          id = this->tag(this->Fields[0], "an element tag");
          for (std::size_t k = 1; k < this->Fields.size(); ++k)
          {
            this->Pending.push_back(this->tag(this->Fields[k], "a node tag"));
          }
        }
        this->element(type, dim, id, owner);
      }
    }
    if (read != total)
    {
      this->fail("the blocks of $Elements hold " + std::to_string(read) + " elements, its header says " + std::to_string(total));
    }
  }

  // ---- the mesh: cells, sets ---------------------------------------------------------------------

  void finish()
  {
    SourceMesh& mesh = this->Out.mesh;
    this->Section = "$Elements";
    int highest = -1;
    for (const TypeGroup& group : this->Groups)
    {
      highest = std::max(highest, group.dim);
    }
    std::vector<std::int64_t> cellIds;
    std::vector<std::size_t> cellOffsets;
    for (TypeGroup& group : this->Groups)
    {
      const ElementType known = elementType(group.type);
      CellKind kind;
      const std::string count = std::to_string(group.ids.size());
      if (known.family == Family::None)
      {
        mesh.warnings.push_back(this->where(group.offsets[0]) + ": element type " + std::to_string(group.type) +
          " is not one of Gmsh's: its " + count + " elements are left out (their nodes are read and move with the rest)");
      }
      else if (group.dim == highest && !cellKind(group.type, kind))
      {
        mesh.warnings.push_back(this->where(group.offsets[0]) + ": element type " + std::to_string(group.type) + " (" +
          typeName(known) + ") is not supported: its " + count + " elements are left out (their nodes are read and move with the rest)");
      }
      else if (group.dim == highest)
      {
        group.cell = true;
        ElementBlock block{ typeName(known), kind.type, group.ids, {} };
        block.nodes.reserve(group.nodes.size());
        for (std::size_t e = 0; e < group.ids.size(); ++e)
        {
          for (int k = 0; k < known.nodes; ++k)
          {
            block.nodes.push_back(group.nodes[e * known.nodes + (kind.order.empty() ? k : kind.order[k])]);
          }
        }
        cellIds.insert(cellIds.end(), group.ids.begin(), group.ids.end());
        cellOffsets.insert(cellOffsets.end(), group.offsets.begin(), group.offsets.end());
        mesh.blocks.push_back(std::move(block));
      }
    }
    const IdIndex cells(cellIds);
    if (cells.duplicate != IdIndex::none)
    {
      this->failAt(cellOffsets[cells.duplicate], "element " + std::to_string(cellIds[cells.duplicate]) + " is defined twice");
    }
    this->sets(highest);
  }

  // Every physical group, in the order of (dimension, tag): a node set, and those of dimension
  // highest an element set. A name that several groups have (Gmsh allows it across dimensions) is
  // told apart: "name (physical <dim> <tag>)".
  void sets(int highest)
  {
    SourceMesh& mesh = this->Out.mesh;
    std::map<std::string, int> uses;
    for (const auto& named : this->Names)
    {
      ++uses[named.second];
    }
    std::map<std::pair<int, int>, std::size_t> groups;
    for (const auto& named : this->Names)
    {
      groups.emplace(named.first, 0);
    }
    for (const Owner& owner : this->Owners)
    {
      for (const int physical : owner.physicals)
      {
        groups.emplace(std::make_pair(owner.dim, physical), 0);
      }
    }
    std::size_t next = 0;
    for (auto& entry : groups)
    {
      entry.second = next++;
    }
    std::vector<std::vector<std::size_t>> ownerGroups(this->Owners.size());
    for (std::size_t o = 0; o < this->Owners.size(); ++o)
    {
      for (const int physical : this->Owners[o].physicals)
      {
        ownerGroups[o].push_back(groups.at({ this->Owners[o].dim, physical }));
      }
    }
    // each group's nodes (their positions in $Nodes) and cells (where they are, and their tags)
    std::vector<std::vector<std::size_t>> nodes(groups.size());
    std::vector<std::vector<std::pair<std::uint64_t, std::int64_t>>> elements(groups.size());
    for (const TypeGroup& group : this->Groups)
    {
      for (std::size_t e = 0; e < group.ids.size(); ++e)
      {
        for (const std::size_t g : ownerGroups[group.owners[e]])
        {
          for (int k = 0; k < group.nodesEach; ++k)
          {
            nodes[g].push_back(this->Nodes->find(group.nodes[e * group.nodesEach + k]));
          }
          if (group.cell)
          {
            elements[g].emplace_back(group.offsets[e], group.ids[e]);
          }
        }
      }
    }
    for (const auto& [key, g] : groups)
    {
      const auto named = this->Names.find(key);
      const std::string number = "physical " + std::to_string(key.first) + " " + std::to_string(key.second);
      const std::string name = named == this->Names.end() ? number
        : uses[named->second] > 1                         ? named->second + " (" + number + ")"
                                                          : named->second;
      std::vector<std::size_t>& positions = nodes[g];
      std::sort(positions.begin(), positions.end());
      positions.erase(std::unique(positions.begin(), positions.end()), positions.end());
      NamedSet nodeSet{ name, {} };
      nodeSet.ids.reserve(positions.size());
      for (const std::size_t position : positions)
      {
        nodeSet.ids.push_back(mesh.nodeIds[position]);
      }
      mesh.nodeSets.push_back(std::move(nodeSet));
      if (key.first == highest)
      {
        std::sort(elements[g].begin(), elements[g].end());
        NamedSet elementSet{ name, {} };
        for (const auto& element : elements[g])
        {
          elementSet.ids.push_back(element.second);
        }
        mesh.elementSets.push_back(std::move(elementSet));
      }
    }
  }
};
} // namespace

MshFile readMsh(const std::string& path)
{
  return std::move(Reader(path, false).Out);
}

MshFile readMshLayout(const std::string& path)
{
  return std::move(Reader(path, true).Out);
}

bool isMsh(const std::string& head)
{
  return head.compare(0, 11, "$MeshFormat") == 0;
}

// ---- the variant -------------------------------------------------------------------------------

void MshFile::writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
  bool overwrite) const
{
  VariantSource source = variantSource(target, this->path, this->hash, this->mesh.nodeIds, ids, xyz, count);
  const std::vector<std::size_t>& row = source.row;
  AtomicWrite write(overwrite);
  AtomicWrite::Aside out = write.open(target);
  rewriteInPieces(out, source.file, count, this->nodesEnd, [&](std::size_t k) { return this->coordinates[k]; },
    [&](std::string& piece, std::string_view text, std::size_t at, std::size_t k) {
      return this->binary ? appendBinaryNumbers<double>(piece, text, at, 3, xyz + 3 * row[k])
                          : appendNumbers(piece, text, at, 3, xyz + 3 * row[k], this->mesh.xyz.data() + 3 * k);
    });
  write.close(out);
  write.commit();
}
} // namespace gmsh
} // namespace mlsformats
