#include "CGNS/CgnsMesh.h"

#include "Common/TextFile.h"
#include "Common/VariantNodes.h"

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <fstream>
#include <functional>
#include <map>


// ParaView's CGNS library (VTK::cgns, CGNS 4.2) reads the files of CGNS 3 and 4; the system's
// (Debian 12's libcgns 3.4) refuses those written by CGNS 4.
#ifdef MLSFORMATS_VTK_CGNS
#include <vtk_cgns.h>
#include VTK_CGNS(cgnslib.h)
#include VTK_CGNS(cgns_io.h)
#else
#include <cgns_io.h>
#include <cgnslib.h>
#endif

namespace mlsformats
{
namespace cgns
{
namespace
{
using ElementType = CGNS_ENUMT(ElementType_t);

// ---- element types ---------------------------------------------------------------------------

// The dimension of an element type; -1 for MIXED, NGON_n, NFACE_n and the unknown.
int dimension(ElementType type)
{
  switch (type)
  {
    case CGNS_ENUMV(NODE): return 0;
    case CGNS_ENUMV(BAR_2):
    case CGNS_ENUMV(BAR_3):
    case CGNS_ENUMV(BAR_4):
    case CGNS_ENUMV(BAR_5): return 1;
    case CGNS_ENUMV(TRI_3):
    case CGNS_ENUMV(TRI_6):
    case CGNS_ENUMV(TRI_9):
    case CGNS_ENUMV(TRI_10):
    case CGNS_ENUMV(TRI_12):
    case CGNS_ENUMV(TRI_15):
    case CGNS_ENUMV(QUAD_4):
    case CGNS_ENUMV(QUAD_8):
    case CGNS_ENUMV(QUAD_9):
    case CGNS_ENUMV(QUAD_12):
    case CGNS_ENUMV(QUAD_16):
    case CGNS_ENUMV(QUAD_P4_16):
    case CGNS_ENUMV(QUAD_25): return 2;
    case CGNS_ENUMV(ElementTypeNull):
    case CGNS_ENUMV(ElementTypeUserDefined):
    case CGNS_ENUMV(MIXED):
    case CGNS_ENUMV(NGON_n):
    case CGNS_ENUMV(NFACE_n): return -1;
    default: return 3;
  }
}

struct CellKind
{
  CellType type;
  std::vector<int> order; // VTK's node i is CGNS's node order[i] (empty: the same)
};

// The cell type of a CGNS element type, or false. CGNS's node numbers are its SIDS' ("Unstructured
// Grid Element Numbering Conventions"), VTK's its cells'. The others number alike: corners, then
// the midside nodes edge by edge as VTK's edges go, then the centre (QUAD_9).
bool cellKind(ElementType type, CellKind& kind)
{
  kind.order.clear();
  switch (type)
  {
    case CGNS_ENUMV(BAR_2): kind.type = CellType::Line; return true;
    case CGNS_ENUMV(BAR_3): kind.type = CellType::QuadraticEdge; return true;
    case CGNS_ENUMV(TRI_3): kind.type = CellType::Triangle; return true;
    case CGNS_ENUMV(TRI_6): kind.type = CellType::QuadraticTriangle; return true;
    case CGNS_ENUMV(QUAD_4): kind.type = CellType::Quad; return true;
    case CGNS_ENUMV(QUAD_8): kind.type = CellType::QuadraticQuad; return true;
    case CGNS_ENUMV(QUAD_9): kind.type = CellType::BiQuadraticQuad; return true;
    case CGNS_ENUMV(TETRA_4): kind.type = CellType::Tetra; return true;
    case CGNS_ENUMV(TETRA_10): kind.type = CellType::QuadraticTetra; return true;
    case CGNS_ENUMV(PYRA_5): kind.type = CellType::Pyramid; return true;
    case CGNS_ENUMV(PYRA_13): kind.type = CellType::QuadraticPyramid; return true;
    case CGNS_ENUMV(HEXA_8): kind.type = CellType::Hexahedron; return true;
    // a PENTA's 1-2-3 turns counter-clockwise seen from 4-5-6 (the SIDS' r, s and t run along 1-2,
    // 1-3 and 1-4; its face 1-3-2 points outward), VTK's wedge the other way ((0,1,2)'s normal
    // points away from (3,4,5): vtkWedge.h), as Gmsh's prism and Abaqus's C3D6 are turned
    case CGNS_ENUMV(PENTA_6): kind.type = CellType::Wedge; kind.order = { 0, 2, 1, 3, 5, 4 }; return true;
    // turned alike, its edges 6-14 being CGNS's 1-2 2-3 3-1 1-4 2-5 3-6 4-5 5-6 6-4 and VTK's 0-1 1-2
    // 2-0 3-4 4-5 5-3 0-3 1-4 2-5 of the turned corners
    case CGNS_ENUMV(PENTA_15):
      kind.type = CellType::QuadraticWedge;
      kind.order = { 0, 2, 1, 3, 5, 4, 8, 7, 6, 14, 13, 12, 9, 11, 10 };
      return true;
    // CGNS's edges 8-19 are 0-1 1-2 2-3 3-0, 0-4 1-5 2-6 3-7, 4-5 5-6 6-7 7-4, VTK's 4-5 5-6 6-7 7-4
    // before 0-4 1-5 2-6 3-7; HEXA_27's face centres 20-25 are CGNS's z=0 y=0 x=1 y=1 x=0 z=1 (faces
    // 0123 0154 1265 2376 0473 4567), VTK's x=0 x=1 y=0 y=1 z=0 z=1
    case CGNS_ENUMV(HEXA_20):
      kind.type = CellType::QuadraticHexahedron;
      kind.order = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 12, 13, 14, 15 };
      return true;
    case CGNS_ENUMV(HEXA_27):
      kind.type = CellType::TriQuadraticHexahedron;
      kind.order = { 0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 16, 17, 18, 19, 12, 13, 14, 15, 24, 22, 21, 23, 20, 25, 26 };
      return true;
    default: return false;
  }
}

// ---- the reader --------------------------------------------------------------------------------

// A file open in the mid-level library, closed when done.
struct OpenFile
{
  int fn = -1;
  ~OpenFile()
  {
    if (this->fn >= 0)
    {
      cg_close(this->fn);
    }
  }
};

// An element section's connectivity as the library gives it: fixed-size elements one after the
// other; MIXED, NGON_n and NFACE_n with offsets (MIXED's elements each start with their type).
struct Section
{
  std::string where; // "/base/zone/section"
  ElementType type;
  std::int64_t start = 0, end = 0;
  int perElement = 0; // fixed-size types
  std::vector<cgsize_t> data, offsets;

  std::size_t count() const { return static_cast<std::size_t>(this->end - this->start + 1); }
  // Element e's (0-based) type, and its nodes [first, last) (NFACE_n's: faces).
  ElementType element(std::size_t e, const cgsize_t*& first, const cgsize_t*& last) const
  {
    if (this->offsets.empty())
    {
      first = this->data.data() + e * this->perElement;
      last = first + this->perElement;
      return this->type;
    }
    first = this->data.data() + this->offsets[e];
    last = this->data.data() + this->offsets[e + 1];
    return this->type == CGNS_ENUMV(MIXED) ? static_cast<ElementType>(*first++) : this->type;
  }
};

// Named sets of ids, a name that comes again adding to its set; each in increasing order at the end.
class Sets
{
public:
  std::vector<std::int64_t>& operator[](const std::string& name)
  {
    const auto found = this->Index.emplace(name, this->All.size());
    if (found.second)
    {
      this->All.push_back({ name, {} });
    }
    return this->All[found.first->second].ids;
  }
  std::vector<NamedSet> finish()
  {
    for (NamedSet& set : this->All)
    {
      std::sort(set.ids.begin(), set.ids.end());
      set.ids.erase(std::unique(set.ids.begin(), set.ids.end()), set.ids.end());
    }
    return std::move(this->All);
  }

private:
  std::vector<NamedSet> All;
  std::map<std::string, std::size_t> Index;
};

class Reader
{
public:
  Reader(const std::string& path, bool layout)
    : Layout(layout)
  {
    this->Out.path = path;
    {
      this->Out.hash = fileHash(path);
      if (!isCgns(readHead(path, 64)))
      {
        throw FileError(path, 0, "is not a CGNS file (neither HDF5 nor ADF)");
      }
    }
    OpenFile file;
    if (cg_open(path.c_str(), CG_MODE_READ, &this->Fn) != CG_OK)
    {
      throw FileError(path, 0, "cannot be read by the CGNS library " + std::to_string(CGNS_DOTVERS).substr(0, 4) + ": " + cg_get_error());
    }
    file.fn = this->Fn;
    int bases = 0;
    this->check(cg_nbases(this->Fn, &bases), "");
    if (bases == 0)
    {
      // a bug of the CGNS libraries 4.2 and 4.3 (fixed in 4.4): HDF5 groups without creation order
      throw FileError(path, 0, "has no bases (the CGNS libraries 4.2 and 4.3 see none in some files of CGNS 3.0 and 3.1)");
    }
    for (int b = 1; b <= bases; ++b)
    {
      char name[33];
      this->check(cg_base_read(this->Fn, b, name, &this->CellDim, &this->PhysDim), "base " + std::to_string(b));
      this->Base = name;
      int zones = 0;
      this->check(cg_nzones(this->Fn, b, &zones), "/" + this->Base);
      for (int z = 1; z <= zones; ++z)
      {
        this->zone(b, z);
      }
    }
    if (this->Out.zones.empty())
    {
      throw FileError(path, 0, "has no zones");
    }
    this->Out.mesh.nodeSets = this->NodeSets.finish();
    this->Out.mesh.elementSets = this->ElementSets.finish();
  }

  MeshFile Out;

private:
  bool Layout;
  int Fn = 0;
  int CellDim = 0, PhysDim = 0;
  std::string Base;
  std::int64_t ElementOffset = 0;
  Sets NodeSets, ElementSets;

  void check(int status, const std::string& where) const
  {
    if (status != CG_OK)
    {
      throw FileError(this->Out.path, 0, where + ": " + cg_get_error());
    }
  }

  [[noreturn]] void fail(const std::string& where, const std::string& reason) const
  {
    throw FileError(this->Out.path, 0, where + ": " + reason);
  }

  void warn(const std::string& where, const std::string& what)
  {
    this->Out.mesh.warnings.push_back(this->Out.path + ": " + where + ": " + what);
  }

  // ---- a zone: its coordinates, then its cells and sets --------------------------------------------

  void zone(int b, int z)
  {
    char name[33];
    cgsize_t size[9] = {};
    CGNS_ENUMT(ZoneType_t) type;
    int indexDim = 0;
    this->check(cg_zone_read(this->Fn, b, z, name, size), "/" + this->Base + " zone " + std::to_string(z));
    const std::string where = "/" + this->Base + "/" + name;
    this->check(cg_zone_type(this->Fn, b, z, &type), where);
    this->check(cg_index_dim(this->Fn, b, z, &indexDim), where);
    const bool structured = type == CGNS_ENUMV(Structured);
    if (!structured && type != CGNS_ENUMV(Unstructured))
    {
      this->fail(where, "is neither structured nor unstructured");
    }
    // a structured zone's points along i, j (and k); an unstructured one's count
    std::vector<std::int64_t> points(size, size + indexDim);
    Zone zone{ this->Base, name, "", 1, 0, {}, {} };
    for (const std::int64_t count : points)
    {
      zone.nodes *= count;
    }
    zone.offset = this->Out.zones.empty() ? 0 : this->Out.zones.back().offset + this->Out.zones.back().nodes;
    this->coordinates(b, z, where, points, zone);
    if (!this->Layout && structured)
    {
      this->structuredCells(where, zone, points);
      this->structuredBCs(b, z, where, zone, points);
    }
    else if (!this->Layout)
    {
      const std::vector<Section> sections = this->sections(b, z, where, zone);
      this->unstructuredBCs(b, z, where, zone, sections);
    }
    this->Out.mesh.zones.push_back({ zone.base + "/" + zone.name, zone.offset + 1, zone.nodes });
    this->Out.zones.push_back(std::move(zone));
  }

  // The zone's node ids, and its coordinates (X, Y, and Z when the base is 3D or the zone has one).
  void coordinates(int b, int z, const std::string& where, const std::vector<std::int64_t>& points, Zone& zone)
  {
    int grids = 0, count = 0;
    this->check(cg_ngrids(this->Fn, b, z, &grids), where);
    if (grids == 0)
    {
      this->fail(where, "has no grid coordinates");
    }
    char name[33];
    this->check(cg_grid_read(this->Fn, b, z, 1, name), where);
    zone.grid = name;
    if (grids > 1)
    {
      this->warn(where, "has " + std::to_string(grids) + " grids: the first, " + zone.grid + ", is read and written, the others stay");
    }
    int rind[6] = {};
    this->check(cg_goto(this->Fn, b, "Zone_t", z, "GridCoordinates_t", 1, "end"), where + "/" + zone.grid);
    if (cg_rind_read(rind) == CG_OK && std::any_of(rind, rind + 6, [](int planes) { return planes != 0; }))
    {
      this->fail(where + "/" + zone.grid, "has rind planes: they are not supported");
    }
    this->check(cg_ncoords(this->Fn, b, z, &count), where);
    std::map<std::string, CGNS_ENUMT(DataType_t)> types;
    for (int c = 1; c <= count; ++c)
    {
      CGNS_ENUMT(DataType_t) type;
      this->check(cg_coord_info(this->Fn, b, z, c, &type, name), where + "/" + zone.grid);
      types[name] = type;
    }
    for (const char* axis : { "CoordinateX", "CoordinateY", "CoordinateZ" })
    {
      const auto found = types.find(axis);
      const bool needed = std::string(axis) != "CoordinateZ" || this->PhysDim == 3;
      if (found == types.end() && needed)
      {
        this->fail(where + "/" + zone.grid, "has no " + std::string(axis) + " (only Cartesian coordinates are supported)");
      }
      if (found == types.end())
      {
        continue;
      }
      if (found->second != CGNS_ENUMV(RealDouble) && found->second != CGNS_ENUMV(RealSingle))
      {
        this->fail(where + "/" + zone.grid + "/" + axis, "is not real (RealDouble or RealSingle)");
      }
      zone.coordinates.push_back(axis);
      zone.single.push_back(found->second == CGNS_ENUMV(RealSingle));
    }
    SourceMesh& mesh = this->Out.mesh;
    for (std::int64_t n = 1; n <= zone.nodes; ++n)
    {
      mesh.nodeIds.push_back(zone.offset + n);
    }
    if (this->Layout)
    {
      return;
    }
    const std::size_t first = mesh.xyz.size();
    mesh.xyz.resize(first + 3 * zone.nodes, 0.0);
    const std::vector<cgsize_t> low(points.size(), 1), high(points.begin(), points.end());
    std::vector<double> values(zone.nodes);
    for (std::size_t c = 0; c < zone.coordinates.size(); ++c)
    {
      const std::string& axis = zone.coordinates[c];
      this->check(cg_coord_read(this->Fn, b, z, axis.c_str(), CGNS_ENUMV(RealDouble), low.data(), high.data(), values.data()),
        where + "/" + zone.grid + "/" + axis);
      for (std::int64_t n = 0; n < zone.nodes; ++n)
      {
        if (!std::isfinite(values[n]))
        {
          this->fail(where + "/" + zone.grid + "/" + axis, "node " + std::to_string(n + 1) + "'s value is not a finite number");
        }
        mesh.xyz[first + 3 * n + c] = values[n];
      }
    }
  }

  // ---- structured zones ----------------------------------------------------------------------------

  // The node id of the 0-based (i, j, k).
  static std::int64_t nodeId(const Zone& zone, const std::vector<std::int64_t>& points, const std::int64_t* ijk)
  {
    std::int64_t index = 0;
    for (std::size_t d = points.size(); d-- > 0;)
    {
      index = index * points[d] + ijk[d];
    }
    return zone.offset + 1 + index;
  }

  // The cells between the points: hexahedra (quadrangles, lines) in VTK's order, numbered as the
  // points are.
  void structuredCells(const std::string& where, const Zone& zone, const std::vector<std::int64_t>& points)
  {
    static const int corners[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 },
      { 0, 1, 1 } };
    static const CellType types[] = { CellType::Line, CellType::Quad, CellType::Hexahedron };
    static const char* const names[] = { "structured line", "structured quadrilateral", "structured hexahedron" };
    const std::size_t dims = points.size();
    if (dims < 1 || dims > 3)
    {
      this->fail(where, "has " + std::to_string(dims) + " index dimensions");
    }
    ElementBlock block{ names[dims - 1], types[dims - 1], {}, {} };
    std::vector<std::int64_t> cells(3, 1);
    for (std::size_t d = 0; d < dims; ++d)
    {
      cells[d] = points[d] - 1;
    }
    std::int64_t id = this->ElementOffset;
    std::int64_t cell[3], at[3];
    for (cell[2] = 0; cell[2] < cells[2]; ++cell[2])
    {
      for (cell[1] = 0; cell[1] < cells[1]; ++cell[1])
      {
        for (cell[0] = 0; cell[0] < cells[0]; ++cell[0])
        {
          block.ids.push_back(++id);
          for (int c = 0; c < (1 << dims); ++c)
          {
            for (std::size_t d = 0; d < dims; ++d)
            {
              at[d] = cell[d] + corners[c][d];
            }
            block.nodes.push_back(nodeId(zone, points, at));
          }
        }
      }
    }
    this->ElementOffset = id;
    std::vector<std::int64_t>& set = this->ElementSets[zone.name];
    set.insert(set.end(), block.ids.begin(), block.ids.end());
    this->Out.mesh.blocks.push_back(std::move(block));
  }

  // Each BC's nodes: its points' boxes, a box being a point (Vertex), a face (its nodes: one more
  // along the other directions) or a cell (one more along each).
  void structuredBCs(int b, int z, const std::string& where, const Zone& zone, const std::vector<std::int64_t>& points)
  {
    const std::size_t dims = points.size();
    int count = 0;
    this->check(cg_nbocos(this->Fn, b, z, &count), where);
    for (int bc = 1; bc <= count; ++bc)
    {
      std::string name, family;
      CGNS_ENUMT(PointSetType_t) pointSet;
      CGNS_ENUMT(GridLocation_t) location;
      std::vector<cgsize_t> data;
      this->boco(b, z, bc, dims, where, name, family, pointSet, location, data);
      const std::string at = where + "/ZoneBC/" + name;
      const std::size_t boxes = data.size() / dims;
      const bool range = pointSet == CGNS_ENUMV(PointRange);
      if (!range && pointSet != CGNS_ENUMV(PointList))
      {
        this->fail(at, "a structured zone's BC is a point range or list (it is " + std::string(cg_PointSetTypeName(pointSet)) + ")");
      }
      if (range && boxes != 2)
      {
        this->fail(at, "a range of " + std::to_string(boxes) + " points");
      }
      // the direction of the faces: I/J/KFaceCenter's, or FaceCenter's index that all points share
      int face = location == CGNS_ENUMV(IFaceCenter) ? 0
        : location == CGNS_ENUMV(JFaceCenter)        ? 1
        : location == CGNS_ENUMV(KFaceCenter)        ? 2
                                                     : -1;
      for (std::size_t d = 0; d < dims && face < 0 && location == CGNS_ENUMV(FaceCenter); ++d)
      {
        bool shared = true;
        for (std::size_t p = 1; p < boxes; ++p)
        {
          shared = shared && data[p * dims + d] == data[d];
        }
        face = shared ? static_cast<int>(d) : -1;
      }
      if (location != CGNS_ENUMV(Vertex) && location != CGNS_ENUMV(CellCenter) && face < 0)
      {
        this->warn(at, "GridLocation " + std::string(cg_GridLocationName(location)) + " is not supported: its node set is left out");
        continue;
      }
      std::int64_t extra[3] = { 0, 0, 0 };
      for (std::size_t d = 0; d < dims; ++d)
      {
        extra[d] = location == CGNS_ENUMV(Vertex) || static_cast<int>(d) == face ? 0 : 1;
      }
      std::vector<std::int64_t> nodes;
      for (std::size_t p = 0; p < boxes; p += range ? 2 : 1)
      {
        std::int64_t low[3] = { 0, 0, 0 }, high[3] = { 0, 0, 0 };
        for (std::size_t d = 0; d < dims; ++d)
        {
          const std::int64_t first = data[p * dims + d], last = data[(range ? p + 1 : p) * dims + d];
          low[d] = std::min(first, last) - 1;
          high[d] = std::max(first, last) - 1 + extra[d];
          if (low[d] < 0 || high[d] >= points[d])
          {
            this->fail(at, "refers to nodes beyond the zone's " + std::to_string(points[d]) + " points along " + "ijk"[d]);
          }
        }
        std::int64_t ijk[3];
        for (ijk[2] = low[2]; ijk[2] <= high[2]; ++ijk[2])
        {
          for (ijk[1] = low[1]; ijk[1] <= high[1]; ++ijk[1])
          {
            for (ijk[0] = low[0]; ijk[0] <= high[0]; ++ijk[0])
            {
              nodes.push_back(nodeId(zone, points, ijk));
            }
          }
        }
      }
      this->bcSets(name, family, nodes);
    }
  }

  // ---- unstructured zones --------------------------------------------------------------------------

  // The zone's sections: cells in blocks, lower-dimensional elements in node sets; kept for the BCs.
  std::vector<Section> sections(int b, int z, const std::string& where, const Zone& zone)
  {
    SourceMesh& mesh = this->Out.mesh;
    int count = 0;
    this->check(cg_nsections(this->Fn, b, z, &count), where);
    std::vector<Section> sections(count);
    std::int64_t highest = 0;
    std::vector<std::int64_t>& zoneCells = this->ElementSets[zone.name];
    for (int s = 1; s <= count; ++s)
    {
      Section& section = sections[s - 1];
      char name[33];
      cgsize_t start = 0, end = 0;
      int boundary = 0, parents = 0;
      this->check(cg_section_read(this->Fn, b, z, s, name, &section.type, &start, &end, &boundary, &parents),
        where + " section " + std::to_string(s));
      section.where = where + "/" + name;
      section.start = start;
      section.end = end;
      if (end < start || start < 1)
      {
        this->fail(section.where, "has the element range " + std::to_string(start) + "-" + std::to_string(end));
      }
      highest = std::max(highest, section.end);
      this->check(cg_npe(section.type, &section.perElement), section.where);
      if (section.perElement > 0)
      {
        section.data.resize(section.count() * section.perElement);
        this->check(cg_elements_read(this->Fn, b, z, s, section.data.data(), nullptr), section.where);
      }
      else
      {
        cgsize_t size = 0;
        this->check(cg_ElementDataSize(this->Fn, b, z, s, &size), section.where);
        section.data.resize(size);
        section.offsets.resize(section.count() + 1);
        this->check(cg_poly_elements_read(this->Fn, b, z, s, section.data.data(), section.offsets.data(), nullptr), section.where);
      }
      // each element: a cell (its type's block), a boundary element (the section's node set), or left out
      std::map<ElementType, std::size_t> blocks;
      std::map<ElementType, std::size_t> leftOut;
      std::vector<std::int64_t>* boundaryNodes = nullptr;
      CellKind kind;
      for (std::size_t e = 0; e < section.count(); ++e)
      {
        const cgsize_t *first, *last;
        const ElementType type = section.element(e, first, last);
        const int dim = dimension(type);
        // NFACE_n's are faces, not nodes
        if (type == CGNS_ENUMV(NFACE_n))
        {
          ++leftOut[type];
          continue;
        }
        for (const cgsize_t* node = first; node < last; ++node)
        {
          if (*node < 1 || *node > zone.nodes)
          {
            this->fail(section.where, "element " + std::to_string(section.start + e) + " refers to node " + std::to_string(*node) +
                "; the zone has " + std::to_string(zone.nodes) + " nodes");
          }
        }
        if (type == CGNS_ENUMV(NGON_n))
        {
          ++leftOut[type];
        }
        else if (dim >= 0 && dim < this->CellDim)
        {
          boundaryNodes = boundaryNodes ? boundaryNodes : &this->NodeSets[name];
          for (const cgsize_t* node = first; node < last; ++node)
          {
            boundaryNodes->push_back(zone.offset + *node);
          }
        }
        else if (dim != this->CellDim || !cellKind(type, kind))
        {
          ++leftOut[type];
        }
        else
        {
          const auto found = blocks.emplace(type, mesh.blocks.size());
          if (found.second)
          {
            mesh.blocks.push_back({ cg_ElementTypeName(type), kind.type, {}, {} });
          }
          ElementBlock& block = mesh.blocks[found.first->second];
          block.ids.push_back(this->ElementOffset + section.start + static_cast<std::int64_t>(e));
          zoneCells.push_back(block.ids.back());
          for (int k = 0; k < nodesPerCell(kind.type); ++k)
          {
            block.nodes.push_back(zone.offset + first[kind.order.empty() ? k : kind.order[k]]);
          }
        }
      }
      for (const auto& [type, elements] : leftOut)
      {
        this->warn(section.where, "element type " + std::string(cg_ElementTypeName(type)) + " is not supported: its " +
            std::to_string(elements) + " elements are left out (their nodes are read and move with the rest)");
      }
    }
    this->ElementOffset += highest;
    return sections;
  }

  // Each BC's nodes: its points (Vertex), or the nodes of its elements (faces, cells).
  void unstructuredBCs(int b, int z, const std::string& where, const Zone& zone, const std::vector<Section>& sections)
  {
    // the sections by their first element, to find an element's
    std::vector<const Section*> byStart;
    for (const Section& section : sections)
    {
      byStart.push_back(&section);
    }
    std::sort(byStart.begin(), byStart.end(), [](const Section* x, const Section* y) { return x->start < y->start; });
    int count = 0;
    this->check(cg_nbocos(this->Fn, b, z, &count), where);
    for (int bc = 1; bc <= count; ++bc)
    {
      std::string name, family;
      CGNS_ENUMT(PointSetType_t) pointSet;
      CGNS_ENUMT(GridLocation_t) location;
      std::vector<cgsize_t> data;
      this->boco(b, z, bc, 1, where, name, family, pointSet, location, data);
      const std::string at = where + "/ZoneBC/" + name;
      const bool range = pointSet == CGNS_ENUMV(PointRange) || pointSet == CGNS_ENUMV(ElementRange);
      const bool vertices = location == CGNS_ENUMV(Vertex) && pointSet != CGNS_ENUMV(ElementRange) && pointSet != CGNS_ENUMV(ElementList);
      if (!range && pointSet != CGNS_ENUMV(PointList) && pointSet != CGNS_ENUMV(ElementList))
      {
        this->fail(at, "a BC's points are a range or a list (they are " + std::string(cg_PointSetTypeName(pointSet)) + ")");
      }
      if (range && data.size() != 2)
      {
        this->fail(at, "a range of " + std::to_string(data.size()) + " numbers");
      }
      std::vector<std::int64_t> nodes;
      std::size_t polyhedra = 0;
      // a node, or an element's nodes (a number that is neither: FileError)
      auto add = [&](std::int64_t number) {
        if (vertices && (number < 1 || number > zone.nodes))
        {
          this->fail(at, "refers to node " + std::to_string(number) + "; the zone has " + std::to_string(zone.nodes) + " nodes");
        }
        if (vertices)
        {
          nodes.push_back(zone.offset + number);
          return;
        }
        const auto after =
          std::upper_bound(byStart.begin(), byStart.end(), number, [](std::int64_t n, const Section* s) { return n < s->start; });
        const Section* section = after == byStart.begin() ? nullptr : *(after - 1);
        if (!section || section->end < number)
        {
          this->fail(at, "refers to element " + std::to_string(number) + ", which no section of the zone holds");
        }
        const cgsize_t *first, *last;
        if (section->element(static_cast<std::size_t>(number - section->start), first, last) == CGNS_ENUMV(NFACE_n))
        {
          ++polyhedra;
          return;
        }
        for (const cgsize_t* node = first; node < last; ++node)
        {
          nodes.push_back(zone.offset + *node);
        }
      };
      if (range)
      {
        for (std::int64_t n = std::min(data[0], data[1]); n <= std::max(data[0], data[1]); ++n)
        {
          add(n);
        }
      }
      for (std::size_t k = 0; !range && k < data.size(); ++k)
      {
        add(data[k]);
      }
      if (polyhedra > 0)
      {
        this->warn(at, "its " + std::to_string(polyhedra) + " NFACE_n elements are not supported: their nodes are left out of its set");
      }
      this->bcSets(name, family, nodes);
    }
  }

  // A BC's name, family (or ""), grid location, and its points (index dimension numbers each).
  void boco(int b, int z, int bc, std::size_t dims, const std::string& where, std::string& name, std::string& family,
    CGNS_ENUMT(PointSetType_t) & pointSet, CGNS_ENUMT(GridLocation_t) & location, std::vector<cgsize_t>& data)
  {
    char text[33];
    CGNS_ENUMT(BCType_t) type;
    CGNS_ENUMT(DataType_t) normalType;
    cgsize_t count = 0, normals = 0;
    int normalIndex[3] = {}, datasets = 0;
    const std::string at = where + "/ZoneBC, BC " + std::to_string(bc);
    this->check(cg_boco_info(this->Fn, b, z, bc, text, &type, &pointSet, &count, normalIndex, &normals, &normalType, &datasets), at);
    name = text;
    this->check(cg_boco_gridlocation_read(this->Fn, b, z, bc, &location), at);
    data.resize(static_cast<std::size_t>(count) * dims);
    this->check(cg_boco_read(this->Fn, b, z, bc, data.data(), nullptr), at);
    this->check(cg_goto(this->Fn, b, "Zone_t", z, "ZoneBC_t", 1, "BC_t", bc, "end"), at);
    char familyName[1024] = {};
    family = cg_famname_read(familyName) == CG_OK ? familyName : "";
  }

  // A BC's node set, and its family's.
  void bcSets(const std::string& name, const std::string& family, const std::vector<std::int64_t>& nodes)
  {
    std::vector<std::int64_t>& set = this->NodeSets[name];
    set.insert(set.end(), nodes.begin(), nodes.end());
    if (!family.empty())
    {
      std::vector<std::int64_t>& familySet = this->NodeSets["family/" + family];
      familySet.insert(familySet.end(), nodes.begin(), nodes.end());
    }
  }
};
} // namespace

MeshFile readCgns(const std::string& path)
{
  return std::move(Reader(path, false).Out);
}

MeshFile readCgnsLayout(const std::string& path)
{
  return std::move(Reader(path, true).Out);
}

bool isCgns(const std::string& head)
{
  return head.compare(0, 8, "\x89HDF\r\n\x1a\n") == 0 || head.compare(4, 20, "ADF Database Version") == 0;
}

// ---- the variant -------------------------------------------------------------------------------

namespace
{
// A coordinate array of a zone as it is written: in its data type.
struct Array
{
  std::string path; // "/base/zone/grid/CoordinateX"
  std::vector<std::string> nodes; // the names along it
  std::vector<double> doubles;
  std::vector<float> floats; // RealSingle
};

// A file open in the CGIO layer, closed when done.
struct CgioFile
{
  int cgio = -1;
  ~CgioFile()
  {
    if (this->cgio >= 0)
    {
      cgio_close_file(this->cgio);
    }
  }
};

std::string cgioError()
{
  char message[CGIO_MAX_ERROR_LENGTH + 1] = {};
  cgio_error_message(message);
  return message;
}

// Overwrites each array's values in the file at path (named target in errors), in place: the same
// nodes, types and sizes, only their data changed.
void overwriteCoordinates(const std::string& path, const std::string& target, const std::vector<Array>& arrays)
{
  CgioFile file;
  double root = 0;
  if (cgio_open_file(path.c_str(), CGIO_MODE_MODIFY, CGIO_FILE_NONE, &file.cgio) != CG_OK ||
    cgio_get_root_id(file.cgio, &root) != CG_OK)
  {
    throw FileError(target, 0, "cannot be opened to write its coordinates: " + cgioError());
  }
  for (const Array& array : arrays)
  {
    double id = root;
    for (const std::string& name : array.nodes)
    {
      int link = 0;
      if (cgio_get_node_id(file.cgio, id, name.c_str(), &id) != CG_OK || cgio_is_link(file.cgio, id, &link) != CG_OK)
      {
        throw FileError(target, 0, array.path + ": " + cgioError());
      }
      if (link > 0)
      {
        throw FileError(target, 0, array.path + ": is linked to another file: a variant is written only of coordinates in the file itself");
      }
    }
    char type[CGIO_MAX_DATATYPE_LENGTH + 1] = {};
    int dimensions = 0;
    cgsize_t sizes[CGIO_MAX_DIMENSIONS] = {};
    if (cgio_get_data_type(file.cgio, id, type) != CG_OK || cgio_get_dimensions(file.cgio, id, &dimensions, sizes) != CG_OK)
    {
      throw FileError(target, 0, array.path + ": " + cgioError());
    }
    std::size_t size = 1;
    for (int d = 0; d < dimensions; ++d)
    {
      size *= static_cast<std::size_t>(sizes[d]);
    }
    const bool single = !array.floats.empty();
    if (std::string(type) != (single ? "R4" : "R8") || size != (single ? array.floats.size() : array.doubles.size()))
    {
      throw FileError(target, 0, array.path + ": its data type or size is not the one read (" + type + ")");
    }
    if (cgio_write_all_data(file.cgio, id, single ? static_cast<const void*>(array.floats.data()) : array.doubles.data()) != CG_OK)
    {
      throw FileError(target, 0, array.path + ": cannot be written: " + cgioError());
    }
  }
  const int closed = cgio_close_file(file.cgio);
  file.cgio = -1;
  if (closed != CG_OK)
  {
    throw FileError(target, 0, "cannot be closed after writing its coordinates: " + cgioError());
  }
}

// An ADF file's header holds the time it was last modified ("AdF1" and 28 characters), which the
// library sets as it writes the coordinates: the source's is put back, so that a variant differs
// from its source only in coordinates (and the same variant is the same bytes whenever written).
void keepModificationDate(const std::string& path, const std::string& target, std::string_view source)
{
  const std::size_t field = source.compare(4, 20, "ADF Database Version") == 0 ? source.find("AdF1") : std::string::npos;
  if (field == std::string::npos || field > 256 || field + 4 + 28 > source.size())
  {
    return; // HDF5: no such field
  }
  std::fstream file(path, std::ios::binary | std::ios::in | std::ios::out);
  file.seekp(static_cast<std::streamoff>(field + 4));
  file.write(source.data() + field + 4, 28);
  if (!file.flush())
  {
    throw FileError(target, 0, "cannot be written (its header)");
  }
}
} // namespace

void MeshFile::writeVariant(const std::string& target, const std::int64_t* ids, const double* xyz, std::size_t count,
  bool overwrite) const
{
  VariantSource source = variantSource(target, this->path, this->hash, this->mesh.nodeIds, ids, xyz, count);
  const std::vector<std::size_t>& row = source.row;
  // the new arrays, each in its data type, before anything is written
  std::vector<Array> arrays;
  for (const Zone& zone : this->zones)
  {
    const std::string where = "/" + zone.base + "/" + zone.name + "/" + zone.grid;
    for (std::size_t c = 0; c < zone.coordinates.size(); ++c)
    {
      Array array{ where + "/" + zone.coordinates[c], { zone.base, zone.name, zone.grid, zone.coordinates[c] }, {}, {} };
      for (std::int64_t n = 0; n < zone.nodes; ++n)
      {
        const double value = xyz[3 * row[zone.offset + n] + c];
        if (zone.single[c] && std::abs(value) > FLT_MAX)
        {
          std::string text;
          appendShortest(text, value);
          throw FileError(target, 0, "node " + std::to_string(zone.offset + n + 1) + "'s coordinate " + text + " is beyond the range of " +
              array.path + " (single precision)");
        }
        if (zone.single[c])
        {
          array.floats.push_back(static_cast<float>(value));
        }
        else
        {
          array.doubles.push_back(value);
        }
      }
      arrays.push_back(std::move(array));
    }
    // a 2D zone's nodes stay at z = 0
    for (std::int64_t n = 0; n < zone.nodes && zone.coordinates.size() < 3; ++n)
    {
      const double z = xyz[3 * row[zone.offset + n] + 2];
      if (z != 0)
      {
        std::string text;
        appendShortest(text, z);
        throw FileError(target, 0, "node " + std::to_string(zone.offset + n + 1) + " has z = " + text + ", but " + where +
            " has no CoordinateZ (the zone is 2D)");
      }
    }
  }
  // the source's bytes written aside, their coordinates overwritten there, renamed into place
  AtomicWrite write(overwrite);
  AtomicWrite::Aside out = write.open(target);
  const std::string head(source.file.read(0, std::min<std::size_t>(source.file.size(), 512))); // its date, if ADF
  out.append(head);
  out.copy(source.file, head.size(), source.file.size());
  const std::string aside = write.close(out);
  overwriteCoordinates(aside, target, arrays);
  keepModificationDate(aside, target, head);
  write.commit();
}
} // namespace cgns
} // namespace mlsformats
