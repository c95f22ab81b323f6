// Abaqus/CalculiX decks without VTK: every element type, sets, surfaces, includes; a variant keeps
// every byte but the moved coordinates; bad decks give an error naming the file and the line.
#include "../TestHarness.h"
#include "Abaqus/AbaqusDeck.h"
#include "Common/TextFile.h"
#include "FormatFiles.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace fs = std::filesystem;
using namespace mlsformats;

namespace
{
using testing::contains;
using testing::find;
using testing::writeFile;

const testing::TestFolders folder{ "abaqus" };
const testing::ReadErrors readError{ abaqus::readDeck };

std::vector<std::int64_t> sorted(std::vector<std::int64_t> ids)
{
  std::sort(ids.begin(), ids.end());
  return ids;
}

// A deck of one hexahedron C3D20 (nodes 1-20 of the unit cube), a C3D10 tetrahedron on its side,
// written as Abaqus users write decks: mixed case, comments, continued lines, an include inside *NODE.
const char* const cubeNodes = "1, 0., 0., 0.\n2, 1., 0., 0.\n3, 1., 1., 0.\n4, 0., 1., 0.\n"
                              "5, 0., 0., 1.\n6, 1., 0., 1.\n7, 1., 1., 1.\n8, 0., 1., 1.\n"
                              "9, 0.5, 0, 0\n10, 1, 0.5, 0\n11, 0.5, 1, 0\n12, 0, 0.5, 0\n"
                              "13, 0.5, 0, 1\n14, 1, 0.5, 1\n15, 0.5, 1, 1\n16, 0, 0.5, 1\n"
                              "17, 0, 0, 0.5\n18, 1, 0, 0.5\n19, 1, 1, 0.5\n20, 0, 1, 0.5\n";

std::string cubeDeck(const std::string& dir)
{
  writeFile(dir + "/mesh/nodes.inp", cubeNodes);
  return writeFile(dir + "/cube.inp", "*Heading\n a cube\n** a comment line\n"
                                      "*NODE, NSET=all\n"
                                      "*include, input=mesh/nodes.inp\n"
                                      "  21 ,  2.0D0 , 0.0 , 0.0\n" // Fortran's exponent, blanks around fields
                                      "22, 2.0, 1.0, 0.0\n23, 2.0, 0.0, 1.0\n"
                                      "24, 1.5, 0, 0\n25, 1.5, 0.5, 0\n26, 1, 0.5, 0.25\n"
                                      "27, 1.5, 0, 0.5\n28, 1.5, 0.5, 0.5\n29, 1, 0.25, 0.5\n"
                                      "*Element, type=C3D20R,\n ELSET=cube\n"
                                      "1, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15,\n"
                                      "16, 17, 18, 19, 20\n"
                                      "*ELEMENT, TYPE=C3D10, ELSET=tip\n"
                                      "2, 2, 21, 22, 23, 24, 25, 26, 27, 28, 29\n"
                                      "*nset, nset=bottom, generate\n1, 4\n9, 12, 1\n"
                                      "*NSET, NSET=pair\n21, 22,\n"
                                      "*NSET, NSET=both\nbottom, pair\n"
                                      "*ELSET, ELSET=solid\ncube, tip\n"
                                      "*NSET, NSET=tipnodes, ELSET=tip\n"
                                      "*SURFACE, NAME=top, TYPE=ELEMENT\ncube, S2\n"
                                      "*SURFACE, NAME=base\n2, S1\n"
                                      "*MATERIAL, NAME=steel\n*ELASTIC\n210000, 0.3\n"
                                      "*STEP\n*STATIC\n*BOUNDARY\nbottom, 1, 3\n*END STEP\n");
}
} // namespace

TEST(ReadsNodesElementsSetsAndSurfaces)
{
  const std::string dir = folder("read");
  const abaqus::Deck deck = abaqus::readDeck(cubeDeck(dir));
  const SourceMesh& mesh = deck.mesh;
  CHECK(deck.files.size() == 2);
  CHECK(deck.includeNames.size() == 2 && deck.includeNames[1] == "mesh/nodes.inp");
  CHECK(mesh.nodeIds.size() == 29);
  CHECK(mesh.xyz.size() == 3 * 29);
  CHECK(mesh.nodeIds[20] == 21 && mesh.xyz[60] == 2.0);
  CHECK(mesh.xyz[3 * 6 + 0] == 1.0 && mesh.xyz[3 * 6 + 1] == 1.0 && mesh.xyz[3 * 6 + 2] == 1.0);
  CHECK(mesh.blocks.size() == 2);
  CHECK(mesh.blocks[0].type == CellType::QuadraticHexahedron && mesh.blocks[0].name == "C3D20R");
  CHECK(mesh.blocks[0].ids == std::vector<std::int64_t>{ 1 });
  CHECK(mesh.blocks[0].nodes.size() == 20 && mesh.blocks[0].nodes[15] == 16 && mesh.blocks[0].nodes[19] == 20);
  CHECK(mesh.blocks[1].type == CellType::QuadraticTetra && mesh.blocks[1].nodes.size() == 10);
  CHECK(mesh.warnings.empty());
  const NamedSet* all = find(mesh.nodeSets, "all");
  CHECK(all && all->ids.size() == 29);
  const NamedSet* bottom = find(mesh.nodeSets, "bottom");
  CHECK(bottom && bottom->ids == (std::vector<std::int64_t>{ 1, 2, 3, 4, 9, 10, 11, 12 }));
  const NamedSet* both = find(mesh.nodeSets, "both");
  CHECK(both && both->ids == (std::vector<std::int64_t>{ 1, 2, 3, 4, 9, 10, 11, 12, 21, 22 }));
  const NamedSet* tipnodes = find(mesh.nodeSets, "tipnodes");
  CHECK(tipnodes && sorted(tipnodes->ids) == (std::vector<std::int64_t>{ 2, 21, 22, 23, 24, 25, 26, 27, 28, 29 }));
  const NamedSet* solid = find(mesh.elementSets, "solid");
  CHECK(solid && solid->ids == (std::vector<std::int64_t>{ 1, 2 }));
  const NamedSet* cube = find(mesh.elementSets, "cube");
  CHECK(cube && cube->ids == std::vector<std::int64_t>{ 1 });
  // face S2 of a C3D20 is 5-8-7-6 with its midside nodes 13-16
  const NamedSet* top = find(mesh.nodeSets, "top");
  CHECK(top && sorted(top->ids) == (std::vector<std::int64_t>{ 5, 6, 7, 8, 13, 14, 15, 16 }));
  // face S1 of a C3D10 is 1-2-3 (nodes 2, 21, 22) with the midside nodes 5, 6, 7 (24, 25, 26)
  const NamedSet* base = find(mesh.nodeSets, "base");
  CHECK(base && sorted(base->ids) == (std::vector<std::int64_t>{ 2, 21, 22, 24, 25, 26 }));
}

TEST(ElementTypesAndNodeOrders)
{
  // one element of each family; a wedge's order is turned to VTK's (the others are VTK's already)
  const std::string dir = folder("types");
  std::string nodes = "*NODE\n";
  for (int i = 1; i <= 20; ++i)
  {
    nodes += std::to_string(i) + ", " + std::to_string(i) + ", 0, 0\n";
  }
  std::string elements;
  const struct
  {
    const char* type;
    int count;
    CellType cell;
  } types[] = { { "C3D4", 4, CellType::Tetra }, { "C3D10", 10, CellType::QuadraticTetra }, { "C3D8", 8, CellType::Hexahedron },
    { "C3D8R", 8, CellType::Hexahedron }, { "C3D8I", 8, CellType::Hexahedron }, { "C3D20", 20, CellType::QuadraticHexahedron },
    { "C3D20R", 20, CellType::QuadraticHexahedron }, { "C3D6", 6, CellType::Wedge }, { "C3D15", 15, CellType::QuadraticWedge },
    { "S3", 3, CellType::Triangle }, { "S4", 4, CellType::Quad }, { "S4R", 4, CellType::Quad }, { "S6", 6, CellType::QuadraticTriangle },
    { "S8", 8, CellType::QuadraticQuad }, { "S8R", 8, CellType::QuadraticQuad }, { "CPS3", 3, CellType::Triangle },
    { "CPE4", 4, CellType::Quad }, { "CAX6", 6, CellType::QuadraticTriangle }, { "CPS8R", 8, CellType::QuadraticQuad },
    { "CAX4R", 4, CellType::Quad }, { "CPE6", 6, CellType::QuadraticTriangle }, { "T3D2", 2, CellType::Line },
    { "B32", 3, CellType::QuadraticEdge } };
  int id = 1;
  for (const auto& type : types)
  {
    elements += std::string("*ELEMENT, TYPE=") + type.type + "\n" + std::to_string(id++);
    for (int k = 1; k <= type.count; ++k)
    {
      elements += ", " + std::to_string(k);
    }
    elements += "\n";
  }
  const abaqus::Deck deck = abaqus::readDeck(writeFile(dir + "/types.inp", nodes + elements));
  CHECK(deck.mesh.blocks.size() == sizeof(types) / sizeof(types[0]));
  for (std::size_t b = 0; b < deck.mesh.blocks.size(); ++b)
  {
    CHECK(deck.mesh.blocks[b].type == types[b].cell);
    CHECK(static_cast<int>(deck.mesh.blocks[b].nodes.size()) == types[b].count);
  }
  CHECK(deck.mesh.blocks[7].nodes == (std::vector<std::int64_t>{ 1, 3, 2, 4, 6, 5 }));
  CHECK(deck.mesh.blocks[8].nodes == (std::vector<std::int64_t>{ 1, 3, 2, 4, 6, 5, 9, 8, 7, 12, 11, 10, 13, 15, 14 }));
  CHECK(deck.mesh.blocks[0].nodes == (std::vector<std::int64_t>{ 1, 2, 3, 4 }));
  CHECK(deck.mesh.warnings.empty());
}

TEST(UnsupportedElementTypeIsReportedWithItsLine)
{
  const std::string dir = folder("unsupported");
  const abaqus::Deck deck = abaqus::readDeck(writeFile(dir + "/spring.inp", "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n"
                                                                            "*ELEMENT, TYPE=SPRINGA\n1, 1, 2\n"
                                                                            "*ELEMENT, TYPE=CPS3\n2, 1, 2, 3\n"));
  CHECK(deck.mesh.warnings.size() == 1);
  for (const std::string& warning : deck.mesh.warnings)
  {
    std::printf("warning: %s\n", warning.c_str());
  }
  CHECK(!deck.mesh.warnings.empty() && contains(deck.mesh.warnings[0], "spring.inp:5: element type SPRINGA is not supported"));
  CHECK(deck.mesh.blocks.size() == 1 && deck.mesh.nodeIds.size() == 3);
}

TEST(BadDecksNameTheFileAndTheLine)
{
  const std::string dir = folder("bad");
  const std::string nodes = "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n";
  CHECK(contains(readError(writeFile(dir + "/number.inp", "*NODE\n1, 0, 0, 0\n2, 1.0.0, 0, 0\n")),
    "number.inp:3: node 2's coordinate \"1.0.0\" is not a finite number"));
  CHECK(contains(readError(writeFile(dir + "/nan.inp", "*NODE\n1, nan, 0, 0\n")), "nan.inp:2: node 1's coordinate \"nan\""));
  CHECK(contains(readError(writeFile(dir + "/huge.inp", "*NODE\n1, 1e400, 0, 0\n")), "huge.inp:2:"));
  CHECK(contains(readError(writeFile(dir + "/id.inp", "*NODE\nx1, 0, 0, 0\n")), "id.inp:2: \"x1\" is not a node id"));
  CHECK(contains(readError(writeFile(dir + "/include.inp", "*NODE\n*INCLUDE, INPUT=gone.inp\n")),
    "include.inp:2: *INCLUDE, INPUT=gone.inp:"));
  CHECK(contains(readError(writeFile(dir + "/twice.inp", nodes + "3, 5, 5, 5\n")), "twice.inp:6: node 3 is defined twice"));
  CHECK(contains(readError(writeFile(dir + "/missing.inp", nodes + "*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 9\n")),
    "missing.inp:7: element 1 refers to node 9, which the deck does not define"));
  CHECK(contains(readError(writeFile(dir + "/short.inp", nodes + "*ELEMENT, TYPE=C3D4\n1, 1, 2, 3\n*STEP\n")),
    "short.inp:7: element 1 has 3 nodes; a C3D4 has 4"));
  CHECK(contains(readError(writeFile(dir + "/long.inp", nodes + "*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4, 4\n")),
    "long.inp:7: element 1 has more than the 4 nodes"));
  CHECK(contains(readError(writeFile(dir + "/eltwice.inp", nodes + "*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n1, 1, 2, 3, 4\n")),
    "eltwice.inp:8: element 1 is defined twice"));
  CHECK(contains(readError(writeFile(dir + "/notype.inp", nodes + "*ELEMENT\n1, 1, 2, 3, 4\n")), "notype.inp:6: *ELEMENT without TYPE="));
  CHECK(contains(readError(writeFile(dir + "/part.inp", "*PART, NAME=p\n" + nodes)), "part.inp:1: *PART: decks of parts"));
  CHECK(contains(readError(writeFile(dir + "/set.inp", nodes + "*NSET, NSET=a\nb\n")), "set.inp:7: no node set is named b"));
  CHECK(contains(readError(writeFile(dir + "/face.inp", nodes + "*ELEMENT, TYPE=C3D4\n1, 1, 2, 3, 4\n*SURFACE, NAME=s\n1, S7\n")),
    "face.inp:9: a C3D4 has no face S7"));
  CHECK(contains(readError(writeFile(dir + "/self.inp", "*INCLUDE, INPUT=self.inp\n")), "nested more than 20 deep"));
  CHECK(contains(readError(dir + "/none.inp"), "none.inp: cannot be read"));
  // a GENERATE far wider than the mesh takes the ids that exist, and says how many do not
  const abaqus::Deck wide = abaqus::readDeck(writeFile(dir + "/wide.inp", nodes + "*NSET, NSET=a, GENERATE\n2, 999999999999, 2\n"));
  CHECK(wide.mesh.nodeSets.size() == 1 && wide.mesh.nodeSets[0].ids == (std::vector<std::int64_t>{ 2, 4 }));
  for (const std::string& warning : wide.mesh.warnings)
  {
    std::printf("warning: %s\n", warning.c_str());
  }
  CHECK(wide.mesh.warnings.size() == 1 && contains(wide.mesh.warnings[0], "wide.inp:7: GENERATE 2 to 999999999999: 499999999997 node ids are not in the deck"));
}

TEST(VariantKeepsEveryOtherByte)
{
  const std::string dir = folder("variant");
  const std::string source = cubeDeck(dir);
  const abaqus::Deck deck = abaqus::readDeck(source);
  const std::size_t count = deck.mesh.nodeIds.size();
  // the same coordinates: the same bytes, in the deck and in its include
  deck.writeVariant(dir + "/same/cube.inp", deck.mesh.nodeIds.data(), deck.mesh.xyz.data(), count, false);
  CHECK(readFile(dir + "/same/cube.inp") == readFile(source));
  CHECK(readFile(dir + "/same/mesh/nodes.inp") == readFile(dir + "/mesh/nodes.inp"));
  // nodes 7 and 21 moved, given in reverse order: only their lines change, and read back exactly
  std::vector<std::int64_t> ids(deck.mesh.nodeIds.rbegin(), deck.mesh.nodeIds.rend());
  std::vector<double> xyz;
  for (std::size_t i = count; i-- > 0;)
  {
    xyz.insert(xyz.end(), deck.mesh.xyz.begin() + 3 * i, deck.mesh.xyz.begin() + 3 * i + 3);
  }
  const double moved7[3] = { 1.1, 1.0 / 3.0, 1.0 }, moved21[3] = { 2.0, -1e-17, 0.0 };
  std::copy(moved7, moved7 + 3, xyz.begin() + 3 * (count - 7));
  std::copy(moved21, moved21 + 3, xyz.begin() + 3 * (count - 21));
  deck.writeVariant(dir + "/moved/cube.inp", ids.data(), xyz.data(), count, false);
  const std::string include = readFile(dir + "/moved/mesh/nodes.inp");
  std::string expected = cubeNodes;
  expected.replace(expected.find("7, 1., 1., 1."), 13, "7, 1.1, 0.3333333333333333, 1.");
  CHECK(include == expected);
  std::string deckText = readFile(source);
  deckText.replace(deckText.find("  21 ,  2.0D0 , 0.0 , 0.0"), 25, "  21 ,  2.0D0 , -1e-17 , 0.0");
  CHECK(readFile(dir + "/moved/cube.inp") == deckText);
  const abaqus::Deck again = abaqus::readDeck(dir + "/moved/cube.inp");
  CHECK(again.mesh.xyz[3 * 6 + 0] == moved7[0] && again.mesh.xyz[3 * 6 + 1] == moved7[1]);
  CHECK(again.mesh.xyz[3 * 20 + 1] == moved21[1]);
  // the layout alone writes the same variant
  const abaqus::Deck layout = abaqus::readNodeLayout(source);
  CHECK(layout.mesh.nodeIds == deck.mesh.nodeIds && layout.mesh.xyz == deck.mesh.xyz && layout.mesh.blocks.empty());
  layout.writeVariant(dir + "/layout/cube.inp", ids.data(), xyz.data(), count, false);
  CHECK(readFile(dir + "/layout/cube.inp") == readFile(dir + "/moved/cube.inp"));
}

TEST(VariantNumbersFitCalculixFields)
{
  // CalculiX reads a number in 20 characters and cuts a longer one without a word: every written
  // coordinate fits, as the shortest text when that fits, else to 14-16 significant digits
  // (relative change below 1e-13: 17 digits make a double, each one fewer rounds by 10x more)
  const std::string dir = folder("width");
  const std::string source = writeFile(dir + "/deck.inp", "*NODE\n1, 0., 0., 0.\n2, 1., 0., 0.\n");
  const abaqus::Deck deck = abaqus::readDeck(source);
  const double xyz[6] = { -1.2345678901234567e-07, 0.0012345678901234567, -123456.78901234567, 1.0 / 3.0, -2e-300, 5.0 };
  deck.writeVariant(dir + "/variant/deck.inp", deck.mesh.nodeIds.data(), xyz, 2, false);
  const std::string text = readFile(dir + "/variant/deck.inp");
  std::printf("%s", text.c_str());
  std::size_t widest = 0, begin = text.find('\n', text.find("*NODE")) + 1;
  while (begin < text.size())
  {
    const std::size_t end = text.find('\n', begin);
    std::string line = text.substr(begin, end - begin);
    for (std::size_t field = 0, comma = 0; comma != std::string::npos; field = comma + 1)
    {
      comma = line.find(',', field);
      std::string number = line.substr(field, (comma == std::string::npos ? line.size() : comma) - field);
      number.erase(std::remove(number.begin(), number.end(), ' '), number.end()); // ccx drops the blanks
      widest = std::max(widest, number.size());
    }
    begin = end + 1;
  }
  CHECK(widest <= 20);
  const abaqus::Deck again = abaqus::readDeck(dir + "/variant/deck.inp");
  for (int i = 0; i < 6; ++i)
  {
    CHECK(std::abs(again.mesh.xyz[i] - xyz[i]) <= 1e-13 * std::abs(xyz[i]));
  }
  CHECK(again.mesh.xyz[3] == 1.0 / 3.0 && again.mesh.xyz[5] == 5.0); // the shortest text, exact, where it fits
}

TEST(VariantRefusesOtherDataAndNeverHalfWrites)
{
  const std::string dir = folder("refuse");
  const std::string source = cubeDeck(dir);
  const abaqus::Deck deck = abaqus::readDeck(source);
  // a variant whose include would go onto the source's include
  CHECK(contains(testing::writeError(deck, dir + "/other.inp", deck.mesh.nodeIds, deck.mesh.xyz, true),
    dir + "/mesh/nodes.inp: is a file of the source " + source + ": a variant is written elsewhere"));
  CHECK(!fs::exists(dir + "/other.inp"));
  // the refusals of every format; the nodes' include changed since it was read
  testing::checkVariantRefusals(deck, source, dir, "** edited\n", dir + "/mesh/nodes.inp");
}

TEST(TwoDimensionalDeckKeepsTwoCoordinates)
{
  const std::string dir = folder("plane");
  const std::string source = writeFile(dir + "/plane.inp", "*NODE\n1, 0, 0\n2, 1, 0\n3, 0, 1\n*ELEMENT, TYPE=CPS3, ELSET=plate\n1, 1, 2, 3\n");
  const abaqus::Deck deck = abaqus::readDeck(source);
  CHECK(deck.mesh.xyz == (std::vector<double>{ 0, 0, 0, 1, 0, 0, 0, 1, 0 }));
  std::vector<double> xyz = deck.mesh.xyz;
  xyz[3] = 1.25;
  deck.writeVariant(dir + "/v/plane.inp", deck.mesh.nodeIds.data(), xyz.data(), 3, false);
  CHECK(readFile(dir + "/v/plane.inp") == "*NODE\n1, 0, 0\n2, 1.25, 0\n3, 0, 1\n*ELEMENT, TYPE=CPS3, ELSET=plate\n1, 1, 2, 3\n");
}

TEST_MAIN
