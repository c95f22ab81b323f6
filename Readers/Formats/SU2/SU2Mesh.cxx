#include "SU2/SU2Mesh.h"

#include "Common/Pieces.h"
#include "Common/TextCursor.h"
#include "Common/TextFile.h"
#include "Common/VariantNodes.h"

#include <algorithm>
#include <functional>
#include <map>
#include <numeric>
#include <set>
#include <string_view>

namespace mlsformats
{
namespace su2
{
namespace
{
struct ElementKind
{
  const char* name;
  CellType type; // its number is SU2's
};

// SU2's element types (its documentation's "Mesh File"): VTK's numbers, and VTK's node orders,
// which it refers to. Read as they are, the prism too: Gmsh's own prism turns 0-1-2 the other way
// (GmshMesh.cxx turns it), but the prisms of the .su2 files Gmsh 4.8 writes, and those of SU2's
// CPrism (its faces 0-1-2 and 5-4-3 turn outwards), turn 0-1-2 away from 3-4-5 as VTK's wedge;
// vtkCellValidator (VTK 9.2) finds Gmsh's extruded prisms valid as they are, and invalid turned.
const ElementKind* elementKind(std::int64_t number)
{
  static const ElementKind kinds[] = { { "line", CellType::Line }, { "triangle", CellType::Triangle },
    { "quadrilateral", CellType::Quad }, { "tetrahedron", CellType::Tetra }, { "hexahedron", CellType::Hexahedron },
    { "prism", CellType::Wedge }, { "pyramid", CellType::Pyramid } };
  for (const ElementKind& kind : kinds)
  {
    if (static_cast<std::int64_t>(kind.type) == number)
    {
      return &kind;
    }
  }
  return nullptr;
}

// The keyword of a line "NAME= value" (NAME of capitals, digits and '_'), and its value trimmed;
// "" when the line is not a keyword's.
std::string_view keyword(std::string_view line, std::string_view& value)
{
  const std::size_t equals = line.find('=');
  if (equals == 0 || equals == std::string_view::npos)
  {
    return {};
  }
  for (std::size_t i = 0; i < equals; ++i)
  {
    const char c = line[i];
    if (!((c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '_'))
    {
      return {};
    }
  }
  value = trim(line.substr(equals + 1));
  return line.substr(0, equals);
}

// A line quoted in a message: its first 40 characters.
std::string quoted(std::string_view text)
{
  return "\"" + std::string(text.substr(0, 40)) + (text.size() > 40 ? "...\"" : "\"");
}

// The zone being read.
struct ZoneRead
{
  int number = 1;
  std::size_t start = 0; // where its IZONE= is
  int dimension = 0;     // 0: before NDIME=
  bool points = false, elements = false;
  std::uint64_t pointCount = 0, elementCount = 0;
  std::size_t firstNode = 0, firstElement = 0;
  std::int64_t markers = -1; // NMARK=, -1 before it
  std::int64_t markersRead = 0;
  std::size_t markersAt = 0;
  std::string tag; // a MARKER_TAG= waiting for its MARKER_ELEMS=
  std::size_t tagAt = 0;
  // the highest point an element refers to, and where it first does: the points may come after
  std::int64_t highest = -1;
  std::size_t highestAt = 0;
  std::vector<std::int64_t> cells; // in a file of several zones
};

struct Marker
{
  int zone;
  std::string tag;
  std::vector<std::int64_t> nodes; // with repeats
};

// The elements of a type that SU2 does not have, in one section: told once, at the first.
struct Unknown
{
  std::string section;
  std::int64_t type;
  std::size_t at;
  std::size_t count;
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
    bool skipping = false; // the lines after a keyword that is not the mesh's
    std::string_view line;
    while (this->nextLine(line))
    {
      const std::string_view content = trim(line);
      if (content.empty() || content[0] == '%')
      {
        continue;
      }
      std::string_view value;
      const std::string_view key = keyword(content, value);
      if (key.empty())
      {
        if (!skipping)
        {
          this->fail(quoted(content) + " is outside any section (are there more lines than the count before them announces?)");
        }
        continue;
      }
      skipping = !this->section(std::string(key), value);
    }
    this->endZone();
    if (this->Out.zones.empty())
    {
      throw FileError(path, 0, "has no NDIME=, NPOIN= or NELEM=: not an SU2 mesh");
    }
    if (this->ZoneCount > 1 && this->Out.zones.size() != static_cast<std::size_t>(this->ZoneCount))
    {
      this->failAt(this->ZoneCountAt, "NZONE= " + std::to_string(this->ZoneCount) + " announces " + std::to_string(this->ZoneCount) +
          " zones; the file has " + std::to_string(this->Out.zones.size()) + " (IZONE=)");
    }
    if (!layoutOnly)
    {
      this->finish();
    }
  }

  MeshFile Out;

private:
  const bool LayoutOnly;
  std::string_view Record;
  std::vector<std::string_view> Fields;
  int ZoneCount = 0; // NZONE=, 0 without it
  std::size_t ZoneCountAt = 0;
  bool Open = false; // whether a zone is being read
  ZoneRead Current;
  std::size_t NextNode = 0, NextElement = 0; // the first ids of the next zone
  std::map<CellType, std::size_t> BlockOfType;
  std::vector<Marker> Markers;
  std::vector<Unknown> Unknowns;
  std::vector<std::vector<std::int64_t>> ZoneCells;

  // ---- errors ----------------------------------------------------------------------------------

  // What a zone lacks: a file of one zone's, or (several) its IZONE= line's.
  [[noreturn]] void zoneFails(const std::string& reason) const
  {
    if (this->ZoneCount > 1)
    {
      this->failAt(this->Current.start, "zone " + std::to_string(this->Current.number) + " " + reason);
    }
    throw FileError(this->Out.path, 0, reason);
  }

  // ---- text --------------------------------------------------------------------------------------

  // The line of item index of the count that key announces, into Fields: SU2 reads them one a
  // line, so a blank line or a keyword there is an error.
  void dataLine(const char* item, std::uint64_t index, std::uint64_t count, const char* key)
  {
    const auto announced = [&] { return " of the " + std::to_string(count) + " " + item + "s that " + key + " announces"; };
    if (!this->nextLine(this->Record))
    {
      this->failAt(this->Text.size(), "the file ends after " + std::to_string(index) + announced() + " (it is cut short)");
    }
    splitBlanks(this->Record, this->Fields);
    if (this->Fields.empty() || this->Fields[0][0] == '%' || this->Fields[0].find('=') != std::string_view::npos)
    {
      this->fail((this->Fields.empty() ? std::string("a blank line") : quoted(trim(this->Record))) + " where " + item + " " +
        std::to_string(index) + announced() + " is expected");
    }
  }

  std::int64_t integer(std::string_view field, const char* what) const
  {
    std::int64_t value = 0;
    if (!parseInteger(field.data(), field.data() + field.size(), value))
    {
      this->fail(quoted(field) + " is not " + what);
    }
    return value;
  }

  std::uint64_t count(std::string_view field, const char* what) const
  {
    const std::int64_t value = this->integer(field, what);
    if (value < 0)
    {
      this->fail(std::string(what) + " " + std::to_string(value) + " is negative");
    }
    return static_cast<std::uint64_t>(value);
  }

  // ---- sections ----------------------------------------------------------------------------------

  // The section of key starting on the line read last; false for a keyword that is not the mesh's.
  bool section(const std::string& key, std::string_view value)
  {
    if (!this->Current.tag.empty() && key != "MARKER_ELEMS")
    {
      this->fail(key + "= where MARKER_ELEMS= of the marker " + this->Current.tag + " is expected");
    }
    if (key == "NZONE")
    {
      if (this->Open || this->ZoneCount > 0)
      {
        this->fail("NZONE= after the mesh's first section: it comes first");
      }
      const std::uint64_t zones = this->count(value, "a number of zones");
      if (zones == 0)
      {
        this->fail("NZONE= 0: a mesh has a zone at least");
      }
      this->room(zones, 8, "zones"); // an IZONE= line each at least
      this->ZoneCount = static_cast<int>(zones);
      this->ZoneCountAt = this->Mark;
      return true;
    }
    if (key == "IZONE")
    {
      this->beginZone(value);
      return true;
    }
    const bool mesh = key == "NDIME" || key == "NPOIN" || key == "NELEM" || key == "NMARK" || key == "MARKER_TAG" || key == "MARKER_ELEMS";
    if (mesh && !this->Open)
    {
      if (this->ZoneCount > 1)
      {
        this->fail(key + "= before the first IZONE= of a file of NZONE= " + std::to_string(this->ZoneCount));
      }
      this->openZone(1);
    }
    ZoneRead& zone = this->Current;
    auto once = [&](bool read) {
      if (read)
      {
        this->fail("a second " + key + "= in one zone (a file of several zones starts each with IZONE=)");
      }
    };
    if (key == "NDIME")
    {
      once(zone.dimension != 0);
      const std::int64_t dimension = this->integer(value, "a dimension (2 or 3)");
      if (dimension != 2 && dimension != 3)
      {
        this->fail("NDIME= " + std::to_string(dimension) + " is neither 2 nor 3");
      }
      zone.dimension = static_cast<int>(dimension);
    }
    else if (key == "NPOIN")
    {
      once(zone.points);
      if (zone.dimension == 0)
      {
        this->fail("NPOIN= before NDIME= (the number of a point's coordinates)");
      }
      // "NPOIN= points [owned]": a partition's file also gives the points it owns
      splitBlanks(value, this->Fields);
      if (this->Fields.empty() || this->Fields.size() > 2)
      {
        this->fail("NPOIN= " + quoted(value) + " is not \"points\" or \"points owned-points\"");
      }
      zone.pointCount = this->count(this->Fields[0], "a number of points");
      if (this->Fields.size() == 2 && this->count(this->Fields[1], "a number of owned points") > zone.pointCount)
      {
        this->fail("NPOIN= " + std::string(value) + ": more owned points than points");
      }
      zone.points = true;
      this->points();
    }
    else if (key == "NELEM")
    {
      once(zone.elements);
      zone.elementCount = this->count(value, "a number of elements");
      zone.elements = true;
      this->elements();
    }
    else if (key == "NMARK")
    {
      once(zone.markers >= 0);
      zone.markers = static_cast<std::int64_t>(this->count(value, "a number of markers"));
      zone.markersAt = this->Mark;
    }
    else if (key == "MARKER_TAG")
    {
      if (zone.markersRead >= zone.markers)
      {
        this->fail(zone.markers < 0 ? "MARKER_TAG= before NMARK=" : "a marker beyond the " + std::to_string(zone.markers) + " that NMARK= announces");
      }
      // without blanks, as SU2 reads it (the name its configuration files give)
      for (const char c : value)
      {
        if (!isBlank(c))
        {
          zone.tag.push_back(c);
        }
      }
      if (zone.tag.empty())
      {
        this->fail("MARKER_TAG= without a name");
      }
      zone.tagAt = this->Mark;
    }
    else if (key == "MARKER_ELEMS")
    {
      if (zone.tag.empty())
      {
        this->fail("MARKER_ELEMS= without its MARKER_TAG= before it");
      }
      this->markerElements(this->count(value, "a number of marker elements"));
      zone.tag.clear();
      ++zone.markersRead;
    }
    return mesh;
  }

  void beginZone(std::string_view value)
  {
    if (this->ZoneCount == 0)
    {
      this->fail("IZONE= without NZONE= at the start of the file");
    }
    const std::int64_t number = this->integer(value, "a zone number");
    if (number < 1 || number > this->ZoneCount)
    {
      this->fail("IZONE= " + std::to_string(number) + " is not a zone of NZONE= " + std::to_string(this->ZoneCount) + " (1 to " +
        std::to_string(this->ZoneCount) + ")");
    }
    this->endZone();
    for (const su2::Zone& zone : this->Out.zones)
    {
      if (zone.number == number)
      {
        this->fail("a second IZONE= " + std::to_string(number));
      }
    }
    this->openZone(static_cast<int>(number));
  }

  // A zone starts on the line read last.
  void openZone(int number)
  {
    this->Current = ZoneRead();
    this->Current.number = number;
    this->Current.start = this->Mark;
    this->Current.firstNode = this->NextNode;
    this->Current.firstElement = this->NextElement;
    this->Open = true;
  }

  // The zone read whole: what it lacks, and an element that refers to a point it does not have.
  void endZone()
  {
    if (!this->Open)
    {
      return;
    }
    ZoneRead& zone = this->Current;
    if (!zone.tag.empty())
    {
      this->failAt(zone.tagAt, "MARKER_TAG= " + zone.tag + " without its MARKER_ELEMS=");
    }
    if (zone.dimension == 0)
    {
      this->zoneFails("has no NDIME=");
    }
    if (!zone.points)
    {
      this->zoneFails("has no NPOIN=");
    }
    if (!zone.elements)
    {
      this->zoneFails("has no NELEM=");
    }
    if (zone.markers > zone.markersRead)
    {
      this->failAt(zone.markersAt, "NMARK= " + std::to_string(zone.markers) + " announces " + std::to_string(zone.markers) +
          " markers; the zone has " + std::to_string(zone.markersRead));
    }
    if (zone.highest >= static_cast<std::int64_t>(zone.pointCount))
    {
      const std::string defined = zone.pointCount == 0 ? "none" : "points 0 to " + std::to_string(zone.pointCount - 1);
      this->failAt(zone.highestAt, "an element refers to point " + std::to_string(zone.highest) + "; NPOIN= " +
          std::to_string(zone.pointCount) + " defines " + defined);
    }
    this->Out.zones.push_back({ zone.number, zone.dimension, zone.firstNode });
    this->NextNode = zone.firstNode + zone.pointCount;
    this->NextElement = zone.firstElement + zone.elementCount;
    this->ZoneCells.push_back(std::move(zone.cells));
    this->Open = false;
  }

  // "x y [z] [index...]" each.
  void points()
  {
    const ZoneRead& zone = this->Current;
    const std::size_t dimension = static_cast<std::size_t>(zone.dimension);
    this->room(zone.pointCount, 2 * dimension, "points");
    this->Out.mesh.nodeIds.reserve(this->Out.mesh.nodeIds.size() + zone.pointCount);
    this->Out.coordinates.reserve(this->Out.coordinates.size() + zone.pointCount);
    this->Out.mesh.xyz.reserve(this->Out.mesh.xyz.size() + 3 * zone.pointCount);
    for (std::uint64_t i = 0; i < zone.pointCount; ++i)
    {
      this->dataLine("point", i, zone.pointCount, "NPOIN=");
      if (this->Fields.size() < dimension)
      {
        this->fail("point " + std::to_string(i) + " is " + quoted(trim(this->Record)) + "; a point of NDIME= " + std::to_string(dimension) +
          " is \"x y" + (dimension == 3 ? " z" : "") + " [index]\"");
      }
      this->Out.mesh.nodeIds.push_back(static_cast<std::int64_t>(zone.firstNode + i));
      this->Out.coordinates.push_back(static_cast<std::uint64_t>(this->Fields[0].data() - this->Text.data()));
      this->Out.nodesEnd = static_cast<std::uint64_t>(this->Fields[dimension - 1].data() + this->Fields[dimension - 1].size() - this->Text.data());
      for (std::size_t c = 0; c < dimension; ++c)
      {
        double value = 0;
        const std::string_view field = this->Fields[c];
        if (!parseReal(field.data(), field.data() + field.size(), value))
        {
          this->fail("point " + std::to_string(i) + "'s coordinate " + quoted(field) + " is not a finite number");
        }
        this->Out.mesh.xyz.push_back(value);
      }
      if (dimension == 2)
      {
        this->Out.mesh.xyz.push_back(0);
      }
      for (std::size_t k = dimension; k < this->Fields.size(); ++k)
      {
        std::int64_t index = 0;
        if (!parseInteger(this->Fields[k].data(), this->Fields[k].data() + this->Fields[k].size(), index))
        {
          this->fail(quoted(this->Fields[k]) + " after the " + std::to_string(dimension) + " coordinates of point " + std::to_string(i) +
            " is not an index (NDIME= " + std::to_string(dimension) + ")");
        }
      }
    }
  }

  // "type point... [index]" each: the cells.
  void elements()
  {
    ZoneRead& zone = this->Current;
    this->room(zone.elementCount, 2, "elements");
    const std::string section = this->sectionName("NELEM=");
    for (std::uint64_t e = 0; e < zone.elementCount; ++e)
    {
      this->dataLine("element", e, zone.elementCount, "NELEM=");
      const ElementKind* kind = this->LayoutOnly ? nullptr : this->kindOf(section);
      if (kind == nullptr)
      {
        continue;
      }
      const auto [at, added] = this->BlockOfType.emplace(kind->type, this->Out.mesh.blocks.size());
      if (added)
      {
        this->Out.mesh.blocks.push_back({ kind->name, kind->type, {}, {} });
      }
      ElementBlock& block = this->Out.mesh.blocks[at->second];
      const std::int64_t id = static_cast<std::int64_t>(zone.firstElement + e);
      block.ids.push_back(id);
      this->appendPoints(*kind, block.nodes);
      if (this->ZoneCount > 1)
      {
        zone.cells.push_back(id);
      }
    }
  }

  // The marker's elements: their points are its node set.
  void markerElements(std::uint64_t count)
  {
    this->room(count, 2, "marker elements");
    if (!this->LayoutOnly)
    {
      this->Markers.push_back({ this->Current.number, this->Current.tag, {} });
    }
    const std::string section = this->sectionName("marker " + this->Current.tag);
    for (std::uint64_t e = 0; e < count; ++e)
    {
      this->dataLine("element", e, count, "MARKER_ELEMS=");
      const ElementKind* kind = this->LayoutOnly ? nullptr : this->kindOf(section);
      if (kind != nullptr)
      {
        this->appendPoints(*kind, this->Markers.back().nodes);
      }
    }
  }

  std::string sectionName(const std::string& name) const
  {
    return this->ZoneCount > 1 ? name + " of zone " + std::to_string(this->Current.number) : name;
  }

  // The kind of the element on the line read last; nullptr (told in a warning) for a type that SU2
  // does not have.
  const ElementKind* kindOf(const std::string& section)
  {
    const std::int64_t type = this->integer(this->Fields[0], "an element type");
    const ElementKind* kind = elementKind(type);
    if (kind == nullptr)
    {
      const auto same = [&](const Unknown& unknown) { return unknown.type == type && unknown.section == section; };
      const auto found = std::find_if(this->Unknowns.begin(), this->Unknowns.end(), same);
      if (found == this->Unknowns.end())
      {
        this->Unknowns.push_back({ section, type, this->Mark, 1 });
      }
      else
      {
        ++found->count;
      }
    }
    return kind;
  }

  // Appends the ids of the points of the element on the line read last.
  void appendPoints(const ElementKind& kind, std::vector<std::int64_t>& nodes)
  {
    const std::size_t count = static_cast<std::size_t>(nodesPerCell(kind.type));
    if (this->Fields.size() != count + 1 && this->Fields.size() != count + 2)
    {
      this->fail("a line of " + std::to_string(this->Fields.size()) + " fields where a " + kind.name + "'s " + std::to_string(count + 1) +
        " or " + std::to_string(count + 2) + " are expected (its type, its " + std::to_string(count) + " points, an optional index)");
    }
    ZoneRead& zone = this->Current;
    for (std::size_t k = 1; k <= count; ++k)
    {
      const std::int64_t point = this->integer(this->Fields[k], "a point's index");
      if (point < 0)
      {
        this->fail("point index " + std::to_string(point) + " is negative");
      }
      if (point > zone.highest)
      {
        zone.highest = point;
        zone.highestAt = this->Mark;
      }
      nodes.push_back(static_cast<std::int64_t>(zone.firstNode) + point);
    }
    if (this->Fields.size() == count + 2)
    {
      this->integer(this->Fields.back(), "an element's index");
    }
  }

  // ---- the mesh: warnings, sets ------------------------------------------------------------------

  void finish()
  {
    SourceMesh& mesh = this->Out.mesh;
    for (const Unknown& unknown : this->Unknowns)
    {
      mesh.warnings.push_back(this->Out.path + ":" + std::to_string(this->lineOf(unknown.at)) + ": element type " +
        std::to_string(unknown.type) + " (" + unknown.section + ") is not one of SU2's (3, 5, 9, 10, 12, 13, 14): its " +
        std::to_string(unknown.count) + " elements are left out (their points are read and move with the rest)");
    }
    // a marker's node set, named by its tag; a tag of several zones' markers, by its zone too
    std::map<std::string, std::set<int>> zonesOfTag;
    for (const Marker& marker : this->Markers)
    {
      zonesOfTag[marker.tag].insert(marker.zone);
    }
    std::map<std::string, std::size_t> setOfName;
    for (const Marker& marker : this->Markers)
    {
      const std::string name = zonesOfTag[marker.tag].size() > 1 ? marker.tag + " (zone " + std::to_string(marker.zone) + ")" : marker.tag;
      const auto [at, added] = setOfName.emplace(name, mesh.nodeSets.size());
      if (added)
      {
        mesh.nodeSets.push_back({ name, {} });
      }
      std::vector<std::int64_t>& ids = mesh.nodeSets[at->second].ids;
      ids.insert(ids.end(), marker.nodes.begin(), marker.nodes.end());
    }
    for (NamedSet& set : mesh.nodeSets)
    {
      std::sort(set.ids.begin(), set.ids.end());
      set.ids.erase(std::unique(set.ids.begin(), set.ids.end()), set.ids.end());
    }
    if (this->ZoneCount < 2)
    {
      return;
    }
    for (std::size_t z = 0; z < this->Out.zones.size(); ++z)
    {
      const std::string name = "zone " + std::to_string(this->Out.zones[z].number);
      const std::size_t end = z + 1 < this->Out.zones.size() ? this->Out.zones[z + 1].firstNode : mesh.nodeIds.size();
      NamedSet nodes{ name, std::vector<std::int64_t>(end - this->Out.zones[z].firstNode) };
      std::iota(nodes.ids.begin(), nodes.ids.end(), static_cast<std::int64_t>(this->Out.zones[z].firstNode));
      mesh.nodeSets.push_back(std::move(nodes));
      mesh.elementSets.push_back({ name, std::move(this->ZoneCells[z]) });
    }
  }
};

} // namespace

MeshFile readSu2(const std::string& path)
{
  return std::move(Reader(path, false).Out);
}

MeshFile readSu2Layout(const std::string& path)
{
  return std::move(Reader(path, true).Out);
}

bool isSu2(const std::string& head)
{
  for (const Line& line : lines(head))
  {
    const std::string_view content = trim(std::string_view(head).substr(line.begin, line.end - line.begin));
    if (!content.empty() && content[0] != '%')
    {
      return content.compare(0, 6, "NDIME=") == 0 || content.compare(0, 6, "NZONE=") == 0;
    }
  }
  return false;
}

void MeshFile::writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
  bool overwrite) const
{
  VariantSource source = variantSource(target, this->path, this->hash, this->mesh.nodeIds, ids, xyz, count);
  const std::vector<std::size_t>& row = source.row;
  std::vector<int> dimension(count); // each node's: its zone's
  for (std::size_t z = 0; z < this->zones.size(); ++z)
  {
    const std::size_t end = z + 1 < this->zones.size() ? this->zones[z + 1].firstNode : count;
    std::fill(dimension.begin() + this->zones[z].firstNode, dimension.begin() + end, this->zones[z].dimension);
  }
  AtomicWrite write(overwrite);
  AtomicWrite::Aside out = write.open(target);
  rewriteInPieces(out, source.file, count, this->nodesEnd, [&](std::size_t k) { return this->coordinates[k]; },
    [&](std::string& piece, std::string_view text, std::size_t at, std::size_t k) {
      return appendNumbers(piece, text, at, dimension[k], xyz + 3 * row[k], this->mesh.xyz.data() + 3 * k);
    });
  write.close(out);
  write.commit();
}
} // namespace su2
} // namespace mlsformats
