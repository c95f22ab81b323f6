// OpenFOAM's polyMesh files as the mesh quality reads them (faces, owner, neighbour): each
// format OpenFOAM writes gives the same lists, and a damaged file is an error naming it.
#include "../TestHarness.h"
#include "Foam/PolyMeshFiles.h"

#include <zlib.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <unistd.h>

using namespace mlsfoam;
namespace fs = std::filesystem;

namespace
{
std::string header(const std::string& format, const std::string& kind, const std::string& object, int labelBits = 32)
{
  return "FoamFile\n{\n    version     2.0;\n    format      " + format + ";\n    class       " + kind +
    ";\n    arch        \"LSB;label=" + std::to_string(labelBits) + ";scalar=64\";\n    object      " + object +
    ";\n}\n// * * * //\n\n";
}

template <typename Label>
std::string binaryList(const std::vector<Label>& values)
{
  std::string s = std::to_string(values.size()) + "\n(";
  s.append(reinterpret_cast<const char*>(values.data()), values.size() * sizeof(Label));
  return s + ")\n";
}

// A fresh folder for one case of files.
std::string folder(const std::string& name)
{
  const fs::path path = fs::temp_directory_path() / ("mlsdeform-polymesh-" + std::to_string(::getpid())) / name;
  fs::remove_all(path);
  fs::create_directories(path);
  return path.string();
}

void write(const std::string& path, const std::string& text)
{
  std::ofstream(path, std::ios::binary) << text;
}

// Whether f throws std::runtime_error whose message holds every one of words.
template <typename F>
bool failsWith(F f, std::initializer_list<const char*> words)
{
  try
  {
    f();
  }
  catch (const std::runtime_error& e)
  {
    const std::string message = e.what();
    std::printf("  error: %s\n", message.c_str());
    for (const char* w : words)
    {
      if (message.find(w) == std::string::npos)
      {
        return false;
      }
    }
    return true;
  }
  return false;
}

// Two faces: a quad and a triangle.
const std::vector<int> Start = { 0, 4, 7 }, Points = { 0, 1, 2, 3, 1, 4, 2 };
}

TEST(FacesInEveryFormatOpenFOAMWrites)
{
  const std::string compact = folder("binary");
  write(compact + "/faces", header("binary", "faceCompactList", "faces") + binaryList(Start) + binaryList(Points));
  const std::string ascii = folder("ascii");
  write(ascii + "/faces", header("ascii", "faceList", "faces") + "2\n(\n4(0 1 2 3)\n3(1 4 2)\n)\n");
  const std::string asciiCompact = folder("ascii-compact");
  write(asciiCompact + "/faces", header("ascii", "faceCompactList", "faces") + "3\n(\n0\n4\n7\n)\n\n7\n(\n0 1 2 3 1 4 2\n)\n");
  const std::string compressed = folder("gz");
  {
    const std::string text = header("ascii", "faceList", "faces") + "2\n(\n4(0 1 2 3)\n3(1 4 2)\n)\n";
    gzFile gz = gzopen((compressed + "/faces.gz").c_str(), "wb");
    gzwrite(gz, text.data(), static_cast<unsigned>(text.size()));
    gzclose(gz);
  }
  for (const std::string& directory : { compact, ascii, asciiCompact, compressed })
  {
    const FoamFaces faces = readFoamFaces(directory);
    CHECK(faces.size() == 2 && faces.start == Start && faces.points == Points);
  }
  // 64-bit labels
  const std::string wide = folder("label64");
  write(wide + "/faces", header("binary", "faceCompactList", "faces", 64) +
      binaryList(std::vector<std::int64_t>(Start.begin(), Start.end())) + binaryList(std::vector<std::int64_t>(Points.begin(), Points.end())));
  CHECK(readFoamFaces(wide).points == Points);
}

TEST(OwnerAndNeighbourLabels)
{
  const std::string binary = folder("labels-binary");
  write(binary + "/owner", header("binary", "labelList", "owner") + binaryList(std::vector<int>{ 0, 0, 1 }));
  const std::string ascii = folder("labels-ascii");
  write(ascii + "/owner", header("ascii", "labelList", "owner") + "3\n(\n0\n0\n1\n)\n");
  CHECK(readFoamIndices(binary, "owner") == std::vector<int>({ 0, 0, 1 }));
  CHECK(readFoamIndices(ascii, "owner") == std::vector<int>({ 0, 0, 1 }));
  // a 64-bit label beyond int: an error for the indices, a value for readFoamLabels
  const std::string wide = folder("labels-wide");
  write(wide + "/owner", header("binary", "labelList", "owner", 64) + binaryList(std::vector<std::int64_t>{ 0, std::int64_t(1) << 40 }));
  CHECK(readFoamLabels(wide, "owner")[1] == std::int64_t(1) << 40);
  CHECK(failsWith([&] { readFoamIndices(wide, "owner"); }, { "owner", "out of range" }));
}

TEST(MeshSizeFromTheOwnersNote)
{
  const std::string noted = folder("noted");
  std::string text = header("binary", "labelList", "owner") + binaryList(std::vector<int>{ 0, 0, 1 });
  text.insert(text.find("    object"), "    note        \"nPoints:12  nCells:2  nFaces:11  nInternalFaces:1\";\n");
  write(noted + "/owner", text);
  const FoamMeshSize size = readFoamMeshSize(noted);
  CHECK(size.points == 12 && size.cells == 2);
  // no note, or no owner file: unknown
  const std::string plain = folder("plain");
  write(plain + "/owner", header("ascii", "labelList", "owner") + "3\n(\n0\n0\n1\n)\n");
  CHECK(readFoamMeshSize(plain).points == -1 && readFoamMeshSize(plain).cells == -1);
  CHECK(readFoamMeshSize(folder("empty")).points == -1);
}

TEST(DamagedFacesAreErrorsNamingTheFile)
{
  const std::string d = folder("damaged");
  CHECK(failsWith([&] { readFoamFaces(d); }, { "faces", "no faces file" }));
  // binary points cut short
  std::string whole = header("binary", "faceCompactList", "faces") + binaryList(Start) + binaryList(Points);
  write(d + "/faces", whole.substr(0, whole.size() - 6));
  CHECK(failsWith([&] { readFoamFaces(d); }, { "faces", "truncated" }));
  // offsets that do not end at the number of points
  write(d + "/faces", header("binary", "faceCompactList", "faces") + binaryList(std::vector<int>{ 0, 4, 6 }) + binaryList(Points));
  CHECK(failsWith([&] { readFoamFaces(d); }, { "faces", "offsets" }));
  // an ascii face with fewer points than its count, and one with more
  write(d + "/faces", header("ascii", "faceList", "faces") + "2\n(\n4(0 1 2)\n3(1 4 2)\n)\n");
  CHECK(failsWith([&] { readFoamFaces(d); }, { "faces", "face 0" }));
  write(d + "/faces", header("ascii", "faceList", "faces") + "2\n(\n4(0 1 2 3)\n3(1 4 2 5)\n)\n");
  CHECK(failsWith([&] { readFoamFaces(d); }, { "faces", "face 1" }));
  // another class
  write(d + "/faces", header("ascii", "labelList", "faces") + "2\n(\n0\n1\n)\n");
  CHECK(failsWith([&] { readFoamFaces(d); }, { "faces", "labelList" }));
  fs::remove_all(fs::temp_directory_path() / ("mlsdeform-polymesh-" + std::to_string(::getpid())));
}

// The boundary's patches and their groups (inGroups), as OpenFOAM writes them and as users edit
// them: a count or none, List<word> or a bare list, comments, a nested dictionary before the
// groups; a truncated file or another class is an error naming the file.
TEST(BoundaryPatchesAndTheirGroups)
{
  const std::string dir = folder("boundary");
  const std::string head = "FoamFile\n{\n    version 2.0;\n    format ascii;\n    class polyBoundaryMesh;\n    object boundary;\n}\n";
  write(dir + "/boundary", head + R"(// a comment
3
(
    inlet { type patch; nFaces 10; startFace 100; }
    motorBike_frt-fairing:001%1
    {
        type            wall;
        inGroups        List<word> 2(wall motorBikeGroup);   // as snappyHexMesh writes them
        nFaces          20;
    }
    periodic
    {
        type cyclic;
        transform { type rotational; axis (0 0 1); }   /* nested */
        inGroups (cyclicGroup);
        neighbourPatch other;
    }
)
)");
  const std::vector<FoamPatch> patches = readFoamBoundary(dir);
  CHECK(patches.size() == 3);
  CHECK(patches[0].name == "inlet" && patches[0].type == "patch" && patches[0].groups.empty());
  CHECK(patches[1].name == "motorBike_frt-fairing:001%1" && patches[1].type == "wall");
  CHECK((patches[1].groups == std::vector<std::string>{ "wall", "motorBikeGroup" }));
  CHECK(patches[2].type == "cyclic" && (patches[2].groups == std::vector<std::string>{ "cyclicGroup" }));

  write(dir + "/boundary", head + "2\n(\n    inlet\n    {\n        type patch;\n");
  CHECK(failsWith([&] { readFoamBoundary(dir); }, { "boundary", "truncated" }));
  write(dir + "/boundary", "FoamFile { class faceList; }\n0()\n");
  CHECK(failsWith([&] { readFoamBoundary(dir); }, { "boundary", "polyBoundaryMesh" }));
  CHECK(failsWith([&] { readFoamBoundary(dir + "/none"); }, { "boundary", "no such file" }));
}

TEST_MAIN
