#include "Fluent/FluentMesh.h"

#include "Common/IdIndex.h"
#include "Common/Pieces.h"
#include "Common/TextFile.h"
#include "Common/VariantNodes.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string_view>

namespace mlsformats
{
namespace fluent
{
namespace
{
bool isSpace(char c)
{
  return c == ' ' || c == '\t' || c == '\r' || c == '\n';
}

// A number or a name ends at a blank or a parenthesis.
bool endsToken(char c)
{
  return isSpace(c) || c == '(' || c == ')';
}

constexpr std::string_view EndOfBinary = "End of Binary Section";

// The shortest text of a number (in messages).
std::string shortest(double value)
{
  std::string text;
  appendShortest(text, value);
  return text;
}

// The index of a binary section: the ASCII one's after 20 (single precision) or 30 (double).
bool isBinary(long index)
{
  return index >= 2000 && index < 4000;
}

// ---- cells from their faces ----------------------------------------------------------------------

// A face of a cell: its nodes, and whether the cell is its c0 (which its nodes' normal points into;
// in 2D: which is on the left of its edge).
struct Side
{
  const std::int64_t* nodes;
  std::size_t count;
  bool c0;
};

bool contains(const std::vector<std::int64_t>& nodes, std::int64_t node)
{
  return std::find(nodes.begin(), nodes.end(), node) != nodes.end();
}

// The side's nodes, turning about the normal into the cell (inward) or out of it.
std::vector<std::int64_t> turned(const Side& side, bool inward)
{
  std::vector<std::int64_t> nodes(side.nodes, side.nodes + side.count);
  if (side.c0 != inward)
  {
    std::reverse(nodes.begin(), nodes.end());
  }
  return nodes;
}

// The node next to node along an edge of the sides that leaves base; 0 (no node's index) if none.
std::int64_t across(const std::vector<Side>& sides, const std::vector<std::int64_t>& base, std::int64_t node)
{
  for (const Side& side : sides)
  {
    for (std::size_t k = 0; k < side.count; ++k)
    {
      if (side.nodes[k] != node)
      {
        continue;
      }
      for (const std::int64_t next : { side.nodes[(k + 1) % side.count], side.nodes[(k + side.count - 1) % side.count] })
      {
        if (!contains(base, next))
        {
          return next;
        }
      }
    }
  }
  return 0;
}

// A 3D cell's type and its nodes in VTK's order, from its faces; false when they are not a
// tetrahedron's (4 triangles), a pyramid's (4 triangles, a quadrilateral), a wedge's (2 triangles,
// 3 quadrilaterals) or a hexahedron's (6 quadrilaterals). VTK's nodes 0-2 (0-3) are a face turning
// about the normal into the cell (vtkTetra, vtkPyramid, vtkHexahedron), a wedge's out of it: VTK
// 9's vtkWedge has (1 - 0) x (2 - 0) point away from 3-4-5. The others are across the edges that
// leave that face: a hexahedron's 4-7 and a wedge's 3-5 over 0-3 (0-2), the apex.
bool solid(const std::vector<Side>& sides, CellType& type, std::vector<std::int64_t>& nodes)
{
  std::size_t triangles = 0, quadrilaterals = 0;
  const Side* triangle = nullptr;
  const Side* quadrilateral = nullptr;
  for (const Side& side : sides)
  {
    if (side.count == 3)
    {
      ++triangles;
      triangle = triangle ? triangle : &side;
    }
    else if (side.count == 4)
    {
      ++quadrilaterals;
      quadrilateral = quadrilateral ? quadrilateral : &side;
    }
    else
    {
      return false;
    }
  }
  if (triangles == 4 && quadrilaterals == 0)
  {
    type = CellType::Tetra;
    nodes = turned(*triangle, true);
  }
  else if (triangles == 4 && quadrilaterals == 1)
  {
    type = CellType::Pyramid;
    nodes = turned(*quadrilateral, true);
  }
  else if (triangles == 2 && quadrilaterals == 3)
  {
    type = CellType::Wedge;
    nodes = turned(*triangle, false);
  }
  else if (triangles == 0 && quadrilaterals == 6)
  {
    type = CellType::Hexahedron;
    nodes = turned(*quadrilateral, true);
  }
  else
  {
    return false;
  }
  const std::vector<std::int64_t> base = nodes;
  const bool apex = type == CellType::Tetra || type == CellType::Pyramid;
  for (std::size_t k = 0; k < (apex ? 1 : base.size()); ++k)
  {
    nodes.push_back(across(sides, base, base[k]));
  }
  // each node once, and every face's nodes among them
  std::vector<std::int64_t> sorted = nodes;
  std::sort(sorted.begin(), sorted.end());
  if (sorted.front() == 0 || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end())
  {
    return false;
  }
  for (const Side& side : sides)
  {
    for (std::size_t k = 0; k < side.count; ++k)
    {
      if (!std::binary_search(sorted.begin(), sorted.end(), side.nodes[k]))
      {
        return false;
      }
    }
  }
  return true;
}

// A 2D cell's type and its nodes turning counter-clockwise, from its edges (each with the cell on
// its left when the cell is its c0); false when they are not a triangle's or a quadrilateral's.
bool planar(const std::vector<Side>& sides, CellType& type, std::vector<std::int64_t>& nodes)
{
  std::vector<std::pair<std::int64_t, std::int64_t>> edges;
  for (const Side& side : sides)
  {
    if (side.count != 2)
    {
      return false;
    }
    edges.emplace_back(side.c0 ? side.nodes[0] : side.nodes[1], side.c0 ? side.nodes[1] : side.nodes[0]);
  }
  if (edges.size() != 3 && edges.size() != 4)
  {
    return false;
  }
  type = edges.size() == 3 ? CellType::Triangle : CellType::Quad;
  nodes.assign(1, edges[0].first);
  std::int64_t next = edges[0].second;
  edges.erase(edges.begin());
  while (!edges.empty())
  {
    const auto edge = std::find_if(edges.begin(), edges.end(), [&](const auto& e) { return e.first == next; });
    if (edge == edges.end() || contains(nodes, next))
    {
      return false;
    }
    nodes.push_back(next);
    next = edge->second;
    edges.erase(edge);
  }
  return next == nodes[0];
}

// Fluent's names of the element types.
std::string typeName(CellType type)
{
  switch (type)
  {
    case CellType::Triangle: return "triangular";
    case CellType::Quad: return "quadrilateral";
    case CellType::Tetra: return "tetrahedral";
    case CellType::Hexahedron: return "hexahedral";
    case CellType::Pyramid: return "pyramid";
    default: return "wedge"; // the one other type that cells are rebuilt as
  }
}

// ---- the reader ----------------------------------------------------------------------------------

// A zone of faces or cells: its id, its indices first..last, its type (a face zone's bc-type, 2
// interior; a cell zone's, 0 dead and 32 inactive), where its section starts, and a face zone's
// first face (its position in the reader's faces).
struct Zone
{
  std::int64_t id, first, last, type;
  std::size_t offset, faces;
};

// Whether a cell zone's cells are the mesh's: not a dead zone's (type 0), nor an inactive one's (32).
bool active(const Zone& zone)
{
  return zone.type != 0 && zone.type != 32;
}

// Whether a face zone's faces are between cells (bc-type 2), not on a boundary.
bool interior(const Zone& zone)
{
  return zone.type == 2;
}

// A binary section's bytes [begin, end) and its index: its errors name the section and the byte.
struct BinarySection
{
  std::size_t begin, end;
  long index;
};

class Reader
{
public:
  Reader(const std::string& path, bool layoutOnly)
    : LayoutOnly(layoutOnly)
    , Text(readFile(path))
  {
    this->Out.path = path;
    this->Out.hash = contentHash(this->Text);
    while (this->nextSection())
    {
      this->section();
    }
    const std::vector<std::int64_t>& ids = this->Out.mesh.nodeIds;
    if (ids.empty())
    {
      throw FileError(path, 0,
        "has no node zone (a section \"(10 (zone first last type ND)(...))\"): not a Fluent mesh, or a case file without its mesh");
    }
    this->Nodes.emplace(ids);
    if (this->Nodes->duplicate != IdIndex::none)
    {
      const std::size_t twice = this->Nodes->duplicate;
      this->failAt(this->Out.coordinates[twice], "node " + std::to_string(ids[twice]) + " is defined twice");
    }
    this->Out.dimension = this->Dimension;
    if (!layoutOnly)
    {
      this->finish();
    }
  }

  MeshFile Out;

private:
  bool LayoutOnly;
  const std::string Text;
  std::size_t At = 0;   // the next byte to read
  std::size_t Mark = 0; // where what was read last starts: errors name it
  long Index = 0;       // the section being read, which starts at Start
  std::size_t Start = 0;
  bool InBinary = false;
  std::vector<BinarySection> Binary;
  int Dimension = 0; // 0 until a section gives it
  std::optional<IdIndex> Nodes;
  std::map<std::int64_t, std::string> Names; // the 39 and 45 sections'
  std::vector<Zone> FaceZones, CellZones;
  // the faces in file order: their nodes (from FaceStart[f] to FaceStart[f + 1]), cells (c0 c1),
  // zones (in FaceZones) and where each starts in the file
  std::vector<std::int64_t> FaceNodes;
  std::vector<std::size_t> FaceStart{ 0 };
  std::vector<std::int64_t> FaceCells;
  std::vector<std::uint32_t> FaceZoneOf;
  std::vector<std::size_t> FaceOffsets;

  // ---- errors ----------------------------------------------------------------------------------

  std::size_t lineOf(std::size_t offset) const
  {
    offset = std::min(offset, this->Text.empty() ? 0 : this->Text.size() - 1);
    return 1 + static_cast<std::size_t>(std::count(this->Text.begin(), this->Text.begin() + offset, '\n'));
  }

  // The binary section the byte at offset is in, or nullptr.
  const BinarySection* binaryAt(std::size_t offset) const
  {
    auto after = std::upper_bound(this->Binary.begin(), this->Binary.end(), offset,
      [](std::size_t at, const BinarySection& section) { return at < section.begin; });
    return after != this->Binary.begin() && offset < (after - 1)->end ? &*(after - 1) : nullptr;
  }

  // "file:line" of the byte at offset; in a binary section: "file: section 3010, byte offset".
  std::string where(std::size_t offset) const
  {
    const BinarySection* binary = this->binaryAt(offset);
    return binary ? this->Out.path + ": section " + std::to_string(binary->index) + ", byte " + std::to_string(offset)
                  : this->Out.path + ":" + std::to_string(this->lineOf(offset));
  }

  [[noreturn]] void failAt(std::size_t offset, const std::string& reason) const
  {
    const BinarySection* binary = this->binaryAt(offset);
    if (binary)
    {
      throw FileError(this->Out.path, 0, "section " + std::to_string(binary->index) + ", byte " + std::to_string(offset) + ": " + reason);
    }
    throw FileError(this->Out.path, this->lineOf(offset), reason);
  }

  [[noreturn]] void fail(const std::string& reason) const { this->failAt(this->Mark, reason); }

  [[noreturn]] void truncated() const
  {
    this->failAt(this->Text.size(), "the file ends inside section " + std::to_string(this->Index) + ", which starts at " +
        (this->InBinary ? "byte " + std::to_string(this->Start) : "line " + std::to_string(this->lineOf(this->Start))) +
        " (the file is cut short, or its parentheses do not balance)");
  }

  // A count read from the file is at most what the rest of the file holds at bytesEach (at least)
  // an item: a huge count is refused before anything is allocated for it.
  void room(std::uint64_t count, std::uint64_t bytesEach, const std::string& what) const
  {
    if (count > (this->Text.size() - this->At) / bytesEach)
    {
      this->fail(std::to_string(count) + " " + what + ": more than the rest of the file holds (is it cut short?)");
    }
  }

  // ---- sections --------------------------------------------------------------------------------

  void skipSpace()
  {
    while (this->At < this->Text.size() && isSpace(this->Text[this->At]))
    {
      ++this->At;
    }
  }

  // The next section's "(index", or false at the end of the file.
  bool nextSection()
  {
    this->skipSpace();
    if (this->At == this->Text.size())
    {
      return false;
    }
    this->Mark = this->At;
    if (this->Text[this->At] != '(')
    {
      this->fail(this->Text[this->At] == ')' ? "\")\" closes no section (the parentheses do not balance)"
                                             : "text outside a section (a section starts with \"(\" and its index)");
    }
    this->Start = this->At++;
    this->skipSpace();
    const char* end = this->Text.data() + this->Text.size();
    const auto parsed = std::from_chars(this->Text.data() + this->At, end, this->Index);
    if (parsed.ec != std::errc() || this->Index < 0 || (parsed.ptr != end && !endsToken(*parsed.ptr) && *parsed.ptr != '"'))
    {
      this->fail("\"(\" not followed by a section index (a decimal number)");
    }
    this->At = static_cast<std::size_t>(parsed.ptr - this->Text.data());
    this->InBinary = isBinary(this->Index);
    if (this->InBinary)
    {
      this->Binary.push_back({ this->Start, std::string::npos, this->Index });
    }
    return true;
  }

  void section()
  {
    const long kind = this->InBinary ? this->Index % 1000 : this->Index;
    if (kind == 2 && !this->InBinary)
    {
      this->dimensionSection();
    }
    else if (kind == 10)
    {
      this->nodes();
    }
    else if ((kind == 39 || kind == 45) && !this->InBinary)
    {
      this->names(); // the layout too: it must end where the full read ends, whatever a name holds
    }
    else if (this->LayoutOnly)
    {
      this->skipRest();
    }
    else if (kind == 12)
    {
      this->cells();
    }
    else if (kind == 13)
    {
      this->faces();
    }
    else
    {
      this->skipRest();
    }
  }

  // Skips the rest of the section to its closing parenthesis: an ASCII one's lists and strings,
  // a binary one's data to its end "End of Binary Section 3010)" (if it has data).
  void skipRest()
  {
    if (this->InBinary)
    {
      this->skipSpace();
      if (this->At < this->Text.size() && this->Text[this->At] == ')')
      {
        this->close();
        return;
      }
      const std::size_t marker = this->Text.find(EndOfBinary, this->At);
      if (marker == std::string::npos)
      {
        this->truncated();
      }
      this->At = marker + EndOfBinary.size();
      this->skipSpace();
      this->Mark = this->At;
      long index = 0;
      const auto [end, error] = std::from_chars(this->Text.data() + this->At, this->Text.data() + this->Text.size(), index);
      if (error != std::errc() || index != this->Index)
      {
        this->fail("not the end of binary section " + std::to_string(this->Index) + " that the data lead to");
      }
      this->At = static_cast<std::size_t>(end - this->Text.data());
      this->skipSpace();
      if (this->At >= this->Text.size())
      {
        this->truncated();
      }
      if (this->Text[this->At] != ')')
      {
        this->failAt(this->At, "\"End of Binary Section " + std::to_string(index) + "\" not followed by \")\"");
      }
      this->close();
      return;
    }
    for (int depth = 1; depth > 0;)
    {
      if (this->At >= this->Text.size())
      {
        this->truncated();
      }
      const char c = this->Text[this->At++];
      if (c == '"')
      {
        while (this->At < this->Text.size() && this->Text[this->At] != '"')
        {
          this->At += this->Text[this->At] == '\\' ? 2 : 1;
        }
        ++this->At;
      }
      depth += c == '(' ? 1 : c == ')' ? -1 : 0;
    }
  }

  // The section's closing parenthesis at At.
  void close()
  {
    ++this->At;
    if (this->InBinary)
    {
      this->Binary.back().end = this->At;
    }
  }

  // The next token of a list (a number, a name), or "" at a parenthesis (not read).
  std::string_view token()
  {
    this->skipSpace();
    if (this->At >= this->Text.size())
    {
      this->truncated();
    }
    this->Mark = this->At;
    while (this->At < this->Text.size() && !endsToken(this->Text[this->At]))
    {
      ++this->At;
    }
    return std::string_view(this->Text).substr(this->Mark, this->At - this->Mark);
  }

  // A list of tokens "(a b c)" (form: what it holds).
  std::vector<std::string_view> list(const char* form)
  {
    this->skipSpace();
    const std::size_t begin = this->Mark = this->At;
    if (this->At >= this->Text.size())
    {
      this->truncated();
    }
    if (this->Text[this->At] != '(')
    {
      this->fail("section " + std::to_string(this->Index) + " without its header " + form);
    }
    ++this->At;
    std::vector<std::string_view> tokens;
    for (std::string_view next = this->token(); !next.empty(); next = this->token())
    {
      tokens.push_back(next);
    }
    if (this->Text[this->At] != ')')
    {
      this->failAt(this->At, std::string("a list inside the header ") + form);
    }
    ++this->At;
    this->Mark = begin;
    return tokens;
  }

  std::int64_t hexadecimal(std::string_view token, const std::string& what) const
  {
    std::int64_t value = -1;
    const char* end = token.data() + token.size();
    const auto parsed = std::from_chars(token.data(), end, value, 16);
    if (parsed.ec != std::errc() || parsed.ptr != end || value < 0)
    {
      this->failAt(static_cast<std::size_t>(token.data() - this->Text.data()),
        "\"" + std::string(token) + "\" is not " + what + " (a hexadecimal number)");
    }
    return value;
  }

  // A header of at least least hexadecimal numbers.
  std::vector<std::int64_t> header(std::size_t least, const char* form)
  {
    const std::vector<std::string_view> tokens = this->list(form);
    if (tokens.size() < least)
    {
      this->fail("a header of " + std::to_string(tokens.size()) + " numbers where " + form + " is expected");
    }
    std::vector<std::int64_t> values;
    for (const std::string_view token : tokens)
    {
      values.push_back(this->hexadecimal(token, "a header's number"));
    }
    return values;
  }

  // The number of indices first..last of a header (zone first last ...), which start from 1.
  std::uint64_t range(const std::vector<std::int64_t>& header, const char* what) const
  {
    if (header[1] < 1 || header[2] < header[1] - 1)
    {
      this->fail(std::string(what) + " zone " + std::to_string(header[0]) + ": its indices " + std::to_string(header[1]) + " to " +
        std::to_string(header[2]) + " are not a range from 1 up");
    }
    return static_cast<std::uint64_t>(header[2] - header[1] + 1);
  }

  void dimension(std::int64_t dimension)
  {
    if (dimension != 2 && dimension != 3)
    {
      this->fail("dimension " + std::to_string(dimension) + " is neither 2 nor 3");
    }
    if (this->Dimension != 0 && dimension != this->Dimension)
    {
      this->fail("dimension " + std::to_string(dimension) + " in a mesh of dimension " + std::to_string(this->Dimension));
    }
    this->Dimension = static_cast<int>(dimension);
  }

  // "(2 ND)"
  void dimensionSection()
  {
    const std::string_view value = this->token();
    std::int64_t dimension = 0;
    if (!parseInteger(value.data(), value.data() + value.size(), dimension))
    {
      this->fail("\"" + std::string(value) + "\" is not a dimension (2 or 3)");
    }
    this->dimension(dimension);
    this->skipRest();
  }

  // "(39 (id type name)(...))" and "(45 (id type name)())": the zone id decimal.
  void names()
  {
    const std::vector<std::string_view> tokens = this->list("(id type name)");
    std::int64_t id = -1;
    if (tokens.size() < 3 || !parseInteger(tokens[0].data(), tokens[0].data() + tokens[0].size(), id) || id < 0)
    {
      this->fail("a zone's name is not given as (id type name), its id decimal");
    }
    this->Names[id] = std::string(tokens[2]);
    this->skipRest();
  }

  // Enters the section's data list: its first byte is right after the "(".
  void enterData(const char* what)
  {
    this->skipSpace();
    this->Mark = this->At;
    if (this->At >= this->Text.size())
    {
      this->truncated();
    }
    if (this->Text[this->At] != '(')
    {
      this->fail(std::string("the header is not followed by the list of ") + what);
    }
    ++this->At;
  }

  // The data list's ")", where the header's count says the data end.
  void leaveData(const std::string& count)
  {
    if (!this->InBinary)
    {
      this->skipSpace();
    }
    if (this->At >= this->Text.size())
    {
      this->truncated();
    }
    if (this->Text[this->At] != ')')
    {
      this->failAt(this->At, this->InBinary ? "the binary data do not end where the header's " + count + " end (are its numbers "
                                                                                            "not of 32-bit integers, floats or doubles?)"
                                            : "more data than the header's " + count);
    }
    ++this->At;
  }

  // The binary number at offset.
  template <class T>
  double number(std::size_t offset) const
  {
    T value;
    std::memcpy(&value, this->Text.data() + offset, sizeof(T));
    return value;
  }

  // The data's next integer: binary a 32-bit one, text a hexadecimal number.
  std::int64_t integer(const char* what)
  {
    if (this->InBinary)
    {
      this->Mark = this->At;
      if (this->Text.size() - this->At < 4)
      {
        this->truncated();
      }
      const std::int64_t value = static_cast<std::int64_t>(this->number<std::int32_t>(this->At));
      this->At += 4;
      if (value < 0)
      {
        this->fail(std::string(what) + " " + std::to_string(value) + " is negative");
      }
      return value;
    }
    const std::string_view next = this->token();
    if (next.empty())
    {
      this->failAt(this->At, std::string("the data end where the header's counts want ") + what);
    }
    return this->hexadecimal(next, what);
  }

  // "(10 (zone first last type ND)(x y z ...))", ND and the data list absent in the declaration of
  // the number of nodes (zone 0).
  void nodes()
  {
    const std::vector<std::int64_t> header = this->header(4, "(zone first last type [ND])");
    if (header.size() > 4)
    {
      this->dimension(header[4]);
    }
    this->Dimension = this->Dimension ? this->Dimension : 3;
    if (header[0] == 0)
    {
      this->skipRest();
      return;
    }
    const std::uint64_t count = this->range(header, "node");
    const int size = !this->InBinary ? 0 : this->Index < 3000 ? 4 : 8;
    const int dimension = this->Dimension;
    this->enterData("coordinates");
    this->room(count, this->InBinary ? dimension * size : 2 * dimension, "nodes");
    this->Out.nodeZones.push_back({ size == 0 ? Precision::Text : size == 4 ? Precision::Single : Precision::Double, count });
    SourceMesh& mesh = this->Out.mesh;
    mesh.nodeIds.reserve(mesh.nodeIds.size() + count);
    this->Out.coordinates.reserve(this->Out.coordinates.size() + count);
    mesh.xyz.reserve(mesh.xyz.size() + 3 * count);
    for (std::uint64_t i = 0; i < count; ++i)
    {
      const std::int64_t id = header[1] + static_cast<std::int64_t>(i);
      double xyz[3] = { 0, 0, 0 };
      std::size_t first = this->At;
      if (this->InBinary)
      {
        this->Mark = first;
        this->At += dimension * size;
        for (int c = 0; c < dimension; ++c)
        {
          xyz[c] = size == 4 ? this->number<float>(first + c * size) : this->number<double>(first + c * size);
          if (!std::isfinite(xyz[c]))
          {
            this->fail("node " + std::to_string(id) + "'s coordinate " + shortest(xyz[c]) + " is not a finite number");
          }
        }
      }
      for (int c = 0; c < dimension && !this->InBinary; ++c)
      {
        const std::string_view value = this->token();
        if (value.empty())
        {
          this->failAt(this->At, "node zone " + std::to_string(header[0]) + " ends after " + std::to_string(i * dimension + c) +
              " coordinates; its " + std::to_string(count) + " nodes have " + std::to_string(count * dimension));
        }
        first = c == 0 ? this->Mark : first;
        if (!parseReal(value.data(), value.data() + value.size(), xyz[c]))
        {
          this->fail("node " + std::to_string(id) + "'s coordinate \"" + std::string(value) + "\" is not a finite number");
        }
      }
      mesh.nodeIds.push_back(id);
      this->Out.coordinates.push_back(first);
      this->Out.nodesEnd = this->At;
      mesh.xyz.insert(mesh.xyz.end(), xyz, xyz + 3);
    }
    this->leaveData(std::to_string(count) + " nodes' coordinates");
    this->skipRest();
  }

  // "(12 (zone first last type element-type)...)": only the zone is read (the cells' shapes are
  // their faces'), the declaration of the number of cells (zone 0) is skipped.
  void cells()
  {
    const std::vector<std::int64_t> header = this->header(4, "(zone first last type [element-type])");
    if (header[0] != 0)
    {
      this->range(header, "cell");
      this->CellZones.push_back({ header[0], header[1], header[2], header[3], this->Start, 0 });
    }
    this->skipRest();
  }

  // "(13 (zone first last bc-type face-type)(n0 n1 ... c0 c1 ...))", each face's number of nodes
  // first in a mixed zone (face-type 0) and a polygonal one (5).
  void faces()
  {
    const std::vector<std::int64_t> header = this->header(4, "(zone first last bc-type [face-type])");
    if (header[0] == 0)
    {
      this->skipRest();
      return;
    }
    const std::uint64_t count = this->range(header, "face");
    const std::int64_t type = header.size() > 4 ? header[4] : 0;
    if (type != 0 && (type < 2 || type > 5))
    {
      this->fail("face type " + std::to_string(type) + " is none of 0 (mixed), 2 (line), 3 (triangle), 4 (quadrilateral), 5 (polygon)");
    }
    const bool counted = type == 0 || type == 5;
    this->enterData("faces");
    this->room(count, (this->InBinary ? 4 : 2) * (counted ? 5 : type + 2), "faces");
    const std::uint32_t zone = static_cast<std::uint32_t>(this->FaceZones.size());
    this->FaceZones.push_back({ header[0], header[1], header[2], header[3], this->Start, this->FaceOffsets.size() });
    for (std::uint64_t i = 0; i < count; ++i)
    {
      if (!this->InBinary)
      {
        this->skipSpace();
      }
      this->FaceOffsets.push_back(this->At);
      const std::int64_t nodes = counted ? this->integer("a face's number of nodes") : type;
      if (nodes < 2)
      {
        this->fail("face " + std::to_string(header[1] + static_cast<std::int64_t>(i)) + " has " + std::to_string(nodes) + " nodes");
      }
      for (std::int64_t k = 0; k < nodes; ++k)
      {
        this->FaceNodes.push_back(this->integer("a node index"));
      }
      this->FaceStart.push_back(this->FaceNodes.size());
      this->FaceCells.push_back(this->integer("a cell index (c0)"));
      this->FaceCells.push_back(this->integer("a cell index (c1)"));
      this->FaceZoneOf.push_back(zone);
    }
    this->leaveData(std::to_string(count) + " faces");
    this->skipRest();
  }

  // ---- the mesh: cells, sets ---------------------------------------------------------------------

  std::string nameOf(std::int64_t id) const
  {
    const auto named = this->Names.find(id);
    return named == this->Names.end() ? "zone " + std::to_string(id) : named->second;
  }

  // The Fluent index of the face at position f.
  std::int64_t faceIndex(std::size_t f) const
  {
    const Zone& zone = this->FaceZones[this->FaceZoneOf[f]];
    return zone.first + static_cast<std::int64_t>(f - zone.faces);
  }

  void finish()
  {
    for (std::size_t f = 0; f < this->FaceOffsets.size(); ++f)
    {
      for (std::size_t k = this->FaceStart[f]; k < this->FaceStart[f + 1]; ++k)
      {
        if (this->Nodes->find(this->FaceNodes[k]) == IdIndex::none)
        {
          this->failAt(this->FaceOffsets[f], "face " + std::to_string(this->faceIndex(f)) + " refers to node " +
              std::to_string(this->FaceNodes[k]) + ", which no node zone holds");
        }
      }
    }
    this->cellZoneSets(this->rebuildCells());
    this->faceZoneSets();
  }

  // The cells of the active zones, rebuilt from their faces into blocks of a type; returns each
  // cell zone's cells.
  std::vector<std::vector<std::int64_t>> rebuildCells()
  {
    // the cell zones by their first index, which must not overlap
    std::vector<std::size_t> byFirst(this->CellZones.size());
    for (std::size_t z = 0; z < byFirst.size(); ++z)
    {
      byFirst[z] = z;
    }
    std::sort(byFirst.begin(), byFirst.end(),
      [&](std::size_t a, std::size_t b) { return this->CellZones[a].first < this->CellZones[b].first; });
    for (std::size_t k = 1; k < byFirst.size(); ++k)
    {
      const Zone &previous = this->CellZones[byFirst[k - 1]], &zone = this->CellZones[byFirst[k]];
      if (zone.first <= previous.last)
      {
        this->failAt(zone.offset,
          "the cells of zone " + std::to_string(zone.id) + " and of zone " + std::to_string(previous.id) + " overlap");
      }
    }
    auto zoneOf = [&](std::int64_t cell) {
      const auto after = std::upper_bound(byFirst.begin(), byFirst.end(), cell,
        [&](std::int64_t c, std::size_t z) { return c < this->CellZones[z].first; });
      return after != byFirst.begin() && cell <= this->CellZones[*(after - 1)].last ? *(after - 1) : IdIndex::none;
    };
    // each cell's faces: (cell, 2 face + 0 for its c0, 1 for its c1), by cell
    std::vector<std::pair<std::int64_t, std::size_t>> sides;
    sides.reserve(this->FaceCells.size());
    for (std::size_t s = 0; s < this->FaceCells.size(); ++s)
    {
      const std::int64_t cell = this->FaceCells[s];
      if (cell != 0 && zoneOf(cell) == IdIndex::none)
      {
        this->failAt(this->FaceOffsets[s / 2], "face " + std::to_string(this->faceIndex(s / 2)) + " refers to cell " +
            std::to_string(cell) + ", which no cell zone holds");
      }
      if (cell != 0)
      {
        sides.emplace_back(cell, s);
      }
    }
    std::sort(sides.begin(), sides.end());
    SourceMesh& mesh = this->Out.mesh;
    std::vector<std::vector<std::int64_t>> zoneCells(this->CellZones.size());
    std::map<CellType, std::size_t> blockOf;
    std::vector<Side> cellSides;
    std::vector<std::int64_t> nodes;
    for (std::size_t begin = 0, end = 0; begin < sides.size(); begin = end)
    {
      const std::int64_t cell = sides[begin].first;
      cellSides.clear();
      for (end = begin; end < sides.size() && sides[end].first == cell; ++end)
      {
        const std::size_t f = sides[end].second / 2, first = this->FaceStart[f];
        cellSides.push_back({ this->FaceNodes.data() + first, this->FaceStart[f + 1] - first, sides[end].second % 2 == 0 });
      }
      const std::size_t zone = zoneOf(cell);
      CellType type;
      if (!active(this->CellZones[zone]) || !(this->Dimension == 2 ? planar(cellSides, type, nodes) : solid(cellSides, type, nodes)))
      {
        continue;
      }
      const auto [block, added] = blockOf.emplace(type, mesh.blocks.size());
      if (added)
      {
        mesh.blocks.push_back({ typeName(type), type, {}, {} });
      }
      mesh.blocks[block->second].ids.push_back(cell);
      mesh.blocks[block->second].nodes.insert(mesh.blocks[block->second].nodes.end(), nodes.begin(), nodes.end());
      zoneCells[zone].push_back(cell);
    }
    return zoneCells;
  }

  // Each cell zone an element set of its cells (zoneCells), the cells it has that were not rebuilt
  // told.
  void cellZoneSets(std::vector<std::vector<std::int64_t>> zoneCells)
  {
    SourceMesh& mesh = this->Out.mesh;
    const std::string shapes =
      this->Dimension == 2 ? "triangles or quadrilaterals (polygons" : "tetrahedra, pyramids, wedges or hexahedra (polyhedra";
    const std::string move = " (their nodes are read and move with the rest)";
    for (std::size_t z = 0; z < this->CellZones.size(); ++z)
    {
      const Zone& zone = this->CellZones[z];
      const std::uint64_t count = static_cast<std::uint64_t>(zone.last - zone.first + 1), built = zoneCells[z].size();
      const std::string name = "cell zone " + this->nameOf(zone.id) + " (" + std::to_string(zone.id) + ")";
      if (!active(zone) && count > 0)
      {
        mesh.warnings.push_back(this->where(zone.offset) + ": " + name + " is " +
          (zone.type == 0 ? "dead" : "inactive (the parents of adapted cells)") + ": its " + std::to_string(count) +
          " cells are left out" + move);
      }
      else if (built < count)
      {
        mesh.warnings.push_back(this->where(zone.offset) + ": " + name + ": " + std::to_string(count - built) + " of its " +
          std::to_string(count) + " cells are not " + shapes + ", cells split by hanging nodes, cells without faces): left out" + move);
      }
      mesh.elementSets.push_back({ this->nameOf(zone.id), std::move(zoneCells[z]) });
    }
  }

  // Each face zone but the interior ones a node set of its faces' nodes.
  void faceZoneSets()
  {
    SourceMesh& mesh = this->Out.mesh;
    std::vector<std::vector<std::size_t>> zoneNodes(this->FaceZones.size());
    for (std::size_t f = 0; f < this->FaceOffsets.size(); ++f)
    {
      for (std::size_t k = this->FaceStart[f]; k < this->FaceStart[f + 1] && !interior(this->FaceZones[this->FaceZoneOf[f]]); ++k)
      {
        zoneNodes[this->FaceZoneOf[f]].push_back(this->Nodes->find(this->FaceNodes[k]));
      }
    }
    for (std::size_t z = 0; z < this->FaceZones.size(); ++z)
    {
      if (interior(this->FaceZones[z]))
      {
        continue;
      }
      std::vector<std::size_t>& positions = zoneNodes[z];
      std::sort(positions.begin(), positions.end());
      positions.erase(std::unique(positions.begin(), positions.end()), positions.end());
      NamedSet set{ this->nameOf(this->FaceZones[z].id), {} };
      set.ids.reserve(positions.size());
      for (const std::size_t position : positions)
      {
        set.ids.push_back(mesh.nodeIds[position]);
      }
      mesh.nodeSets.push_back(std::move(set));
    }
  }
};
} // namespace

MeshFile readFluent(const std::string& path)
{
  return std::move(Reader(path, false).Out);
}

MeshFile readFluentLayout(const std::string& path)
{
  return std::move(Reader(path, true).Out);
}

bool isFluent(const std::string& head)
{
  std::size_t at = head.find_first_not_of(" \t\r\n");
  if (at == std::string::npos || head[at] != '(')
  {
    return false;
  }
  at = head.find_first_not_of(" \t", at + 1);
  const std::size_t digits = at;
  while (at < head.size() && head[at] >= '0' && head[at] <= '9')
  {
    ++at;
  }
  return at != digits && at < head.size() && (endsToken(head[at]) || head[at] == '"');
}

// ---- the variant -------------------------------------------------------------------------------

namespace
{
} // namespace

void MeshFile::writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
  bool overwrite) const
{
  VariantSource source = variantSource(target, this->path, this->hash, this->mesh.nodeIds, ids, xyz, count);
  const std::vector<std::size_t>& row = source.row;
  // each node's zone's precision; a coordinate a single-precision zone cannot hold is refused
  std::vector<Precision> precision(count);
  std::size_t k = 0;
  for (const NodeZone& zone : this->nodeZones)
  {
    for (std::size_t i = 0; i < zone.count; ++i, ++k)
    {
      precision[k] = zone.precision;
      for (int c = 0; c < this->dimension && zone.precision == Precision::Single; ++c)
      {
        const double value = xyz[3 * row[k] + c];
        if (!(std::abs(value) <= std::numeric_limits<float>::max()))
        {
          throw FileError(target, 0, "node " + std::to_string(this->mesh.nodeIds[k]) + "'s coordinate " + shortest(value) +
              " is beyond the range of the single-precision numbers its zone holds");
        }
      }
    }
  }
  AtomicWrite write(overwrite);
  AtomicWrite::Aside out = write.open(target);
  rewriteInPieces(out, source.file, count, this->nodesEnd, [&](std::size_t n) { return this->coordinates[n]; },
    [&](std::string& piece, std::string_view text, std::size_t at, std::size_t n) {
      const double* value = xyz + 3 * row[n];
      if (precision[n] == Precision::Text)
      {
        return appendNumbers(piece, text, at, this->dimension, value, this->mesh.xyz.data() + 3 * n);
      }
      return precision[n] == Precision::Single ? appendBinaryNumbers<float>(piece, text, at, this->dimension, value)
                                               : appendBinaryNumbers<double>(piece, text, at, this->dimension, value);
    });
  write.close(out);
  write.commit();
}
} // namespace fluent
} // namespace mlsformats
