// Nastran bulk data without VTK: small, large and free field, Nastran's numbers, coordinate systems,
// every element type's node order and turn, sets, includes; a variant keeps every byte but the moved
// grids' coordinates, written in their systems and field widths; bad decks give the file and line.
#include "../TestHarness.h"
#include "Common/TextFile.h"
#include "FormatFiles.h"
#include "Nastran/NastranDeck.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace fs = std::filesystem;
using namespace mlsformats;

namespace
{
using testing::contains;
using testing::find;
using testing::writeFile;

const testing::TestFolders folder{ "nastran" };
const testing::ReadErrors readError{ nastran::readDeck };

// A small-field entry: 8 columns a field, 8 fields a line, continued on lines marked "+".
std::string smallEntry(const std::string& name, const std::vector<std::string>& fields)
{
  auto column = [](std::string text) {
    text.resize(8, ' ');
    return text;
  };
  std::string out = column(name);
  for (std::size_t i = 0; i < fields.size(); ++i)
  {
    if (i > 0 && i % 8 == 0)
    {
      out += "+\n" + column("+");
    }
    out += column(fields[i]);
  }
  return out + "\n";
}

// Grid id's basic coordinates in mesh.
std::array<double, 3> at(const SourceMesh& mesh, std::int64_t id)
{
  const std::size_t k = static_cast<std::size_t>(std::find(mesh.nodeIds.begin(), mesh.nodeIds.end(), id) - mesh.nodeIds.begin());
  return { mesh.xyz[3 * k], mesh.xyz[3 * k + 1], mesh.xyz[3 * k + 2] };
}

double distance(const std::array<double, 3>& a, const std::array<double, 3>& b)
{
  return std::sqrt((a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]));
}

// The edges VTK's quadratic cells have their midside nodes on, in order.
std::vector<std::array<int, 2>> vtkEdges(CellType type)
{
  switch (type)
  {
    case CellType::QuadraticTriangle: return { { 0, 1 }, { 1, 2 }, { 2, 0 } };
    case CellType::QuadraticQuad: return { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 } };
    case CellType::QuadraticTetra: return { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 0, 3 }, { 1, 3 }, { 2, 3 } };
    case CellType::QuadraticPyramid: return { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 0, 4 }, { 1, 4 }, { 2, 4 }, { 3, 4 } };
    case CellType::QuadraticWedge: return { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 3, 4 }, { 4, 5 }, { 5, 3 }, { 0, 3 }, { 1, 4 }, { 2, 5 } };
    case CellType::QuadraticHexahedron:
      return { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 4, 5 }, { 5, 6 }, { 6, 7 }, { 7, 4 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 } };
    default: return {};
  }
}

// Whether a solid is as VTK 9.2 turns it: the base face's normal towards the other corners (the
// wedge's away from them).
bool turnsAsVTK(const SourceMesh& mesh, CellType type, const std::int64_t* nodes)
{
  const int corners = type == CellType::Tetra || type == CellType::QuadraticTetra ? 4
    : type == CellType::Pyramid || type == CellType::QuadraticPyramid          ? 5
    : type == CellType::Wedge || type == CellType::QuadraticWedge              ? 6
                                                                                : 8;
  const int base = corners == 4 || corners == 6 ? 3 : 4;
  std::vector<std::array<double, 3>> x;
  for (int i = 0; i < corners; ++i)
  {
    x.push_back(at(mesh, nodes[i]));
  }
  std::array<double, 3> u{}, v{}, toward{};
  for (int a = 0; a < 3; ++a)
  {
    u[a] = x[base == 3 ? 1 : 2][a] - x[0][a];
    v[a] = base == 3 ? x[2][a] - x[0][a] : x[3][a] - x[1][a];
    for (int i = 0; i < corners; ++i)
    {
      toward[a] += i < base ? -x[i][a] / base : x[i][a] / (corners - base);
    }
  }
  const double turn =
    (u[1] * v[2] - u[2] * v[1]) * toward[0] + (u[2] * v[0] - u[0] * v[2]) * toward[1] + (u[0] * v[1] - u[1] * v[0]) * toward[2];
  return corners == 6 ? turn < 0 : turn > 0;
}

// A cube's 8 corners and its 12 edges' middles, as CHEXA numbers them (G9-G20: the edges of
// 1-2-3-4, then 1-5 2-6 3-7 4-8, then those of 5-6-7-8), grids first + 0..19.
std::string cubeGrids(int first, double x0)
{
  const double corner[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };
  const int edges[12][2] = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 0, 4 }, { 1, 5 }, { 2, 6 }, { 3, 7 }, { 4, 5 }, { 5, 6 },
    { 6, 7 }, { 7, 4 } };
  std::string out;
  auto grid = [&](int id, double x, double y, double z) {
    out += "GRID," + std::to_string(id) + ",," + std::to_string(x + x0) + "," + std::to_string(y) + "," + std::to_string(z) + "\n";
  };
  for (int i = 0; i < 8; ++i)
  {
    grid(first + i, corner[i][0], corner[i][1], corner[i][2]);
  }
  for (int e = 0; e < 12; ++e)
  {
    const double* a = corner[edges[e][0]];
    const double* b = corner[edges[e][1]];
    grid(first + 8 + e, (a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2);
  }
  return out;
}
} // namespace

TEST(ReadsSmallLargeAndFreeFieldAlike)
{
  // the same four grids and tetrahedron in each format, with Nastran's numbers: "1.", ".5", "1.5-3"
  // (no E), "-.5+2", "1.E0", "1.D0", "+2.5", an integer, a blank (0.)
  const std::string dir = folder("fields");
  const std::string small = "$ small field\n"
                            "GRID    1               0.      0.      0.\n"
                            "GRID    2       0       1.      .5      1.5-3   \n"
                            "grid    3               -.5+2   1.E0    1.D0    $ lower case, a comment\n"
                            "GRID\t4\t\t+2.5\t3\t\t\n" // tabs stop every 8 columns
                            "CTETRA  1       7       1       2       3       4\n";
  const std::string large = "GRID*   1                               0.              0.\n"
                            "*       0.\n"
                            "GRID*   2               0               1.              .5              +\n"
                            "*       1.5-3\n"
                            "GRID*   3                               -.5+2           1.E0\n"
                            "*       1.D0\n"
                            "GRID*   4                               +2.5            3\n"
                            "*\n"
                            "CTETRA  1       7       1       2       3       4\n";
  const std::string free = "GRID,1,,0.,0.,0.\n"
                           "GRID, 2 , 0 , 1. , .5 , 1.5-3\n"
                           "GRID*,3,,-.5+2,1.E0\n"
                           "*,1.D0\n"
                           "GRID,4,,+2.5,3\n" // X3 left out: 0.
                           "CTETRA,1,7,1,2,3,4\n";
  const std::vector<double> expected = { 0, 0, 0, 1, 0.5, 1.5e-3, -50, 1, 1, 2.5, 3, 0 };
  for (const auto& [name, text] : { std::make_pair("small", small), std::make_pair("large", large), std::make_pair("free", free) })
  {
    const nastran::Deck deck = nastran::readDeck(writeFile(dir + "/" + name + ".bdf", text));
    std::printf("%s field\n", name);
    CHECK(deck.mesh.nodeIds == (std::vector<std::int64_t>{ 1, 2, 3, 4 }));
    CHECK(deck.mesh.xyz == expected);
    CHECK(deck.mesh.blocks.size() == 1 && deck.mesh.blocks[0].type == CellType::Tetra && deck.mesh.blocks[0].name == "CTETRA");
    CHECK(deck.mesh.blocks[0].ids == std::vector<std::int64_t>{ 1 });
    CHECK(deck.mesh.elementSets.size() == 1 && deck.mesh.elementSets[0].name == "PID 7");
    CHECK(deck.mesh.warnings.empty());
  }
}

TEST(ElementTypesNodeOrdersAndTurns)
{
  // one element of each type with its grids where the QRG puts them: each quadratic cell's midside
  // nodes at the middles of VTK's edges, each solid turned as VTK's
  const std::string dir = folder("types");
  std::string text = cubeGrids(1, 0); // the unit cube's corners and edge middles, grids 1-20
  text += smallEntry("CHEXA", { "1", "1", "1", "2", "3", "4", "5", "6", "7", "8", "9", "10", "11", "12", "13", "14", "15", "16", "17", "18",
                                "19", "20" });
  text += smallEntry("CHEXA", { "2", "1", "1", "2", "3", "4", "5", "6", "7", "8" });
  // the wedge 1-2-3 / 5-6-7 of the cube (G7-G15: 1-2 2-3 3-1, 1-4 2-5 3-6, 4-5 5-6 6-4 of the wedge)
  text += "GRID,22,,.5,.5,0.\nGRID,24,,.5,.5,1.\n";
  text += smallEntry("CPENTA", { "3", "2", "1", "2", "3", "5", "6", "7", "9", "10", "22", "13", "14", "15", "17", "18", "24" });
  text += smallEntry("CPENTA", { "4", "2", "1", "2", "3", "5", "6", "7" });
  // the tetrahedron 1-2-4-5 (G5-G10: 1-2 2-3 3-1 1-4 2-4 3-4)
  text += "GRID,25,,.5,.5,0.\nGRID,26,,.5,0.,.5\nGRID,27,,0.,.5,.5\n";
  text += "CTETRA,5,3,1,2,4,5,9,25,+\n+,12,13,26,27\n"; // free field too has 8 data fields a line
  text += "CTETRA,6,3,1,2,4,5\n";
  // the pyramid 1-2-3-4 with its apex at the cube's centre (G6-G13: 1-2 2-3 3-4 4-1 1-5 2-5 3-5 4-5)
  text += "GRID,30,,.5,.5,.5\nGRID,31,,.25,.25,.25\nGRID,32,,.75,.25,.25\nGRID,33,,.75,.75,.25\nGRID,34,,.25,.75,.25\n";
  text += smallEntry("CPYRAM", { "7", "4", "1", "2", "3", "4", "30", "9", "10", "11", "12", "31", "32", "33", "34" });
  text += smallEntry("CPYRAM", { "8", "4", "1", "2", "3", "4", "30" });
  text += "CTRIA6,9,5,1,2,3,9,10,25\nCTRIA3,10,5,1,2,3\nCTRIAR,11,5,1,2,3\n";
  text += "CQUAD8,12,6,1,2,3,4,9,10,\n,11,12\n"; // continued after a trailing comma
  text += "CQUAD4,13,6,1,2,3,4,,1.5\nCQUADR,14,6,1,2,3,4\nCSHEAR,15,6,1,2,3,4\n";
  text += "CBAR,16,8,1,2,0.,0.,1.\nCBEAM,17,8,1,2,3\nCROD,18,8,1,2\nCTUBE,19,8,1,2\nCONROD,20,1,2,9\n";
  const nastran::Deck deck = nastran::readDeck(writeFile(dir + "/types.bdf", text));
  const SourceMesh& mesh = deck.mesh;
  for (const std::string& warning : mesh.warnings)
  {
    std::printf("warning: %s\n", warning.c_str());
  }
  CHECK(mesh.warnings.empty());
  const std::map<std::string, std::vector<CellType>> expected = { { "CHEXA", { CellType::QuadraticHexahedron, CellType::Hexahedron } },
    { "CPENTA", { CellType::QuadraticWedge, CellType::Wedge } }, { "CTETRA", { CellType::QuadraticTetra, CellType::Tetra } },
    { "CPYRAM", { CellType::QuadraticPyramid, CellType::Pyramid } }, { "CTRIA6", { CellType::QuadraticTriangle } },
    { "CTRIA3", { CellType::Triangle } }, { "CTRIAR", { CellType::Triangle } }, { "CQUAD8", { CellType::QuadraticQuad } },
    { "CQUAD4", { CellType::Quad } }, { "CQUADR", { CellType::Quad } }, { "CSHEAR", { CellType::Quad } }, { "CBAR", { CellType::Line } },
    { "CBEAM", { CellType::Line } }, { "CROD", { CellType::Line } }, { "CTUBE", { CellType::Line } }, { "CONROD", { CellType::Line } } };
  std::map<std::string, std::vector<CellType>> found;
  std::size_t cells = 0;
  for (const ElementBlock& block : mesh.blocks)
  {
    found[block.name].push_back(block.type);
    cells += block.ids.size();
    const int perCell = nodesPerCell(block.type);
    CHECK(block.nodes.size() == block.ids.size() * static_cast<std::size_t>(perCell));
    const std::vector<std::array<int, 2>> edges = vtkEdges(block.type);
    for (std::size_t e = 0; e < block.ids.size(); ++e)
    {
      const std::int64_t* nodes = &block.nodes[e * perCell];
      const int corners = perCell - static_cast<int>(edges.size());
      for (std::size_t m = 0; m < edges.size(); ++m)
      {
        const std::array<double, 3> a = at(mesh, nodes[edges[m][0]]), b = at(mesh, nodes[edges[m][1]]);
        const std::array<double, 3> middle = { (a[0] + b[0]) / 2, (a[1] + b[1]) / 2, (a[2] + b[2]) / 2 };
        if (distance(at(mesh, nodes[corners + m]), middle) > 1e-12)
        {
          std::printf("%s %lld: node %zu is not on VTK's edge %d-%d\n", block.name.c_str(), static_cast<long long>(block.ids[e]),
            corners + m, edges[m][0], edges[m][1]);
          CHECK(false);
        }
      }
      if (block.name == "CHEXA" || block.name == "CPENTA" || block.name == "CTETRA" || block.name == "CPYRAM")
      {
        CHECK(turnsAsVTK(mesh, block.type, nodes));
      }
    }
  }
  CHECK(found == expected);
  CHECK(cells == 20);
  // the wedge is given as Gmsh writes it (1-2-3 turning towards 4-5-6): VTK's turns the other way
  CHECK(mesh.blocks[3].name == "CPENTA" && mesh.blocks[3].nodes == (std::vector<std::int64_t>{ 1, 3, 2, 5, 7, 6 }));
  // property sets (CONROD has none)
  const NamedSet* solids = find(mesh.elementSets, "PID 1");
  CHECK(solids && solids->ids == (std::vector<std::int64_t>{ 1, 2 }));
  CHECK(find(mesh.elementSets, "PID 8") && find(mesh.elementSets, "PID 8")->ids.size() == 4);
}

TEST(SolidsGivenEitherWayTurnAsVTKs)
{
  // Nastran takes a solid's grids turned either way (the QRG asks their topology only): each is
  // read as VTK's, a mirrored one reordered
  const std::string dir = folder("turns");
  std::string text = cubeGrids(1, 0) + cubeGrids(101, 2);
  text += smallEntry("CHEXA", { "1", "1", "1", "2", "3", "4", "5", "6", "7", "8" });
  text += smallEntry("CHEXA", { "2", "1", "101", "104", "103", "102", "105", "108", "107", "106" });
  text += smallEntry("CHEXA", { "3", "1", "101", "104", "103", "102", "105", "108", "107", "106", "112", "111", "110", "109", "113",
                                "116", "115", "114", "120", "119", "118", "117" });
  text += "CTETRA,4,1,1,2,4,5\nCTETRA,5,1,1,4,2,5\nCPENTA,6,1,1,2,4,5,6,8\nCPENTA,7,1,1,4,2,5,8,6\n";
  text += "CPYRAM,8,1,1,2,3,4,5\nCPYRAM,9,1,1,4,3,2,5\n";
  const nastran::Deck deck = nastran::readDeck(writeFile(dir + "/turns.bdf", text));
  for (const ElementBlock& block : deck.mesh.blocks)
  {
    const int perCell = nodesPerCell(block.type);
    for (std::size_t e = 0; e < block.ids.size(); ++e)
    {
      CHECK(turnsAsVTK(deck.mesh, block.type, &block.nodes[e * perCell]));
    }
  }
  // the mirrored hexahedron 20 keeps its midside nodes on its edges
  const ElementBlock& quadratic = deck.mesh.blocks[1];
  CHECK(quadratic.type == CellType::QuadraticHexahedron);
  CHECK(quadratic.nodes == (std::vector<std::int64_t>{ 101, 102, 103, 104, 105, 106, 107, 108, 109, 110, 111, 112, 117, 118, 119, 120, 113,
                             114, 115, 116 }));
}

TEST(GridsInCoordinateSystemsReadAtTheirBasicPlace)
{
  const std::string dir = folder("systems");
  // 3: rectangular at (1, 2, 3), x along (1, 1, 0); 7: cylindrical in 3; 9: spherical; 11: through grids
  const std::string text = "CORD2R  3               1.      2.      3.      1.      2.      4.      +\n"
                           "+       2.      3.      3.\n"
                           "CORD2C,7,3,0.,0.,0.,0.,0.,1.\n,1.,0.,0.\n"
                           "CORD2S*               9               0              0.              0.\n"
                           "*                     0.              0.              0.              1.\n"
                           "*                     1.              0.              0.\n"
                           "CORD1R,11,12,5,6\n"
                           "GRID,1,7,2.,30.,.5\n"
                           "GRID,2,9,1.,60.,45.\n"
                           "GRID,3,11,1.,2.,3.\n"
                           "GRID,4,,10.,0.,0.\nGRID,5,0,10.,0.,1.\nGRID,6,0,11.,0.,0.\nGRID,12,0,10.,0.,0.\n"
                           "GRID,8,,0.,0.,0.\n"
                           "GRDSET,,3\n"; // a blank CP is 3's, after it too
  const nastran::Deck deck = nastran::readDeck(writeFile(dir + "/systems.bdf", text));
  const SourceMesh& mesh = deck.mesh;
  const double s = std::sqrt(0.5);
  // in 3: x = sqrt(3), y = 1 (r = 2 at 30 degrees), z = .5
  const std::array<double, 3> one = { 1 + (std::sqrt(3.0) - 1) * s, 2 + (std::sqrt(3.0) + 1) * s, 3.5 };
  CHECK(distance(at(mesh, 1), one) < 1e-14);
  CHECK(distance(at(mesh, 2), { std::sin(M_PI / 3) * s, std::sin(M_PI / 3) * s, 0.5 }) < 1e-15);
  CHECK(distance(at(mesh, 3), { 11, 2, 3 }) < 1e-15);
  CHECK(distance(at(mesh, 4), { 1 + 10 * s, 2 + 10 * s, 3 }) < 1e-14); // GRDSET's CP
  CHECK(distance(at(mesh, 5), { 10, 0, 1 }) == 0 && distance(at(mesh, 8), { 1, 2, 3 }) < 1e-15);
  CHECK(deck.systems.size() == 5);
  // pyNastran's test_coords.py (test_cord2_rcs_01 to 03, from MSC Nastran): systems of each type
  // defined in each type, a grid in each, every one at (30, 40, 50); moved, each is written in its
  // system and read back where it moved
  const std::string chained = writeFile(dir + "/chained.bdf", R"(CORD2R*               10               0             10.              5.
*                     3.   10.3420201433   4.53015368961   3.81379768136*       
*          10.7198463104   5.68767171433   3.09449287122
CORD2C*               11               0              7.              3.
*                     9.   7.64278760969   2.73799736977   9.71984631039*       
*          7.75440650673   3.37968226211   8.46454486422
CORD2S*               12               0             12.              8.
*                     5.   12.6427876097   7.86697777844   5.75440650673*       
*          12.6634139482   8.58906867688   4.53861076379
GRID*                 10              10   42.9066011565   34.2422137135
*          28.6442730262               0
GRID*                 11              11   48.8014631871   78.8394787869
*          34.6037164304               0
GRID*                 12              12   58.0775343829   44.7276544324
*          75.7955331161               0
CORD2C*                1               0              0.              0.
*                     0.              0.              0.              1.*       
*                     1.              0.              1.
CORD2R*               20               1              7.             20.
*                    -6.   7.07106781187   28.1301023542             -6.*       
*          7.70710678119             20.  -5.29289321881
CORD2C*               21               1             15.            -30.
*                    12.   14.6565766735  -30.3177805524   12.9355733712*       
*          14.6234241583  -26.4257323272   11.9304419665
CORD2S*               22               1              5.            -75.
*                    20.   5.66032384035  -82.9319986389   19.8502545865*       
*          4.88876051026  -73.8006653677   19.0116094889
GRID*                 20              20   64.2559135157  -14.9400459772
*          27.3271005317               0
GRID*                 21              21   52.8328862418  -28.8729017195
*           34.615939507               0
GRID*                 22              22   61.1042111232   158.773483595
*           -167.4951724               0
CORD2S*                2               0              0.              0.
*                     0.              0.              0.              1.*       
*                     1.              0.              1.
CORD2R*               30               2             14.             30.
*                    70.    13.431863852   32.1458443949   75.2107442927*       
*          14.4583462334   33.4569982885   68.2297989286
CORD2C*               31               2              3.             42.
*                  -173.   2.86526881213   45.5425615252   159.180363517*       
*          3.65222385965   29.2536614627  -178.631312271
CORD2S*               32               2             22.             14.
*                    85.   22.1243073983   11.9537753718   77.9978191005*       
*          21.0997242967   13.1806120497   88.4824763008
GRID*                 30              30   40.7437952957  -23.6254877994
*           -33.09784854               0
GRID*                 31              31   62.9378078196   15.9774797923
*          31.0484428362               0
GRID*                 32              32   53.8270847449   95.8215692632
*          159.097767463               0
)");
  const nastran::Deck rcs = nastran::readDeck(chained);
  CHECK(rcs.mesh.nodeIds.size() == 9 && rcs.systems.size() == 12);
  std::vector<double> moved;
  for (std::size_t k = 0; k < rcs.mesh.nodeIds.size(); ++k)
  {
    CHECK(distance(at(rcs.mesh, rcs.mesh.nodeIds[k]), { 30, 40, 50 }) < 1e-8); // their 12 digits
    moved.insert(moved.end(), { 31, 41.5, 49 - 0.1 * k });
  }
  rcs.writeVariant(dir + "/v/chained.bdf", rcs.mesh.nodeIds.data(), moved.data(), 9, false);
  const nastran::Deck back = nastran::readDeck(dir + "/v/chained.bdf");
  for (std::size_t i = 0; i < moved.size(); ++i)
  {
    CHECK_NEAR(back.mesh.xyz[i], moved[i], 1e-12 * 50);
  }
  // chains are followed, cycles and undefined systems refused
  CHECK(contains(readError(writeFile(dir + "/cycle.bdf", "CORD2R,1,2,0.,0.,0.,0.,0.,1.\n,1.,0.,0.\n"
                                                         "CORD2R,2,1,0.,0.,0.,0.,0.,1.\n,1.,0.,0.\n"
                                                         "GRID,1,1,0.,0.,0.\n")),
    "cycle.bdf:1: CORD2R 1 is defined through itself"));
  CHECK(contains(readError(writeFile(dir + "/undefined.bdf", "GRID,1,,0.,0.,0.\nGRID,2,5,0.,0.,0.\n")),
    "undefined.bdf:2: GRID 2's CP 5 is not defined"));
  CHECK(contains(readError(writeFile(dir + "/rid.bdf", "CORD2C,4,8,0.,0.,0.,0.,0.,1.\n,1.,0.,0.\nGRID,1,4,1.,0.,0.\n")),
    "rid.bdf:1: CORD2C 4's RID 8 is not defined"));
  CHECK(contains(readError(writeFile(dir + "/cord3.bdf", "CORD3G,4,EQN,2\nGRID,1,4,1.,0.,0.\n")),
    "cord3.bdf:2: GRID 1's CP 4 is a CORD3G: only CORD1R/C/S and CORD2R/C/S are supported"));
  CHECK(contains(readError(writeFile(dir + "/line.bdf", "CORD2R,4,,0.,0.,0.,0.,0.,1.\n,0.,0.,2.\nGRID,1,4,1.,0.,0.\n")),
    "line.bdf:1: CORD2R 4's points A, B and C are on one line"));
  CHECK(contains(readError(writeFile(dir + "/twice.bdf", "CORD2R,4,,0.,0.,0.,0.,0.,1.\n,1.,0.,0.\n"
                                                         "CORD2C,4,,0.,0.,0.,0.,0.,1.\n,1.,0.,0.\n")),
    "twice.bdf:3: coordinate system 4 is defined twice (first by the CORD2R at"));
  CHECK(contains(readError(writeFile(dir + "/self.bdf", "CORD1R,4,1,2,3\nGRID,1,4,0.,0.,0.\nGRID,2,,0.,0.,1.\nGRID,3,,1.,0.,0.\n")),
    "self.bdf:2: GRID 1's position depends on itself"));
}

TEST(MovedGridIsWrittenInItsSystem)
{
  // moved grids in cylindrical and spherical systems are written back in them (free and large field:
  // their basic place to 1e-12; small field: to its 8 characters), each field in its own width
  const std::string dir = folder("cylindrical");
  const std::string source = writeFile(dir + "/deck.bdf", "CORD2C,7,,1.,2.,3.,1.,2.,4.\n,2.,2.,3.\n"
                                                          "CORD2S,9,7,0.,0.,0.,0.,0.,1.\n,1.,0.,0.\n"
                                                          "GRID,1,7,2.,350.,.5,,123456\n"
                                                          "GRID*   2               7               1.              30.             +\n"
                                                          "*       -1.                             345\n"
                                                          "GRID    3       9       2.      60.     -30.    $ in 9, in 7\n"
                                                          "GRID,4,0,0.,0.,0.\n");
  const nastran::Deck deck = nastran::readDeck(source);
  std::vector<double> xyz = deck.mesh.xyz;
  const std::vector<double> moved = { 1.4, 1.93, 3.7, 4, -1.0 / 7, 2.2, 0.3, 2.7, 4.4 };
  std::copy(moved.begin(), moved.end(), xyz.begin());
  deck.writeVariant(dir + "/v/deck.bdf", deck.mesh.nodeIds.data(), xyz.data(), 4, false);
  const std::string text = readFile(dir + "/v/deck.bdf");
  std::printf("%s", text.c_str());
  const nastran::Deck again = nastran::readDeck(dir + "/v/deck.bdf");
  for (int i = 0; i < 6; ++i)
  {
    CHECK_NEAR(again.mesh.xyz[i], moved[i], 1e-12 * 5);
  }
  for (int i = 6; i < 9; ++i)
  {
    CHECK_NEAR(again.mesh.xyz[i], moved[i], 1e-5 * 5);
  }
  CHECK(again.mesh.xyz[9] == 0 && again.mesh.xyz[11] == 0);
  // the other fields as they were; an angle in [0, 360) when it was (350, not -10)
  const std::vector<Line> lines = mlsformats::lines(text);
  const std::string grid1 = text.substr(lines[4].begin, lines[4].end - lines[4].begin);
  CHECK(grid1.compare(0, 9, "GRID,1,7,") == 0 && contains(grid1, ",,123456"));
  const double theta = std::stod(grid1.substr(grid1.find(',', 9) + 1));
  CHECK(theta > 180 && theta < 360);
  CHECK(contains(text, "GRID*   2               7               "));
  const std::string continuation = text.substr(lines[6].begin, lines[6].end - lines[6].begin);
  CHECK(continuation.compare(0, 8, "*       ") == 0 && continuation.substr(24) == "                345");
  const std::string grid3 = text.substr(lines[7].begin, lines[7].end - lines[7].begin);
  CHECK(grid3.compare(0, 24, "GRID    3       9       ") == 0 && contains(grid3, "$ in 9, in 7") && grid3.find('$') == 48);
  CHECK(text.substr(lines[8].begin) == "GRID,4,0,0.,0.,0.\n");
}

TEST(WrittenNumbersFitTheirFields)
{
  // small field: 8 characters, Nastran's forms ("1.2346-5", without E) for as many digits as fit;
  // large field: 16; free field: the shortest text that reads back exactly
  const std::string dir = folder("widths");
  const std::string source = writeFile(dir + "/deck.bdf", "GRID    1               0.      0.      0.\n"
                                                          "GRID    2               0.      0.      0.\n"
                                                          "GRID*   3                               0.              0.\n*       0.\n"
                                                          "GRID,4,,0.,0.,0.\n");
  const nastran::Deck deck = nastran::readDeck(source);
  const double xyz[12] = { 1.2345678901234567e-05, -0.123456789, -123456.789, 1.0 / 3, 5, -2e-300, 1.0 / 3, -1.2345678901234567e-10, 1e10,
    1.0 / 3, -1.2345678901234567e-10, 2.5e-7 };
  deck.writeVariant(dir + "/v/deck.bdf", deck.mesh.nodeIds.data(), xyz, 4, false);
  const std::string text = readFile(dir + "/v/deck.bdf");
  std::printf("%s", text.c_str());
  CHECK(text == "GRID    1               1.2346-5-.123457-123457.\n"
                "GRID    2               .33333335.      -2.-300\n"
                "GRID*   3                               .333333333333333-.123456789012-9\n*       1.+10\n"
                "GRID,4,,.3333333333333333,-.12345678901234568-9,2.5-7\n");
  const nastran::Deck again = nastran::readDeck(dir + "/v/deck.bdf");
  for (int i = 0; i < 6; ++i)
  {
    CHECK(std::abs(again.mesh.xyz[i] - xyz[i]) <= 5e-5 * std::abs(xyz[i]));
  }
  for (int i = 6; i < 9; ++i)
  {
    CHECK(std::abs(again.mesh.xyz[i] - xyz[i]) <= 5e-11 * std::abs(xyz[i]));
  }
  for (int i = 9; i < 12; ++i)
  {
    CHECK(again.mesh.xyz[i] == xyz[i]);
  }
}

TEST(IncludesControlStatementsAndVariantKeepingEveryOtherByte)
{
  // executive and case control statements are skipped (through an include too), INCLUDE 'name' is
  // read relative to the deck's folder (its name continued on a line), ENDDATA ends the deck
  const std::string dir = folder("include");
  writeFile(dir + "/case.inc", "DISP = ALL\n  SET 1 = 1, 2\n");
  const std::string grids = "$ the grids\nGRID    1               0.      0.      0.\nGRID    2               1.      0.      0.\n"
                            "GRID    3               0.      1.      0.\nGRID    4               0.      0.      1.\n";
  writeFile(dir + "/mesh/grids.bdf", grids);
  const std::string source = writeFile(dir + "/deck.dat", "SOL 101\nCEND\nTITLE = a tetrahedron\nINCLUDE 'case.inc'\n"
                                                          "SUBCASE 1\n  LOAD = 1\nBEGIN BULK\n"
                                                          "INCLUDE 'mesh/\n"
                                                          "        grids.bdf'\n"
                                                          "CTETRA  1       1       1       2       3       4\n"
                                                          "PSOLID  1       1\nMAT1    1       210000.         .3\n"
                                                          "ENDDATA\nGRID    9 after ENDDATA: not read\n");
  const nastran::Deck deck = nastran::readDeck(source);
  CHECK(deck.files.size() == 3 && deck.includeNames[1] == "case.inc" && deck.includeNames[2] == "mesh/grids.bdf");
  CHECK(deck.mesh.nodeIds == (std::vector<std::int64_t>{ 1, 2, 3, 4 }) && deck.mesh.blocks.size() == 1);
  CHECK(deck.mesh.warnings.empty());
  // the same coordinates: the same bytes
  deck.writeVariant(dir + "/same/deck.dat", deck.mesh.nodeIds.data(), deck.mesh.xyz.data(), 4, false);
  CHECK(readFile(dir + "/same/deck.dat") == readFile(source));
  CHECK(readFile(dir + "/same/mesh/grids.bdf") == grids && readFile(dir + "/same/case.inc") == readFile(dir + "/case.inc"));
  // grid 3 moved, the data in reverse order: its line only
  std::vector<std::int64_t> ids = { 4, 3, 2, 1 };
  std::vector<double> xyz = { 0, 0, 1, 0.25, 1, -0.5, 1, 0, 0, 0, 0, 0 };
  deck.writeVariant(dir + "/moved/deck.dat", ids.data(), xyz.data(), 4, false);
  std::string expected = grids;
  const std::string line3 = "GRID    3               0.      1.      0.";
  expected.replace(expected.find(line3), line3.size(), "GRID    3               .25     1.      -.5");
  CHECK(readFile(dir + "/moved/mesh/grids.bdf") == expected);
  CHECK(readFile(dir + "/moved/deck.dat") == readFile(source));
  // the layout alone writes the same variant
  const nastran::Deck layout = nastran::readNodeLayout(source);
  CHECK(layout.mesh.nodeIds == deck.mesh.nodeIds && layout.mesh.blocks.empty() && layout.mesh.xyz.empty());
  layout.writeVariant(dir + "/layout/deck.dat", ids.data(), xyz.data(), 4, false);
  CHECK(readFile(dir + "/layout/mesh/grids.bdf") == expected);
}

TEST(SetsOfPropertiesRigidElementsAndConstraints)
{
  const std::string dir = folder("sets");
  std::string text;
  for (int id = 1; id <= 12; ++id)
  {
    text += "GRID," + std::to_string(id) + ",," + std::to_string(id) + ".,0.,0.\n";
  }
  text += "CROD,1,5,1,2\nCROD,2,6,2,3\nCROD,3,5,3,4\nCROD,4,,4,5\n" // a blank PID is the element's id
          "RBE2,10,6,123456,7,8,9,1.-6\n"
          "RBE3,11,,12,123,1.,123,9,10,+\n+,2.,12,11,UM,10,1\n"
          "SPC1,100,123,1,2,3\nSPC1,100,456,3,THRU,6\nSPC1,200,1,2,THRU,99999999999\nSPC1,300,1,77\n";
  const nastran::Deck deck = nastran::readDeck(writeFile(dir + "/sets.bdf", text));
  const SourceMesh& mesh = deck.mesh;
  const NamedSet* five = find(mesh.elementSets, "PID 5");
  CHECK(five && five->ids == (std::vector<std::int64_t>{ 1, 3 }));
  const NamedSet* four = find(mesh.elementSets, "PID 4");
  CHECK(find(mesh.elementSets, "PID 6") && four && four->ids == std::vector<std::int64_t>{ 4 });
  const NamedSet* rbe2 = find(mesh.nodeSets, "RBE2");
  CHECK(rbe2 && rbe2->ids == (std::vector<std::int64_t>{ 6, 7, 8, 9 }));
  const NamedSet* rbe3 = find(mesh.nodeSets, "RBE3");
  CHECK(rbe3 && rbe3->ids == (std::vector<std::int64_t>{ 12, 9, 10, 11 }));
  const NamedSet* spc = find(mesh.nodeSets, "SPC1 100");
  CHECK(spc && spc->ids == (std::vector<std::int64_t>{ 1, 2, 3, 4, 5, 6 }));
  const NamedSet* wide = find(mesh.nodeSets, "SPC1 200");
  CHECK(wide && wide->ids.size() == 11);
  for (const std::string& warning : mesh.warnings)
  {
    std::printf("warning: %s\n", warning.c_str());
  }
  CHECK(mesh.warnings.size() == 1 && contains(mesh.warnings[0], "sets.bdf:23: grid 77 is not in the deck: left out of set SPC1 300"));
}

TEST(OtherElementsAreLeftOutWithAWarning)
{
  const std::string dir = folder("others");
  const nastran::Deck deck = nastran::readDeck(writeFile(dir + "/others.bdf", "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\n"
                                                                             "$ a spring\n"
                                                                             "CBUSH,1,2,1,2,,1.,0.,0.\n"
                                                                             "CONM2,2,3,,1.\n"
                                                                             "CTRIA3,3,1,1,2,3\n"
                                                                             "CBUSH,4,2,2,3,,1.,0.,0.\n"
                                                                             "CTRIA6,5,1,1,2,3,,,4\n"
                                                                             "GRID,4,,.5,.5,0.\n"));
  for (const std::string& warning : deck.mesh.warnings)
  {
    std::printf("warning: %s\n", warning.c_str());
  }
  CHECK(deck.mesh.warnings.size() == 2);
  CHECK(contains(deck.mesh.warnings[0], "others.bdf:5: CBUSH (2 entries, the first here) is not read as cells"));
  CHECK(contains(deck.mesh.warnings[1], "others.bdf:9: CTRIA6 with some of its edge grids is not read as cells"));
  CHECK(deck.mesh.blocks.size() == 1 && deck.mesh.nodeIds.size() == 4);
}

TEST(BadDecksNameTheFileAndTheLine)
{
  const std::string dir = folder("bad");
  const std::string grids = "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\nGRID,4,,0.,0.,1.\n";
  CHECK(contains(readError(writeFile(dir + "/number.bdf", "GRID,1,,0.,0.,0.\nGRID,2,,1.0.0,0.,0.\n")),
    "number.bdf:2: GRID 2's X1 \"1.0.0\" is not a finite number"));
  CHECK(contains(readError(writeFile(dir + "/nan.bdf", "GRID    1               NaN     0.      0.\n")), "nan.bdf:1: GRID 1's X1 \"NaN\""));
  CHECK(contains(readError(writeFile(dir + "/huge.bdf", "GRID,1,,1.+400,0.,0.\n")), "huge.bdf:1: GRID 1's X1"));
  CHECK(contains(readError(writeFile(dir + "/id.bdf", "GRID,x1,,0.,0.,0.\n")), "id.bdf:1: GRID's id \"x1\" is not a positive integer"));
  CHECK(contains(readError(writeFile(dir + "/include.bdf", "BEGIN BULK\nINCLUDE 'gone.bdf'\n")), "include.bdf:2: INCLUDE 'gone.bdf': "));
  CHECK(contains(readError(writeFile(dir + "/self.bdf", "INCLUDE 'self.bdf'\n")), "nested more than 20 deep"));
  CHECK(contains(readError(writeFile(dir + "/twice.bdf", grids + "GRID,3,,5.,5.,5.\n")), "twice.bdf:5: GRID 3 is defined twice"));
  CHECK(contains(readError(writeFile(dir + "/missing.bdf", grids + "$\nCTETRA,1,1,1,2,3,9\n")),
    "missing.bdf:6: CTETRA 1 refers to grid 9, which the deck does not define"));
  CHECK(contains(readError(writeFile(dir + "/corner.bdf", grids + "CTETRA,1,1,1,2,3\n")), "corner.bdf:5: CTETRA 1's G4 is blank"));
  CHECK(contains(readError(writeFile(dir + "/eltwice.bdf", grids + "CTETRA,1,1,1,2,3,4\nCTRIA3,1,1,1,2,3\n")),
    "eltwice.bdf:6: element 1 is defined twice"));
  CHECK(contains(readError(writeFile(dir + "/super.bdf", "BEGIN BULK\n" + grids + "BEGIN SUPER=2\n" + grids)),
    "super.bdf:6: BEGIN SUPER=2: part superelements and auxiliary models are not supported"));
  CHECK(contains(readError(writeFile(dir + "/orphan.bdf", "        1       2\n" + grids)),
    "orphan.bdf:1: a continuation line with no entry"));
  CHECK(contains(readError(writeFile(dir + "/wide.bdf", "CTETRA,1,1,1,2,3,4,5,6,+,7\n")), "wide.bdf:1: more than 8 data fields"));
  CHECK(contains(readError(writeFile(dir + "/half.bdf", "GRID*   1                               0.              0.\n")),
    "half.bdf:1: GRID* 1 has no continuation line (its X3)"));
  CHECK(contains(readError(writeFile(dir + "/quote.bdf", "INCLUDE 'a.bdf\n")), "quote.bdf:1: INCLUDE's file name has no closing quote"));
  CHECK(contains(readError(dir + "/none.bdf"), "none.bdf: cannot be read"));
}

TEST(VariantRefusesOtherDataAndNeverHalfWrites)
{
  const std::string dir = folder("refuse");
  writeFile(dir + "/mesh/grids.bdf", "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\n");
  const std::string source = writeFile(dir + "/deck.bdf", "INCLUDE 'mesh/grids.bdf'\nCROD,1,1,1,2\n");
  const nastran::Deck deck = nastran::readDeck(source);
  // a variant whose include would go onto the source's include
  CHECK(contains(testing::writeError(deck, dir + "/other.bdf", deck.mesh.nodeIds, deck.mesh.xyz, true),
    dir + "/mesh/grids.bdf: is a file of the source " + source + ": a variant is written elsewhere"));
  CHECK(!fs::exists(dir + "/other.bdf"));
  // the refusals of every format; the grids' include changed since it was read
  testing::checkVariantRefusals(deck, source, dir, "$ edited\n", dir + "/mesh/grids.bdf");
  // grids in an include named by its absolute path
  const std::string absolute = writeFile(dir + "/absolute.bdf", "INCLUDE '" + fs::absolute(dir + "/mesh/grids.bdf").string() + "'\n");
  const nastran::Deck outside = nastran::readDeck(absolute);
  CHECK_THROWS(outside.writeVariant(dir + "/d/v.bdf", outside.mesh.nodeIds.data(), outside.mesh.xyz.data(), 2, false), FileError);
}

TEST(RecognizedByContent)
{
  // a .dat file may be anything: Nastran's is told by its statements
  CHECK(nastran::isNastran("$ Created by Gmsh\nGRID,1,0,0.00E+00,0.00E+00,0.300000\n"));
  CHECK(nastran::isNastran("$ Created by Gmsh\nGRID*   1               0               0               0\n"));
  CHECK(nastran::isNastran("$ meshio\nBEGIN BULK\nGRID    1               0.      0.      0.\n"));
  CHECK(nastran::isNastran("ID job\nSOL 101\nTIME 10\nCEND\nTITLE = x\n"));
  CHECK(nastran::isNastran("$ elements first\nCHEXA   1       1       1       2       3       4       5       6       +\n"));
  CHECK(nastran::isNastran("INIT MASTER(S)\nSOL SESTATIC\n"));
  CHECK(!nastran::isNastran("*HEADING\n*NODE\n1, 0., 0., 0.\n"));
  CHECK(!nastran::isNastran(" displacements (vx,vy,vz) for set NALL and time  0.1000000E+01\n         1  0.0  0.0  0.0\n"));
  CHECK(!nastran::isNastran("TITLE = \"tecplot\"\nVARIABLES = \"X\", \"Y\"\nZONE I=2\n1.0 2.0\n"));
  CHECK(!nastran::isNastran("GRID,X,Y,Z\n0.5,1.0,2.0\n"));
  CHECK(!nastran::isNastran("1 2 3\n4 5 6\n"));
  CHECK(!nastran::isNastran(""));
}

TEST_MAIN
