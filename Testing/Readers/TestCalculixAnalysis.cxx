// A CalculiX deck's linear static analysis (Abaqus/CalculixAnalysis.h) without VTK: materials,
// sections, supports and point loads read; what the exact shape derivatives do not cover refused
// naming the keyword; ccx's result files read in ASCII and binary, bad ones refused.
#include "../TestHarness.h"
#include "Abaqus/CalculixAnalysis.h"
#include "FormatFiles.h"

#include <cstring>
#include <string>
#include <vector>

using namespace mlsformats;

namespace
{
using testing::contains;
using testing::writeFile;

const testing::TestFolders folder{ "calculix-analysis" };

// One C3D8 cube, its face x = 0 clamped, a load on node 2, as a user writes it (mixed case).
const std::string Mesh = "*NODE, NSET=all\n1, 0, 0, 0\n2, 1, 0, 0\n3, 1, 1, 0\n4, 0, 1, 0\n5, 0, 0, 1\n6, 1, 0, 1\n7, 1, 1, 1\n8, 0, 1, 1\n"
                         "*ELEMENT, TYPE=C3D8, ELSET=part\n1, 1, 2, 3, 4, 5, 6, 7, 8\n"
                         "*NSET, NSET=fixed\n1, 4, 5, 8\n";
const std::string Model = "*Material, name=Steel\n*Elastic\n210000., 0.3\n*DENSITY\n7.85e-9\n"
                          "*Solid Section, elset=part, material=STEEL\n";
const std::string Step = "*STEP\n*STATIC\n*BOUNDARY\nfixed, 1, 3\n2, 2, 2, 0.5\n*CLOAD\n2, 3, -10.\n7, 1, 4.\n"
                         "*DLOAD\npart, GRAV, 9810., 0, 0, -2\n1, GRAV, 10., 1, 0, 0\n1, P2, 3.\n*NODE FILE\nU\n*END STEP\n";

// The message of what call throws, printed; "" when it throws nothing.
template <typename Call>
std::string errorOf(Call call)
{
  try
  {
    call();
  }
  catch (const std::exception& e)
  {
    std::printf("expected error: %s\n", e.what());
    return e.what();
  }
  return "";
}
std::string analysisError(const std::string& path)
{
  return errorOf([&] { abaqus::readCalculixAnalysis(path); });
}
std::string frdError(const std::string& path)
{
  return errorOf([&] { abaqus::readFrdDisplacements(path); });
}

// A result file of the cube's 8 nodes as ccx writes it: the coordinates, then DISP (format '1':
// ASCII lines, '3': binary doubles); u = (i, -i, 2 i) * 1e-3 + 1e-9 at node i (a value six digits
// cannot hold).
std::string frd(char format)
{
  const double X[8][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };
  std::string text = "    1C                                                                   \n";
  char line[256];
  std::snprintf(line, sizeof line, "    2C%28d%37c%c\n", 8, ' ', format);
  text += line;
  const auto record = [&](int node, const double* v) {
    if (format == '1')
    {
      std::snprintf(line, sizeof line, " -1%10d%12.5E%12.5E%12.5E\n", node, v[0], v[1], v[2]);
      text += line;
    }
    else
    {
      const std::int32_t n = node;
      text.append(reinterpret_cast<const char*>(&n), 4);
      text.append(reinterpret_cast<const char*>(v), 24);
    }
  };
  for (int i = 0; i < 8; ++i)
  {
    record(i + 1, X[i]);
  }
  if (format == '1')
  {
    text += " -3\n";
  }
  std::snprintf(line, sizeof line, "  100CL  101 1.000000000%12d%21c0    1%12c%c\n", 8, ' ', ' ', format);
  text += "    1PSTEP                         1           1           1          \n";
  text += line;
  text += " -4  DISP        4    1\n -5  D1          1    2    1    0\n -5  D2          1    2    2    0\n"
          " -5  D3          1    2    3    0\n -5  ALL         1    2    0    0    1ALL\n";
  for (int i = 0; i < 8; ++i)
  {
    const double u[3] = { (i + 1) * 1e-3 + 1e-9, -(i + 1) * 1e-3, 2 * (i + 1) * 1e-3 };
    record(i + 1, u);
  }
  if (format == '1')
  {
    text += " -3\n";
  }
  return text + "9999\n";
}
} // namespace

TEST(ReadsMaterialsSectionsSupportsAndLoads)
{
  const std::string dir = folder("reads");
  const abaqus::CalculixAnalysis a = abaqus::readCalculixAnalysis(writeFile(dir + "/cube.inp", Mesh + Model + Step));
  CHECK(a.materials.size() == 1 && a.materials[0].youngs == 210000 && a.materials[0].poisson == 0.3 && a.materials[0].density == 7.85e-9);
  CHECK(a.elementMaterial == std::vector<int>{ 0 });
  CHECK(a.supports.size() == 13); // 4 nodes x 3 and node 2's y
  CHECK(a.supports.back().node == a.nodeIndex(2) && a.supports.back().dof == 1 && a.supports.back().value == 0.5);
  CHECK(a.loads.size() == 2 && a.loads[0].node == a.nodeIndex(2) && a.loads[0].dof == 2 && a.loads[0].value == -10);
  CHECK(a.nodeSet("FIXED").size() == 4 && a.elementSet("Part").size() == 1);
  // the two GRAV lines summed, their directions normalized as ccx does; the pressure on face 2
  CHECK((a.elementAcceleration == std::vector<std::array<double, 3>>{ { 10, 0, -9810 } }));
  CHECK(a.pressures.size() == 1 && a.pressures[0].element == 0 && a.pressures[0].face == 2 && a.pressures[0].pressure == 3);
  CHECK(contains(analysisError(writeFile(dir + "/nostep.inp", Mesh + Model)), "no *STATIC step"));
}

TEST(RefusesWhatTheDerivativesDoNotCover)
{
  const std::string dir = folder("refuses");
  const std::vector<std::pair<std::string, std::string>> cases = {
    { Mesh + Model + "*STEP, NLGEOM\n*STATIC\n*END STEP\n", "NLGEOM" },
    { Mesh + Model + "*STEP\n*STATIC\n*DLOAD\n1, P7, 2.\n*END STEP\n", "P7 loads are not supported" },
    { Mesh + Model + "*STEP\n*STATIC\n*DLOAD\n1, BX, 2.\n*END STEP\n", "BX loads are not supported" },
    { Mesh + Model + "*STEP\n*STATIC\n*DLOAD\npart, GRAV, 9810, 0, 0, 0\n*END STEP\n", "direction is zero" },
    { Mesh + Model + "*STEP\n*STATIC\n*DLOAD\npart, GRAV, 9810\n*END STEP\n", "the direction's three components" },
    { Mesh + Model + "*STEP\n*DYNAMIC\n*END STEP\n", "*DYNAMIC" },
    { Mesh + Model + "*CONTACT PAIR, INTERACTION=i\na, b\n" + Step, "*CONTACT PAIR" },
    { Mesh + "*MATERIAL, NAME=steel\n*ELASTIC, TYPE=ORTHO\n1, 2, 3, 4, 5, 6, 7, 8, 9\n*SOLID SECTION, ELSET=part, MATERIAL=steel\n" + Step,
      "TYPE=ORTHO" },
    { Mesh + "*MATERIAL, NAME=steel\n*ELASTIC\n210000, 0.3\n*PLASTIC\n200, 0\n*SOLID SECTION, ELSET=part, MATERIAL=steel\n" + Step,
      "*PLASTIC" },
    { Mesh + Model + "*STEP\n*STATIC\n*CLOAD, AMPLITUDE=ramp\n2, 3, 1\n*END STEP\n", "AMPLITUDE" },
    { Mesh + Model + Step + "*STEP\n*STATIC\n*END STEP\n", "a second static step" },
    { Mesh + "*MATERIAL, NAME=steel\n*ELASTIC\n210000, 0.3\n" + Step, "element 1 has no *SOLID SECTION" },
    { Mesh + "*MATERIAL, NAME=steel\n*SOLID SECTION, ELSET=part, MATERIAL=steel\n" + Step, "has no *ELASTIC" },
    { Mesh + "*SOLID SECTION, ELSET=part, MATERIAL=steel\n" + Step, "no *MATERIAL named steel" },
    { Mesh + Model + "*STEP\n*STATIC\n*BOUNDARY\nnowhere, 1, 3\n*END STEP\n", "no node set nowhere" },
    { Mesh + Model + "*STEP\n*STATIC\n*BOUNDARY\nfixed, 1, 6\n*END STEP\n", "degrees of freedom 1 to 3" },
    { Mesh + "*MATERIAL, NAME=steel\n*ELASTIC\n210000, 0.7\n*SOLID SECTION, ELSET=part, MATERIAL=steel\n" + Step, "-1 < nu < 0.5" },
  };
  for (std::size_t k = 0; k < cases.size(); ++k)
  {
    const std::string error = analysisError(writeFile(dir + "/deck" + std::to_string(k) + ".inp", cases[k].first));
    CHECK(contains(error, cases[k].second));
  }
}

TEST(ReadsAsciiAndBinaryResults)
{
  const std::string dir = folder("results");
  const abaqus::FrdDisplacements ascii = abaqus::readFrdDisplacements(writeFile(dir + "/ascii.frd", frd('1')));
  const abaqus::FrdDisplacements binary = abaqus::readFrdDisplacements(writeFile(dir + "/binary.frd", frd('3')));
  CHECK(ascii.coordinates.size() == 8 && ascii.displacements.size() == 8 && binary.displacements.size() == 8);
  CHECK(binary.coordinates.at(7)[0] == 1 && binary.coordinates.at(7)[2] == 1);
  // binary doubles exactly, the ASCII file to its six digits
  CHECK(binary.displacements.at(3)[0] == 3e-3 + 1e-9 && binary.displacements.at(3)[2] == 6e-3);
  CHECK(std::abs(ascii.displacements.at(3)[0] - (3e-3 + 1e-9)) <= 5e-6 * 3e-3 && ascii.displacements.at(3)[0] != 3e-3 + 1e-9);
  // no DISP block, a binary block cut short, not a result file
  std::string text = frd('1');
  CHECK(contains(frdError(writeFile(dir + "/nodisp.frd", text.substr(0, text.find("    1PSTEP")))), "*NODE FILE and U"));
  text = frd('3');
  CHECK(contains(frdError(writeFile(dir + "/short.frd", text.substr(0, text.size() - 40))), "cut short"));
  CHECK(contains(frdError(writeFile(dir + "/deck.frd", Mesh)), "no node coordinates"));
  CHECK(contains(frdError(dir + "/missing.frd"), "cannot be read"));
}

TEST_MAIN
