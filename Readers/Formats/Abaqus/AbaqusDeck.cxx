#include "Abaqus/AbaqusDeck.h"

#include "Common/IdIndex.h"
#include "Common/Pieces.h"
#include "Common/VariantNodes.h"
#include "Common/TextFile.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cctype>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <string_view>

namespace fs = std::filesystem;

namespace mlsformats
{
namespace abaqus
{
namespace
{
// ---- element types ---------------------------------------------------------------------------

// How an element's faces are named in *SURFACE: solids S1..S6 by their faces, shells by both sides
// (SPOS, SNEG, S1, S2) and their edges (S3.., E1..), plane and axisymmetric elements S1.. by edges.
enum class Family
{
  Solid,
  Shell,
  Plane,
  Line
};

struct ElementKind
{
  CellType type;
  Family family;
  std::vector<int> order; // VTK's node i is the file's node order[i] (empty: the same)
};

// The cell type of an Abaqus element type ("C3D10", "C3D8R", "S4R", "CPS6", "CAX8R", "T3D2",
// "B31"), or false. A type is a family's prefix, its node count and letters (reduced integration,
// hybrid, incompatible modes, modified) that do not change its nodes.
bool elementKind(const std::string& upper, ElementKind& kind)
{
  struct Prefix
  {
    const char* text;
    Family family;
  };
  static const Prefix prefixes[] = { { "DC3D", Family::Solid }, { "C3D", Family::Solid }, { "CPEG", Family::Plane },
    { "CPS", Family::Plane }, { "CPE", Family::Plane }, { "CAX", Family::Plane }, { "DC2D", Family::Plane },
    { "DCAX", Family::Plane }, { "M3D", Family::Shell }, { "S", Family::Shell }, { "T3D", Family::Line },
    { "T2D", Family::Line }, { "B3", Family::Line }, { "B2", Family::Line } };
  for (const Prefix& prefix : prefixes)
  {
    const std::size_t length = std::strlen(prefix.text);
    if (upper.compare(0, length, prefix.text) != 0)
    {
      continue;
    }
    std::size_t end = length;
    const bool beam = prefix.text[0] == 'B';
    while (end < upper.size() && std::isdigit(static_cast<unsigned char>(upper[end])) && !(beam && end > length))
    {
      ++end;
    }
    if (end == length)
    {
      return false;
    }
    const int count = std::stoi(upper.substr(length, end - length));
    // what follows the count: letters, and for shells a thickness variant's digit (S4R5)
    for (std::size_t i = end; i < upper.size(); ++i)
    {
      if (!std::isalpha(static_cast<unsigned char>(upper[i])) && !(prefix.family == Family::Shell && i > end))
      {
        return false;
      }
    }
    kind.family = prefix.family;
    kind.order.clear();
    switch (prefix.family)
    {
      case Family::Solid:
        switch (count)
        {
          case 4: kind.type = CellType::Tetra; return true;
          case 10: kind.type = CellType::QuadraticTetra; return true;
          case 8: kind.type = CellType::Hexahedron; return true;
          case 20: kind.type = CellType::QuadraticHexahedron; return true;
          // Abaqus' wedge turns 1-2-3 counter-clockwise seen from 4-5-6, VTK's the other way
          case 6: kind.type = CellType::Wedge; kind.order = { 0, 2, 1, 3, 5, 4 }; return true;
          case 15:
            kind.type = CellType::QuadraticWedge;
            kind.order = { 0, 2, 1, 3, 5, 4, 8, 7, 6, 11, 10, 9, 12, 14, 13 };
            return true;
          default: return false;
        }
      case Family::Shell:
      case Family::Plane:
        switch (count)
        {
          case 3: kind.type = CellType::Triangle; return true;
          case 4: kind.type = CellType::Quad; return true;
          case 6: kind.type = CellType::QuadraticTriangle; return true;
          case 8: kind.type = CellType::QuadraticQuad; return true;
          default: return false;
        }
      case Family::Line:
        if (beam)
        {
          kind.type = count == 1 ? CellType::Line : CellType::QuadraticEdge;
          return count == 1 || count == 2;
        }
        kind.type = count == 2 ? CellType::Line : CellType::QuadraticEdge;
        return count == 2 || count == 3;
    }
  }
  return false;
}

// The corners of face label (upper case) of an element of kind, as the file numbers its nodes
// (0-based), or false when the element has no such face.
bool faceCorners(const ElementKind& kind, const std::string& label, std::vector<int>& corners)
{
  using Faces = std::vector<std::vector<int>>;
  static const Faces tetra = { { 0, 1, 2 }, { 0, 3, 1 }, { 1, 3, 2 }, { 2, 3, 0 } };
  static const Faces hexahedron = { { 0, 1, 2, 3 }, { 4, 7, 6, 5 }, { 0, 4, 5, 1 }, { 1, 5, 6, 2 }, { 2, 6, 7, 3 }, { 3, 7, 4, 0 } };
  static const Faces wedge = { { 0, 1, 2 }, { 3, 5, 4 }, { 0, 3, 4, 1 }, { 1, 4, 5, 2 }, { 2, 5, 3, 0 } };
  const int corners2D = kind.type == CellType::Triangle || kind.type == CellType::QuadraticTriangle ? 3 : 4;
  auto edge = [&](int k) { return std::vector<int>{ k % corners2D, (k + 1) % corners2D }; };
  if (label.empty() && kind.family != Family::Shell)
  {
    return false;
  }
  int number = 0;
  if (label.size() >= 2 && (label[0] == 'S' || label[0] == 'E') && std::isdigit(static_cast<unsigned char>(label[1])))
  {
    number = std::atoi(label.c_str() + 1);
  }
  switch (kind.family)
  {
    case Family::Solid:
    {
      const Faces& faces = kind.type == CellType::Tetra || kind.type == CellType::QuadraticTetra ? tetra
        : kind.type == CellType::Wedge || kind.type == CellType::QuadraticWedge                ? wedge
                                                                                                : hexahedron;
      if (label[0] != 'S' || number < 1 || number > static_cast<int>(faces.size()))
      {
        return false;
      }
      corners = faces[number - 1];
      return true;
    }
    case Family::Shell:
      // both sides (SPOS, SNEG; CalculiX's S1, S2), the edges (S3.., Abaqus' E1..)
      if (label.empty() || label == "SPOS" || label == "SNEG" || label == "POS" || label == "NEG" ||
        (label[0] == 'S' && (number == 1 || number == 2)))
      {
        corners.resize(corners2D);
        for (int k = 0; k < corners2D; ++k)
        {
          corners[k] = k;
        }
        return true;
      }
      if (label[0] == 'S' && number >= 3 && number < 3 + corners2D)
      {
        corners = edge(number - 3);
        return true;
      }
      if (label[0] == 'E' && number >= 1 && number <= corners2D)
      {
        corners = edge(number - 1);
        return true;
      }
      return false;
    case Family::Plane:
      if (label[0] != 'S' || number < 1 || number > corners2D)
      {
        return false;
      }
      corners = edge(number - 1);
      return true;
    case Family::Line: return false;
  }
  return false;
}

// The midside nodes of VTK's quadratic cells: node corners + i lies on the edge edges[i].
const std::vector<std::array<int, 2>>& midsideEdges(CellType type)
{
  static const std::vector<std::array<int, 2>> none, edge = { { { 0, 1 } } },
                                                     triangle = { { { 0, 1 } }, { { 1, 2 } }, { { 2, 0 } } },
                                                     quad = { { { 0, 1 } }, { { 1, 2 } }, { { 2, 3 } }, { { 3, 0 } } },
                                                     tetra = { { { 0, 1 } }, { { 1, 2 } }, { { 2, 0 } }, { { 0, 3 } }, { { 1, 3 } },
                                                       { { 2, 3 } } },
                                                     hexahedron = { { { 0, 1 } }, { { 1, 2 } }, { { 2, 3 } }, { { 3, 0 } }, { { 4, 5 } },
                                                       { { 5, 6 } }, { { 6, 7 } }, { { 7, 4 } }, { { 0, 4 } }, { { 1, 5 } },
                                                       { { 2, 6 } }, { { 3, 7 } } },
                                                     wedge = { { { 0, 1 } }, { { 1, 2 } }, { { 2, 0 } }, { { 3, 4 } }, { { 4, 5 } },
                                                       { { 5, 3 } }, { { 0, 3 } }, { { 1, 4 } }, { { 2, 5 } } };
  switch (type)
  {
    case CellType::QuadraticEdge: return edge;
    case CellType::QuadraticTriangle: return triangle;
    case CellType::QuadraticQuad: return quad;
    case CellType::QuadraticTetra: return tetra;
    case CellType::QuadraticHexahedron: return hexahedron;
    case CellType::QuadraticWedge: return wedge;
    default: return none;
  }
}

// ---- lines, keywords and fields ----------------------------------------------------------------

std::string upperCase(std::string_view text)
{
  std::string out(text);
  for (char& c : out)
  {
    c = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  }
  return out;
}

// A data line's fields (between commas, blanks trimmed), as views into the file's text.
void splitFields(std::string_view line, std::vector<std::string_view>& fields)
{
  fields.clear();
  std::size_t begin = 0;
  while (true)
  {
    const std::size_t comma = line.find(',', begin);
    fields.push_back(trim(line.substr(begin, comma == std::string_view::npos ? std::string_view::npos : comma - begin)));
    if (comma == std::string_view::npos)
    {
      break;
    }
    begin = comma + 1;
  }
  // a trailing comma (which Gmsh writes after sets) ends the line without a field
  if (fields.size() > 1 && fields.back().empty())
  {
    fields.pop_back();
  }
}

// A keyword line: its keyword (upper case, without "*") and its parameters (keys upper case); the
// analysis keeps those the mesh does not need, with their data lines and where they stand.
using Keyword = DeckKeyword;

Keyword parseKeyword(std::string_view text)
{
  Keyword keyword;
  std::vector<std::string_view> fields;
  splitFields(text.substr(1), fields);
  keyword.name = upperCase(fields[0]);
  for (std::size_t i = 1; i < fields.size(); ++i)
  {
    const std::size_t equals = fields[i].find('=');
    if (fields[i].empty())
    {
      continue;
    }
    const std::string key = upperCase(trim(fields[i].substr(0, equals)));
    keyword.parameters[key] = equals == std::string_view::npos ? std::string() : std::string(trim(fields[i].substr(equals + 1)));
  }
  return keyword;
}

// One item of a set as the deck lists it: an id, a GENERATE range, another set, or the nodes of an
// element set or an element's face (*NSET, ELSET= and *SURFACE).
struct SetItem
{
  enum Kind
  {
    Id,
    Range,
    Set,
    ElementNodes,
    FaceNodes
  } kind;
  std::int64_t first = 0, last = 0, step = 1;
  std::string name;  // Set, ElementNodes, FaceNodes: an element set (or "" with first: one element)
  std::string label; // FaceNodes: the face's label
  std::uint32_t file = 0;
  std::size_t line = 0;
};

struct SetDefinition
{
  std::string name; // as first written
  std::vector<SetItem> items;
};

// The sets of one kind, by upper-case name, in the order of their first definition.
struct SetTable
{
  std::vector<SetDefinition> sets;
  std::map<std::string, std::size_t> byName;
  SetDefinition& get(const std::string& name)
  {
    const auto [found, added] = this->byName.emplace(upperCase(name), this->sets.size());
    if (added)
    {
      this->sets.push_back({ name, {} });
    }
    return this->sets[found->second];
  }
};

// ---- the reader --------------------------------------------------------------------------------

class Reader
{
public:
  Reader(const std::string& path, bool layoutOnly)
    : LayoutOnly(layoutOnly)
    , Folder(fs::path(path).parent_path())
  {
    this->read(path, "", 0);
    this->finishElement();
    this->Out.mesh.nodeIds.shrink_to_fit();
    if (!layoutOnly)
    {
      this->resolve();
    }
  }

  Deck Out;

private:
  enum class Section
  {
    None,
    Node,
    Element,
    NodeSet,
    ElementSet,
    Surface,
    Skip
  };

  bool LayoutOnly;
  fs::path Folder;
  Section Current = Section::None;
  bool Analysis = false; // the data lines go to the last of Out.analysis
  std::uint32_t File = 0;
  std::size_t Line = 0;
  std::vector<std::string_view> Fields;

  // the section's state
  std::string NodeSetName;       // *NODE, NSET=
  SetDefinition* Set = nullptr;  // *NSET, *ELSET, *SURFACE
  bool Generate = false;
  bool NodeSurface = false;      // *SURFACE, TYPE=NODE
  std::size_t Block = 0;         // *ELEMENT: the block in Deck.mesh.blocks
  std::string BlockSetName;      // *ELEMENT, ELSET=
  std::vector<std::int64_t> Pending; // an element's id and the nodes read so far
  std::size_t PendingLine = 0;

  std::vector<ElementKind> Kinds;                  // a block's
  std::vector<std::vector<std::uint64_t>> Where;    // each element's file (high 24 bits) and line
  SetTable NodeSets, ElementSets, Surfaces;

  [[noreturn]] void fail(const std::string& reason) const
  {
    throw FileError(this->Out.files[this->File], this->Line, reason);
  }

  void read(const std::string& path, const std::string& includeName, int depth)
  {
    if (depth > 20)
    {
      this->fail("*INCLUDE nested more than 20 deep (does a file include itself?)");
    }
    const std::string text = readFile(path);
    const std::uint32_t file = static_cast<std::uint32_t>(this->Out.files.size());
    this->Out.files.push_back(path);
    this->Out.hashes.push_back(contentHash(text));
    this->Out.includeNames.push_back(includeName);
    const std::uint32_t includingFile = this->File;
    const std::size_t includingLine = this->Line;
    this->File = file;
    this->Line = 0;
    std::size_t begin = 0;
    while (begin < text.size())
    {
      std::size_t end = text.find('\n', begin);
      const std::size_t next = end == std::string::npos ? text.size() : end + 1;
      end = end == std::string::npos ? text.size() : end;
      if (end > begin && text[end - 1] == '\r')
      {
        --end;
      }
      ++this->Line;
      std::string_view line(text.data() + begin, end - begin);
      if (line.size() >= 2 && line[0] == '*' && line[1] == '*')
      {
        // a comment
      }
      else if (!line.empty() && line[0] == '*')
      {
        // a keyword line, continued while it ends in a comma
        std::string keyword(line);
        const std::size_t keywordLine = this->Line;
        begin = next;
        while (!trim(keyword).empty() && trim(keyword).back() == ',' && begin < text.size())
        {
          std::size_t more = text.find('\n', begin);
          more = more == std::string::npos ? text.size() : more;
          std::string_view continued(text.data() + begin, more - begin);
          if (!continued.empty() && continued.back() == '\r')
          {
            continued.remove_suffix(1);
          }
          if (!continued.empty() && continued[0] == '*')
          {
            break;
          }
          keyword += continued;
          ++this->Line;
          begin = std::min(more + 1, text.size());
        }
        const std::size_t lastLine = this->Line;
        this->Line = keywordLine;
        this->keyword(parseKeyword(keyword), depth);
        this->File = file;
        this->Line = lastLine;
        continue;
      }
      else if (!trim(line).empty())
      {
        this->data(line, begin);
      }
      begin = next;
    }
    this->File = includingFile;
    this->Line = includingLine;
  }

  void keyword(const Keyword& keyword, int depth)
  {
    // *INCLUDE inserts a file where it stands: its data lines continue the keyword before it
    if (keyword.name == "INCLUDE")
    {
      const std::string name = keyword.get("INPUT");
      if (name.empty())
      {
        this->fail("*INCLUDE without INPUT=");
      }
      const fs::path included = fs::path(name).is_absolute() ? fs::path(name) : this->Folder / name;
      if (!fs::exists(included))
      {
        this->fail("*INCLUDE, INPUT=" + name + ": " + included.string() + " does not exist");
      }
      this->read(included.string(), name, depth + 1);
      return;
    }
    this->finishElement();
    this->Current = Section::Skip;
    this->Analysis = false;
    if (keyword.name == "NODE" && !keyword.has("PRINT") && !keyword.has("FILE") && !keyword.has("OUTPUT"))
    {
      this->refuseInput(keyword);
      const std::string system = upperCase(keyword.get("SYSTEM"));
      if (!system.empty() && system != "R")
      {
        this->fail("*NODE, SYSTEM=" + system + ": coordinates in a cylindrical or spherical system are not supported");
      }
      this->Current = Section::Node;
      this->NodeSetName = keyword.get("NSET");
    }
    else if (keyword.name == "ELEMENT" && !keyword.has("OUTPUT"))
    {
      this->refuseInput(keyword);
      this->startElements(keyword);
    }
    else if ((keyword.name == "NSET" || keyword.name == "ELSET") && !this->LayoutOnly)
    {
      this->refuseInput(keyword);
      const bool nodes = keyword.name == "NSET";
      const std::string name = keyword.get(nodes ? "NSET" : "ELSET");
      if (name.empty())
      {
        this->fail("*" + keyword.name + " without " + keyword.name + "=");
      }
      this->Set = &(nodes ? this->NodeSets : this->ElementSets).get(name);
      this->Generate = keyword.has("GENERATE");
      this->Current = nodes ? Section::NodeSet : Section::ElementSet;
      if (nodes && keyword.has("ELSET"))
      {
        // the nodes of an element set
        this->Set->items.push_back(this->item(SetItem::ElementNodes, keyword.get("ELSET")));
        this->Current = Section::Skip;
      }
    }
    else if (keyword.name == "SURFACE" && !this->LayoutOnly)
    {
      this->refuseInput(keyword);
      const std::string name = keyword.get("NAME");
      if (name.empty())
      {
        this->fail("*SURFACE without NAME=");
      }
      const std::string type = upperCase(keyword.get("TYPE"));
      if (!type.empty() && type != "ELEMENT" && type != "NODE")
      {
        this->Out.mesh.warnings.push_back(this->where() + ": *SURFACE, TYPE=" + type + " is not read (only ELEMENT and NODE)");
        return;
      }
      this->Set = &this->Surfaces.get(name);
      this->NodeSurface = type == "NODE";
      this->Current = Section::Surface;
    }
    else if (keyword.name == "PART" || keyword.name == "INSTANCE" || keyword.name == "ASSEMBLY")
    {
      this->fail("*" + keyword.name + ": decks of parts and instances are not supported; write the deck flat (Abaqus/CAE: "
                                      "Model > Edit Attributes > \"Do not use parts and assemblies in input files\")");
    }
    else if (keyword.name == "SYSTEM")
    {
      this->fail("*SYSTEM: nodes in a transformed system are not supported (their coordinates are not the *NODE lines')");
    }
    else if (keyword.name == "NGEN" || keyword.name == "NFILL" || keyword.name == "NCOPY" || keyword.name == "NMAP" ||
      keyword.name == "ELGEN" || keyword.name == "ELCOPY")
    {
      this->fail("*" + keyword.name + ": generated nodes and elements are not supported (list them with *NODE and *ELEMENT)");
    }
    else if (!this->LayoutOnly && keyword.name != "NSET" && keyword.name != "ELSET" && keyword.name != "SURFACE" &&
      keyword.name != "ELEMENT" && keyword.name != "NODE" && keyword.name != "HEADING")
    {
      // kept for the analysis (Abaqus/CalculixAnalysis.h): a material, a section, a step's loads
      this->Out.analysis.push_back(keyword);
      this->Out.analysis.back().where = this->where();
      this->Analysis = true;
    }
  }

  void refuseInput(const Keyword& keyword) const
  {
    if (keyword.has("INPUT"))
    {
      this->fail("*" + keyword.name + ", INPUT=: data read from another file is not supported (use *INCLUDE)");
    }
  }

  std::string where() const { return this->Out.files[this->File] + ":" + std::to_string(this->Line); }

  SetItem item(SetItem::Kind kind, const std::string& name) const
  {
    SetItem item{ kind };
    item.name = name;
    item.file = this->File;
    item.line = this->Line;
    return item;
  }

  void startElements(const Keyword& keyword)
  {
    const std::string type = upperCase(keyword.get("TYPE"));
    ElementKind kind;
    if (type.empty())
    {
      this->fail("*ELEMENT without TYPE=");
    }
    if (!elementKind(type, kind))
    {
      this->Out.mesh.warnings.push_back(this->where() + ": element type " + type +
        " is not supported: its elements are left out (their nodes are read and move with the rest)");
      return;
    }
    if (this->LayoutOnly)
    {
      return;
    }
    this->Current = Section::Element;
    this->Block = this->Out.mesh.blocks.size();
    this->Out.mesh.blocks.push_back({ type, kind.type, {}, {} });
    this->Kinds.push_back(kind);
    this->Where.emplace_back();
    this->BlockSetName = keyword.get("ELSET");
  }

  void data(std::string_view line, std::size_t offset)
  {
    switch (this->Current)
    {
      case Section::Node: this->node(line, offset); break;
      case Section::Element: this->element(line); break;
      case Section::NodeSet:
      case Section::ElementSet: this->setLine(line); break;
      case Section::Surface: this->surfaceLine(line); break;
      case Section::None:
      case Section::Skip:
        if (this->Analysis)
        {
          this->Out.analysis.back().lines.emplace_back(trim(line));
        }
        break;
    }
  }

  std::int64_t id(std::string_view field, const char* what) const
  {
    std::int64_t value = 0;
    if (!parseInteger(field.data(), field.data() + field.size(), value))
    {
      this->fail("\"" + std::string(field) + "\" is not " + what);
    }
    if (value <= 0)
    {
      this->fail(std::string(what) + " " + std::to_string(value) + " is not positive");
    }
    return value;
  }

  void node(std::string_view line, std::size_t offset)
  {
    splitFields(line, this->Fields);
    const std::int64_t id = this->id(this->Fields[0], "a node id");
    const std::size_t count = std::min<std::size_t>(this->Fields.size() - 1, 3);
    if (count == 0)
    {
      this->fail("node " + std::to_string(id) + " has no coordinates");
    }
    Mesh().nodeIds.push_back(id);
    const std::string_view first = this->Fields[1], last = this->Fields[count];
    // the slot: from the first coordinate's start (the position after the comma when it is blank)
    // to the last one's end
    const std::size_t begin = first.data() - line.data(), end = last.data() + last.size() - line.data();
    this->Out.slots.push_back({ this->File, static_cast<std::uint32_t>(count), offset + begin, offset + end });
    for (std::size_t c = 0; c < 3; ++c)
    {
      double value = 0;
      if (c < count && !this->Fields[1 + c].empty() &&
        !parseReal(this->Fields[1 + c].data(), this->Fields[1 + c].data() + this->Fields[1 + c].size(), value))
      {
        this->fail("node " + std::to_string(id) + "'s coordinate \"" + std::string(this->Fields[1 + c]) +
          "\" is not a finite number");
      }
      Mesh().xyz.push_back(value);
    }
    if (!this->NodeSetName.empty() && !this->LayoutOnly)
    {
      SetItem item = this->item(SetItem::Id, "");
      item.first = id;
      this->NodeSets.get(this->NodeSetName).items.push_back(item);
    }
  }

  SourceMesh& Mesh() { return this->Out.mesh; }

  void element(std::string_view line)
  {
    splitFields(line, this->Fields);
    ElementBlock& block = Mesh().blocks[this->Block];
    const std::size_t wanted = 1 + nodesPerCell(block.type);
    if (this->Pending.empty())
    {
      this->PendingLine = this->Line;
    }
    for (const std::string_view field : this->Fields)
    {
      if (field.empty())
      {
        this->fail("an empty field in element " + (this->Pending.empty() ? std::string("data") : std::to_string(this->Pending[0])));
      }
      if (this->Pending.size() == wanted)
      {
        this->fail("element " + std::to_string(this->Pending[0]) + " has more than the " + std::to_string(wanted - 1) + " nodes of a " +
          block.name);
      }
      this->Pending.push_back(this->id(field, this->Pending.empty() ? "an element id" : "a node id"));
    }
    if (this->Pending.size() == wanted)
    {
      this->finishElement();
    }
  }

  // Stores the element read (or fails when its nodes are incomplete).
  void finishElement()
  {
    if (this->Pending.empty())
    {
      return;
    }
    ElementBlock& block = Mesh().blocks[this->Block];
    const std::size_t nodes = nodesPerCell(block.type);
    if (this->Pending.size() != 1 + nodes)
    {
      this->Line = this->PendingLine;
      this->fail("element " + std::to_string(this->Pending[0]) + " has " + std::to_string(this->Pending.size() - 1) + " nodes; a " +
        block.name + " has " + std::to_string(nodes));
    }
    block.ids.push_back(this->Pending[0]);
    const std::vector<int>& order = this->Kinds[this->Block].order;
    for (std::size_t i = 0; i < nodes; ++i)
    {
      block.nodes.push_back(this->Pending[1 + (order.empty() ? i : order[i])]);
    }
    this->Where[this->Block].push_back(static_cast<std::uint64_t>(this->File) << 40 | this->PendingLine);
    if (!this->BlockSetName.empty())
    {
      SetItem item = this->item(SetItem::Id, "");
      item.first = this->Pending[0];
      item.line = this->PendingLine;
      this->ElementSets.get(this->BlockSetName).items.push_back(item);
    }
    this->Pending.clear();
  }

  void setLine(std::string_view line)
  {
    splitFields(line, this->Fields);
    if (this->Generate)
    {
      if (this->Fields.size() < 2 || this->Fields.size() > 3)
      {
        this->fail("a GENERATE line is \"first, last[, increment]\"");
      }
      SetItem item = this->item(SetItem::Range, "");
      item.first = this->id(this->Fields[0], "an id");
      item.last = this->id(this->Fields[1], "an id");
      item.step = this->Fields.size() == 3 ? this->id(this->Fields[2], "an increment") : 1;
      if (item.last < item.first)
      {
        this->fail("GENERATE from " + std::to_string(item.first) + " down to " + std::to_string(item.last));
      }
      this->Set->items.push_back(item);
      return;
    }
    for (const std::string_view field : this->Fields)
    {
      if (field.empty())
      {
        continue;
      }
      SetItem item = this->item(SetItem::Id, "");
      if (!parseInteger(field.data(), field.data() + field.size(), item.first))
      {
        item.kind = SetItem::Set;
        item.name = std::string(field);
      }
      else if (item.first <= 0)
      {
        this->fail("id " + std::string(field) + " is not positive");
      }
      this->Set->items.push_back(item);
    }
  }

  void surfaceLine(std::string_view line)
  {
    splitFields(line, this->Fields);
    const std::string_view target = this->Fields[0];
    if (target.empty())
    {
      this->fail("a *SURFACE line without an element, element set, node or node set");
    }
    SetItem item = this->item(this->NodeSurface ? SetItem::Id : SetItem::FaceNodes, "");
    const bool number = parseInteger(target.data(), target.data() + target.size(), item.first);
    if (number && item.first <= 0)
    {
      this->fail("id " + std::string(target) + " is not positive");
    }
    if (!number)
    {
      item.name = std::string(target);
      item.first = 0;
      if (this->NodeSurface)
      {
        item.kind = SetItem::Set;
      }
    }
    if (!this->NodeSurface)
    {
      item.label = this->Fields.size() > 1 ? upperCase(this->Fields[1]) : std::string();
    }
    this->Set->items.push_back(item);
  }

  // ---- sets, resolved once every node and element is read --------------------------------------

  struct Located
  {
    std::size_t block, index;
  };

  void resolve()
  {
    SourceMesh& mesh = Mesh();
    const IdIndex nodes(mesh.nodeIds);
    if (nodes.duplicate != IdIndex::none)
    {
      const NodeSlot& slot = this->Out.slots[nodes.duplicate];
      throw FileError(this->Out.files[slot.file], this->lineOf(slot), "node " + std::to_string(mesh.nodeIds[nodes.duplicate]) +
          " is defined twice");
    }
    // every element's nodes exist
    std::vector<std::int64_t> elementIds;
    std::vector<Located> located;
    for (std::size_t b = 0; b < mesh.blocks.size(); ++b)
    {
      const ElementBlock& block = mesh.blocks[b];
      const std::size_t perCell = nodesPerCell(block.type);
      for (std::size_t e = 0; e < block.ids.size(); ++e)
      {
        for (std::size_t k = 0; k < perCell; ++k)
        {
          if (nodes.find(block.nodes[e * perCell + k]) == IdIndex::none)
          {
            this->failAt(this->Where[b][e], "element " + std::to_string(block.ids[e]) + " refers to node " +
                std::to_string(block.nodes[e * perCell + k]) + ", which the deck does not define");
          }
        }
        elementIds.push_back(block.ids[e]);
        located.push_back({ b, e });
      }
    }
    const IdIndex elements(elementIds);
    if (elements.duplicate != IdIndex::none)
    {
      const Located at = located[elements.duplicate];
      this->failAt(this->Where[at.block][at.index], "element " + std::to_string(elementIds[elements.duplicate]) + " is defined twice");
    }
    Resolver resolver{ *this, nodes, elements, located };
    for (std::size_t s = 0; s < this->ElementSets.sets.size(); ++s)
    {
      mesh.elementSets.push_back({ this->ElementSets.sets[s].name, resolver.elementSet(s) });
    }
    for (std::size_t s = 0; s < this->NodeSets.sets.size(); ++s)
    {
      mesh.nodeSets.push_back({ this->NodeSets.sets[s].name, resolver.nodeSet(s) });
    }
    for (const SetDefinition& surface : this->Surfaces.sets)
    {
      // a surface's array is named after it, unless a node set has that name
      const bool taken = this->NodeSets.byName.count(upperCase(surface.name)) != 0;
      mesh.nodeSets.push_back({ taken ? surface.name + " (surface)" : surface.name, resolver.items(surface.items, true) });
    }
  }

  std::size_t lineOf(const NodeSlot& slot) const
  {
    const std::string text = readFile(this->Out.files[slot.file]);
    return 1 + static_cast<std::size_t>(std::count(text.begin(), text.begin() + slot.begin, '\n'));
  }

  [[noreturn]] void failAt(std::uint64_t where, const std::string& reason) const
  {
    throw FileError(this->Out.files[where >> 40], where & ((std::uint64_t(1) << 40) - 1), reason);
  }

  struct Resolver
  {
    Reader& reader;
    const IdIndex& nodes;
    const IdIndex& elements;
    const std::vector<Located>& located;
    std::vector<std::vector<std::int64_t>> nodeSets = std::vector<std::vector<std::int64_t>>(reader.NodeSets.sets.size());
    std::vector<std::vector<std::int64_t>> elementSets = std::vector<std::vector<std::int64_t>>(reader.ElementSets.sets.size());
    std::vector<char> nodeState = std::vector<char>(reader.NodeSets.sets.size(), 0); // 1 resolving, 2 resolved
    std::vector<char> elementState = std::vector<char>(reader.ElementSets.sets.size(), 0);

    const std::vector<std::int64_t>& nodeSet(std::size_t s)
    {
      return this->resolveSet(s, true);
    }
    const std::vector<std::int64_t>& elementSet(std::size_t s)
    {
      return this->resolveSet(s, false);
    }

    const std::vector<std::int64_t>& resolveSet(std::size_t s, bool ofNodes)
    {
      std::vector<char>& state = ofNodes ? this->nodeState : this->elementState;
      std::vector<std::vector<std::int64_t>>& resolved = ofNodes ? this->nodeSets : this->elementSets;
      const SetDefinition& set = (ofNodes ? this->reader.NodeSets : this->reader.ElementSets).sets[s];
      if (state[s] == 1)
      {
        this->fail(set.items.empty() ? SetItem{} : set.items[0], "set " + set.name + " contains itself");
      }
      if (state[s] == 0)
      {
        state[s] = 1;
        resolved[s] = this->items(set.items, ofNodes);
        state[s] = 2;
      }
      return resolved[s];
    }

    [[noreturn]] void fail(const SetItem& item, const std::string& reason) const
    {
      throw FileError(this->reader.Out.files[item.file], item.line, reason);
    }

    void warn(const SetItem& item, const std::string& text) const
    {
      this->reader.Out.mesh.warnings.push_back(this->reader.Out.files[item.file] + ":" + std::to_string(item.line) + ": " + text);
    }

    // The ids of items, in order, without repeats; ofNodes: node ids (else element ids).
    std::vector<std::int64_t> items(const std::vector<SetItem>& items, bool ofNodes)
    {
      const IdIndex& index = ofNodes ? this->nodes : this->elements;
      const char* what = ofNodes ? "node" : "element";
      std::vector<std::int64_t> out;
      std::vector<char> taken;
      auto add = [&](std::int64_t id) {
        const std::size_t at = index.find(id);
        if (at == IdIndex::none)
        {
          return false;
        }
        taken.resize(std::max(taken.size(), ofNodes ? this->reader.Out.mesh.nodeIds.size() : this->located.size()), 0);
        if (!taken[at])
        {
          taken[at] = 1;
          out.push_back(id);
        }
        return true;
      };
      for (const SetItem& item : items)
      {
        switch (item.kind)
        {
          case SetItem::Id:
            if (!add(item.first))
            {
              this->warn(item, std::string(what) + " " + std::to_string(item.first) + " is not in the deck: left out of the set");
            }
            break;
          case SetItem::Range:
          {
            // the ids in the range that exist (a range may be far wider than the mesh)
            const std::uint64_t span = static_cast<std::uint64_t>(item.last - item.first) / static_cast<std::uint64_t>(item.step) + 1;
            std::size_t missing = 0;
            if (span <= 4 * (ofNodes ? this->reader.Out.mesh.nodeIds.size() : this->located.size()) + 1024)
            {
              for (std::int64_t id = item.first; id <= item.last; id += item.step)
              {
                missing += add(id) ? 0 : 1;
                if (item.last - id < item.step)
                {
                  break;
                }
              }
            }
            else
            {
              const std::vector<std::int64_t> all = ofNodes ? this->reader.Out.mesh.nodeIds : this->allElementIds();
              std::vector<std::int64_t> inRange;
              for (const std::int64_t id : all)
              {
                if (id >= item.first && id <= item.last && (id - item.first) % item.step == 0)
                {
                  inRange.push_back(id);
                }
              }
              std::sort(inRange.begin(), inRange.end());
              for (const std::int64_t id : inRange)
              {
                add(id);
              }
              missing = static_cast<std::size_t>(span - inRange.size());
            }
            if (missing > 0)
            {
              this->warn(item, "GENERATE " + std::to_string(item.first) + " to " + std::to_string(item.last) + ": " +
                  std::to_string(missing) + " " + what + " ids are not in the deck");
            }
            break;
          }
          case SetItem::Set:
          {
            const SetTable& table = ofNodes ? this->reader.NodeSets : this->reader.ElementSets;
            const auto found = table.byName.find(upperCase(item.name));
            if (found == table.byName.end())
            {
              this->fail(item, "no " + std::string(ofNodes ? "node" : "element") + " set is named " + item.name);
            }
            for (const std::int64_t id : this->resolveSet(found->second, ofNodes))
            {
              add(id);
            }
            break;
          }
          case SetItem::ElementNodes:
          case SetItem::FaceNodes:
            for (const std::int64_t element : this->elementsOf(item))
            {
              for (const std::int64_t node : this->nodesOf(item, element))
              {
                add(node);
              }
            }
            break;
        }
      }
      return out;
    }

    std::vector<std::int64_t> allElementIds() const
    {
      std::vector<std::int64_t> ids;
      for (const ElementBlock& block : this->reader.Out.mesh.blocks)
      {
        ids.insert(ids.end(), block.ids.begin(), block.ids.end());
      }
      return ids;
    }

    // The elements an ElementNodes or FaceNodes item names: one by its id, or an element set.
    std::vector<std::int64_t> elementsOf(const SetItem& item)
    {
      if (item.name.empty())
      {
        if (this->elements.find(item.first) == IdIndex::none)
        {
          this->fail(item, "element " + std::to_string(item.first) + " is not in the deck");
        }
        return { item.first };
      }
      const auto found = this->reader.ElementSets.byName.find(upperCase(item.name));
      if (found == this->reader.ElementSets.byName.end())
      {
        this->fail(item, "no element set is named " + item.name);
      }
      return this->resolveSet(found->second, false);
    }

    // The nodes of an element, or of its face item.label (with the midside nodes on its edges).
    std::vector<std::int64_t> nodesOf(const SetItem& item, std::int64_t element)
    {
      const Located at = this->located[this->elements.find(element)];
      const ElementBlock& block = this->reader.Out.mesh.blocks[at.block];
      const int perCell = nodesPerCell(block.type);
      const std::int64_t* nodes = block.nodes.data() + at.index * perCell;
      if (item.kind == SetItem::ElementNodes)
      {
        return std::vector<std::int64_t>(nodes, nodes + perCell);
      }
      const ElementKind& kind = this->reader.Kinds[at.block];
      std::vector<int> corners;
      if (!faceCorners(kind, item.label, corners))
      {
        this->fail(item, "a " + block.name + " has no face " + (item.label.empty() ? std::string("(none given)") : item.label));
      }
      // the file's node numbers to VTK's (the orders are their own inverses)
      std::vector<char> inFace(perCell, 0);
      for (int& corner : corners)
      {
        corner = kind.order.empty() ? corner : kind.order[corner];
        inFace[corner] = 1;
      }
      const auto& edges = midsideEdges(block.type);
      const int firstMidside = perCell - static_cast<int>(edges.size());
      std::vector<std::int64_t> out;
      for (const int corner : corners)
      {
        out.push_back(nodes[corner]);
      }
      for (std::size_t e = 0; e < edges.size(); ++e)
      {
        if (inFace[edges[e][0]] && inFace[edges[e][1]])
        {
          out.push_back(nodes[firstMidside + e]);
        }
      }
      return out;
    }
  };
};
} // namespace

std::string DeckKeyword::get(const std::string& key) const
{
  const auto found = this->parameters.find(key);
  return found == this->parameters.end() ? std::string() : found->second;
}

bool DeckKeyword::has(const std::string& key) const
{
  return this->parameters.count(key) != 0;
}

Deck readDeck(const std::string& path)
{
  return std::move(Reader(path, false).Out);
}

Deck readNodeLayout(const std::string& path)
{
  return std::move(Reader(path, true).Out);
}

// ---- the variant -------------------------------------------------------------------------------

namespace
{
// Appends the slot's text with the coordinates xyz: each number whose value changed (from old, its
// value as read; a blank field's is 0) is replaced by the shortest text of the new one; blanks,
// separators and unchanged numbers stay as they were.
// CalculiX reads a number in 20 characters and silently cuts a longer one ("1.2345678901234567e-05"
// becomes 1.2345678901234567e-0): a changed coordinate's text fits them.
constexpr std::size_t NumberWidth = 20;

void appendSlot(std::string& out, std::string_view slot, std::uint32_t count, const double* xyz, const double* old)
{
  std::size_t begin = 0;
  for (std::uint32_t c = 0; c < count; ++c)
  {
    std::size_t end = c + 1 < count ? slot.find(',', begin) : slot.size();
    end = end == std::string_view::npos ? slot.size() : end;
    const std::string_view field = slot.substr(begin, end - begin);
    const std::string_view number = trim(field);
    if (old[c] == xyz[c])
    {
      out.append(field);
    }
    else
    {
      const std::size_t lead = number.empty() ? field.size() : static_cast<std::size_t>(number.data() - field.data());
      out.append(field.substr(0, lead));
      appendShortest(out, xyz[c], NumberWidth);
      out.append(field.substr(lead + number.size()));
    }
    if (c + 1 < count)
    {
      out.push_back(',');
    }
    begin = end + 1;
  }
}

// Appends to out the text of file f with each of its nodes' coordinates replaced by xyz (row: where
// node k's are; old: the coordinates as read).
void writeWithCoordinates(AtomicWrite::Aside& out, SourceBytes& file, const std::vector<NodeSlot>& slots, std::uint32_t f,
  const std::vector<std::size_t>& row, const double* xyz, const double* old)
{
  std::vector<std::size_t> mine; // the nodes in file f, in file order
  for (std::size_t k = 0; k < slots.size(); ++k)
  {
    if (slots[k].file == f)
    {
      mine.push_back(k);
    }
  }
  rewriteInPieces(
    out, file, mine.size(), mine.empty() ? 0 : slots[mine.back()].end, [&](std::size_t i) { return slots[mine[i]].begin; },
    [&](std::string& piece, std::string_view text, std::size_t at, std::size_t i) {
      const NodeSlot& s = slots[mine[i]];
      appendSlot(piece, text.substr(at, s.end - s.begin), s.count, xyz + 3 * row[mine[i]], old + 3 * mine[i]);
      return at + (s.end - s.begin);
    });
}

} // namespace

void Deck::writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
  bool overwrite) const
{
  const Deck& deck = *this;
  const std::vector<std::int64_t>& nodeIds = deck.mesh.nodeIds;
  const std::string& source = deck.files.at(0);
  const std::vector<std::size_t> row = variantRows(target, source, nodeIds, ids, xyz, count);
  // each file's destination: the deck at target, a relative include beside it under its name
  std::vector<char> hasNodes(deck.files.size(), 0);
  for (const NodeSlot& slot : deck.slots)
  {
    hasNodes[slot.file] = 1;
  }
  const std::vector<std::string> destinations = variantDestinations(target, deck.files, deck.includeNames, hasNodes);
  AtomicWrite write(overwrite);
  for (std::size_t f = 0; f < deck.files.size(); ++f)
  {
    if (destinations[f].empty())
    {
      continue;
    }
    SourceBytes file(deck.files[f], deck.hashes[f], "deck");
    AtomicWrite::Aside out = write.open(destinations[f]);
    writeWithCoordinates(out, file, deck.slots, f, row, xyz, deck.mesh.xyz.data());
    write.close(out);
  }
  write.commit();
}
} // namespace abaqus
} // namespace mlsformats
