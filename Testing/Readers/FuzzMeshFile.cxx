// The Mesh File reader on thousands of mutated decks (Fuzzing.h, the OFF reader's mutations and
// the deck's own keywords and separators): each either reads as a valid mesh or gives one clear
// error naming the file and an empty output; none crashes (the sanitizer build checks memory).
// Every deck that reads is written back as a variant with its own coordinates: byte for byte the
// deck (a variant changes the coordinates and nothing else).
#include "../TestHarness.h"
#include "Fuzzing.h"
#include "SourceFile.h"
#include "vtkMeshFileReader.h"

#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkExecutive.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace
{
using testing::LastError;

// Valid decks of what the reader knows: the seeds of the mutations.
const std::vector<std::string>& seeds()
{
  static const std::vector<std::string> files = {
    // quadratic tetrahedra, a continuation line, sets as lists and GENERATE, a surface
    "*HEADING\nfuzz\n*NODE, NSET=ALL\n1, 0, 0, 0\n2, 1, 0, 0\n3, 0, 1, 0\n4, 0, 0, 1\n5, 0.5, 0, 0\n6, 0.5, 0.5, 0\n"
    "7, 0, 0.5, 0\n8, 0, 0, 0.5\n9, 0.5, 0, 0.5\n10, 0, 0.5, 0.5\n*ELEMENT, TYPE=C3D10, ELSET=part\n"
    "1, 1, 2, 3, 4, 5, 6, 7, 8,\n9, 10\n*NSET, NSET=base\n1, 2, 3, 5, 6, 7\n*NSET, NSET=range, GENERATE\n1, 10, 3\n"
    "*ELSET, ELSET=all\npart\n*SURFACE, NAME=bottom, TYPE=ELEMENT\npart, S1\n*MATERIAL, NAME=steel\n*ELASTIC\n210000., 0.3\n",
    // hexahedra and wedges in 2 blocks, a comment, lower-case keywords, Fortran exponents
    "** a comment\n*node\n1,0.,0.,0.\n2,1.D0,0.,0.\n3,1.,1.,0.\n4,0.,1.,0.\n5,0.,0.,1.\n6,1.,0.,1.\n7,1.,1.,1.\n8,0.,1.,1.\n"
    "9,2.,0.,0.\n10,2.,0.,1.\n*element,type=C3D8R,elset=hexes\n1,1,2,3,4,5,6,7,8\n*element,type=C3D6,elset=wedges\n"
    "2,2,9,3,6,10,7\n*elset,elset=both\nhexes,wedges\n*step\n*static\n*end step\n",
    // shells and a 2D deck
    "*NODE\n1, 0, 0\n2, 1, 0\n3, 1, 1\n4, 0, 1\n*ELEMENT, TYPE=CPS4, ELSET=plate\n1, 1, 2, 3, 4\n*NSET, NSET=edge\n1, 2\n",
  };
  return files;
}

// A mesh a pipeline can use: finite points, every cell's ids among them, NodeId per point.
bool valid(vtkUnstructuredGrid* mesh)
{
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    const double* x = mesh->GetPoint(i);
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
      return false;
  }
  vtkNew<vtkIdList> ids;
  for (vtkIdType c = 0; c < mesh->GetNumberOfCells(); ++c)
  {
    mesh->GetCellPoints(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      if (ids->GetId(k) < 0 || ids->GetId(k) >= mesh->GetNumberOfPoints())
        return false;
  }
  vtkDataArray* nodeIds = mesh->GetPointData()->GetArray("NodeId");
  return nodeIds && nodeIds->GetNumberOfTuples() == mesh->GetNumberOfPoints();
}

std::string outputFile(const std::string& name)
{
  return std::string(TEST_OUTPUT_DIR) + "/" + name;
}

std::string contents(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Reads files mutated from the seeds (as name.extension; with keyword, a deck's first character is
// made a keyword's so that the deck reader, not the format guesser, meets the mutation): each gives
// a valid mesh whose variant with its own coordinates is the file, or one clear error naming it.
void fuzz(const std::string& extension, const std::vector<std::string>& seeds, bool keyword, unsigned seed)
{
  // files of this run's own (ctest -j runs the formats side by side; Gmsh and Fluent share .msh)
  const std::string name = "fuzz-" + std::to_string(seed) + "." + extension;
  const std::string path = outputFile(name), variant = outputFile("fuzz-variant/" + name);
  std::mt19937 random(seed);
  int errors = 0, read = 0, unclear = 0, broken = 0, changed = 0;
  const int files = 3000;
  for (int f = 0; f < files; ++f)
  {
    std::string text = seeds[f % seeds.size()];
    for (int m = std::uniform_int_distribution<int>(1, 3)(random); m > 0 && f >= static_cast<int>(seeds.size()); --m)
      text = testing::mutate(text, random); // (the seeds themselves first, unmutated: each must read)
    if (keyword && (text.find_first_not_of(" \t\r\n") == std::string::npos || text[text.find_first_not_of(" \t\r\n")] != '*'))
      text = "*" + text;
    std::ofstream(path, std::ios::binary) << text;
    vtkNew<vtkMeshFileReader> reader;
    vtkNew<LastError> error, pipeline, warnings; // the reader's error; the executive's "returned failure"
    reader->AddObserver(vtkCommand::ErrorEvent, error);
    reader->AddObserver(vtkCommand::WarningEvent, warnings); // what is left out of a mutated file: not counted
    reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, pipeline);
    reader->SetFileName(path.c_str());
    reader->Update();
    vtkUnstructuredGrid* output = reader->GetOutput();
    if (error->count > 0)
    {
      ++errors;
      const bool clear = error->count == 1 && error->text.find(path) != std::string::npos && reader->GetLastError() &&
        std::string(reader->GetLastError()).find(path) != std::string::npos && output->GetNumberOfPoints() == 0 &&
        output->GetNumberOfCells() == 0;
      if (!clear && unclear++ < 5)
        std::printf("unclear error on file %d (%d messages, %lld points): %s\n", f, error->count,
          static_cast<long long>(output->GetNumberOfPoints()), error->text.c_str());
      CHECK(f >= static_cast<int>(seeds.size())); // a seed reads
      continue;
    }
    ++read;
    if (!valid(output))
    {
      if (broken++ < 5)
        std::printf("file %d read without error into an invalid mesh\n", f);
      continue;
    }
    // the variant with the file's own coordinates is the file
    std::vector<std::int64_t> ids(output->GetNumberOfPoints());
    std::vector<double> xyz(3 * ids.size());
    for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
    {
      ids[i] = vtkIdTypeArray::SafeDownCast(output->GetPointData()->GetArray("NodeId"))->GetValue(i);
      output->GetPoint(i, xyz.data() + 3 * i);
    }
    try
    {
      mlsformats::formatOf(path)->read(path, true)->writeVariant(variant, ids.data(), xyz.data(), ids.size(), true);
      if (contents(variant) != text && changed++ < 5)
        std::printf("file %d: its variant with unchanged coordinates differs from it\n", f);
    }
    catch (const std::exception& e)
    {
      if (changed++ < 5)
      {
        const std::string kept = outputFile("fuzz-refused-" + std::to_string(f) + "." + extension); // to reproduce it
        std::ofstream(kept, std::ios::binary) << text;
        std::printf("file %d (kept as %s) read, but its variant was refused: %s\n", f, kept.c_str(), e.what());
      }
    }
  }
  std::printf("%d mutated .%s files: %d errors, %d read as valid meshes\n", files, extension.c_str(), errors, read);
  CHECK(unclear == 0);
  CHECK(broken == 0);
  CHECK(changed == 0);
  // the mutations reach both outcomes (a fuzzer that only produced errors would test less)
  CHECK(errors > 0 && read > 0);
}
}

TEST(MutatedDecksGiveAValidMeshOrOneClearError)
{
  fuzz("inp", seeds(), true, 20261128);
}

TEST(MutatedGmshMeshesGiveAValidMeshOrOneClearError)
{
  fuzz("msh",
    { "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n2 2 \"base\"\n3 1 \"solid\"\n$EndPhysicalNames\n"
      "$Nodes\n4\n1 0 0 0\n2 1 0 0\n3 0 1 0\n4 0 0 1\n$EndNodes\n$Elements\n2\n1 2 2 2 1 1 3 2\n2 4 2 1 1 1 2 3 4\n"
      "$EndElements\n" },
    false, 20261129);
}

TEST(MutatedSU2MeshesGiveAValidMeshOrOneClearError)
{
  fuzz("su2",
    { "NDIME= 3\nNELEM= 1\n10 0 1 2 3 0\nNPOIN= 4\n0 0 0 0\n1 0 0 1\n0 1 0 2\n0 0 1 3\nNMARK= 1\nMARKER_TAG= wall\n"
      "MARKER_ELEMS= 1\n5 0 2 1\n",
      "% a plane\nNDIME= 2\nNELEM= 2\n5 0 1 2\n5 0 2 3\nNPOIN= 4\n0 0\n1 0\n1 1\n0 1\nNMARK= 1\nMARKER_TAG= edge\n"
      "MARKER_ELEMS= 1\n3 0 1\n" },
    false, 20261130);
}

TEST(MutatedNastranDecksGiveAValidMeshOrOneClearError)
{
  fuzz("bdf",
    { "BEGIN BULK\nGRID    1               0.      0.      0.\nGRID    2               1.      0.      0.\n"
      "GRID    3               0.      1.      0.\nGRID    4               0.      0.      1.5-1\n"
      "CTETRA  1       1       1       2       3       4\nENDDATA\n",
      "GRID,1,,0.,0.,0.\nGRID,2,,1.,0.,0.\nGRID,3,,0.,1.,0.\nCTRIA3,1,2,1,2,3\n" },
    false, 20261131);
}

TEST(MutatedFluentMeshesGiveAValidMeshOrOneClearError)
{
  // a tetrahedron: its faces turn their normals into cell 1 (c0), the boundary's right cell 0
  fuzz("msh",
    { "(0 \"a tetrahedron\")\n(2 3)\n(10 (0 1 4 0 3))\n(10 (1 1 4 1 3)(\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n))\n"
      "(12 (0 1 1 0 0))\n(12 (2 1 1 1 2))\n(13 (0 1 4 0 0))\n(13 (3 1 4 3 0)(\n3 1 2 3 1 0\n3 1 4 2 1 0\n"
      "3 2 4 3 1 0\n3 1 3 4 1 0\n))\n(45 (2 fluid solid)())\n(45 (3 wall skin)())\n" },
    false, 20261132);
}

TEST(HugeCountsAndGeneratesAreRefusedBeforeAllocating)
{
  // a GENERATE range of 10^18 ids would never end; an element id of 2^62 is a valid integer
  const std::string path = outputFile("fuzz-huge.inp");
  std::ofstream(path) << "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n*NSET, NSET=huge, GENERATE\n1, 1000000000000000000, 1\n";
  vtkNew<vtkMeshFileReader> reader;
  vtkNew<LastError> error;
  reader->AddObserver(vtkCommand::ErrorEvent, error);
  reader->SetFileName(path.c_str());
  reader->Update();
  std::printf("errors %d: %s\n", error->count, error->text.c_str());
  // either refused with the line, or read with the set of the nodes that exist
  CHECK((error->count == 1 && error->text.find(path + ":4") != std::string::npos) ||
    (error->count == 0 && reader->GetOutput()->GetNumberOfPoints() == 2));
}

TEST_MAIN
