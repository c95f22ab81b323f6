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
}

TEST(MutatedDecksGiveAValidMeshOrOneClearError)
{
  const std::string path = outputFile("fuzz-mutated.inp"), variant = outputFile("fuzz-variant/fuzz-mutated.inp");
  std::mt19937 random(20261128);
  int errors = 0, read = 0, unclear = 0, broken = 0, changed = 0;
  const int files = 3000;
  for (int f = 0; f < files; ++f)
  {
    std::string text = seeds()[f % seeds().size()];
    for (int m = std::uniform_int_distribution<int>(1, 3)(random); m > 0; --m)
      text = testing::mutate(text, random);
    if (text.find_first_not_of(" \t\r\n") == std::string::npos || text[text.find_first_not_of(" \t\r\n")] != '*')
      text = "*" + text; // a deck starts with a keyword: the reader is asked, not the format guesser
    std::ofstream(path, std::ios::binary) << text;
    vtkNew<vtkMeshFileReader> reader;
    vtkNew<LastError> error, pipeline, warnings; // the reader's error; the executive's "returned failure"
    reader->AddObserver(vtkCommand::ErrorEvent, error);
    reader->AddObserver(vtkCommand::WarningEvent, warnings); // what is left out of a mutated deck: not counted
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
        std::printf("unclear error on deck %d (%d messages, %lld points): %s\n", f, error->count,
          static_cast<long long>(output->GetNumberOfPoints()), error->text.c_str());
      continue;
    }
    ++read;
    if (!valid(output))
    {
      if (broken++ < 5)
        std::printf("deck %d read without error into an invalid mesh\n", f);
      continue;
    }
    // the variant with the deck's own coordinates is the deck
    std::vector<std::int64_t> ids(output->GetNumberOfPoints());
    std::vector<double> xyz(3 * ids.size());
    for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
    {
      ids[i] = static_cast<std::int64_t>(output->GetPointData()->GetArray("NodeId")->GetTuple1(i));
      output->GetPoint(i, xyz.data() + 3 * i);
    }
    try
    {
      mlsformats::formatOf(path)->read(path, true)->writeVariant(variant, ids.data(), xyz.data(), ids.size(), true);
      if (contents(variant) != text && changed++ < 5)
        std::printf("deck %d: its variant with unchanged coordinates differs from it\n", f);
    }
    catch (const std::exception& e)
    {
      if (changed++ < 5)
        std::printf("deck %d read, but its variant was refused: %s\n", f, e.what());
    }
  }
  std::printf("%d mutated decks: %d errors, %d read as valid meshes\n", files, errors, read);
  CHECK(unclear == 0);
  CHECK(broken == 0);
  CHECK(changed == 0);
  // the mutations reach both outcomes (a fuzzer that only produced errors would test less)
  CHECK(errors > files / 4 && read > files / 10);
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
