// vtkOFFReader on thousands of mutated files (truncated, huge counts, negative indices, NaN,
// binary garbage, flipped bits, lost or repeated lines): each either reads as a valid mesh or
// gives one clear error and an empty output; none crashes (the sanitizer build checks memory).
#include "../TestHarness.h"
#include "Fuzzing.h"
#include "vtkOFFReader.h"

#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkExecutive.h>
#include <vtkIdList.h>
#include <vtkNew.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

namespace
{
using testing::LastError;

// Valid files of every header kind the reader knows: the seeds of the mutations.
const std::vector<std::string>& seeds()
{
  static const std::vector<std::string> files = {
    "OFF # a cube\n8 6 12\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n"
    "4 0 3 2 1\n4 4 5 6 7\n4 0 1 5 4\n4 1 2 6 5\n4 2 3 7 6\n4 3 0 4 7\n",
    "COFF\n4 2 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 255 255\n1 1 0 0.5 0.5 0.5 1\n3 0 1 2 255 0 0\n3 1 3 2\n",
    "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n",
    "STOFF\n3 1 0\n0 0 0 0 0\n1 0 0 1 0\n0 1 0 0 1\n3 0 1 2\n",
  };
  return files;
}

// A mesh a pipeline can use: finite points, every face's ids among them.
bool valid(vtkPolyData* mesh)
{
  for (vtkIdType i = 0; i < mesh->GetNumberOfPoints(); ++i)
  {
    const double* x = mesh->GetPoint(i);
    if (!std::isfinite(x[0]) || !std::isfinite(x[1]) || !std::isfinite(x[2]))
      return false;
  }
  vtkNew<vtkIdList> ids;
  vtkCellArray* polygons = mesh->GetPolys();
  for (vtkIdType c = 0; c < polygons->GetNumberOfCells(); ++c)
  {
    polygons->GetCellAtId(c, ids);
    for (vtkIdType k = 0; k < ids->GetNumberOfIds(); ++k)
      if (ids->GetId(k) < 0 || ids->GetId(k) >= mesh->GetNumberOfPoints())
        return false;
  }
  return true;
}

// What reading text as an OFF file gives: the output, and the reader's error messages.
struct Reading
{
  vtkSmartPointer<vtkPolyData> output;
  int errors = 0;
  std::string message; // the last one
};

Reading readText(const std::string& path, const std::string& text)
{
  std::ofstream(path, std::ios::binary) << text;
  vtkNew<vtkOFFReader> reader;
  vtkNew<LastError> error, pipeline; // the reader's message; the executive's "returned failure"
  reader->AddObserver(vtkCommand::ErrorEvent, error);
  reader->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, pipeline);
  reader->SetFileName(path.c_str());
  reader->Update();
  return { reader->GetOutput(), error->count, error->text };
}

// A file of each test's own: ctest -j runs the tests of this program side by side.
std::string outputFile(const std::string& name)
{
  return std::string(TEST_OUTPUT_DIR) + "/" + name;
}
}

TEST(HugeCountsAreRefusedBeforeAllocating)
{
  // 10^12 vertices would be 24 TB of points; a face of 2e9 vertices 16 GB of ids
  const std::string path = outputFile("fuzz-huge-counts.off");
  const Reading vertices = readText(path, "OFF\n999999999999 1 0\n0 0 0\n");
  std::printf("%s\n", vertices.message.c_str());
  CHECK(vertices.message.find("announces 999999999999 vertices") != std::string::npos && vertices.output->GetNumberOfPoints() == 0);
  const Reading face = readText(path, "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n2000000000 0 1 2\n");
  std::printf("%s\n", face.message.c_str());
  CHECK(face.message.find("face 0 has 2000000000 vertices") != std::string::npos && face.output->GetNumberOfPoints() == 0);
}

TEST(MutatedFilesGiveAValidMeshOrOneClearError)
{
  const std::string path = outputFile("fuzz-mutated.off");
  std::mt19937 random(20261123);
  int errors = 0, read = 0, unclear = 0, broken = 0;
  const int files = 5000;
  for (int f = 0; f < files; ++f)
  {
    std::string text = seeds()[f % seeds().size()];
    for (int m = std::uniform_int_distribution<int>(1, 3)(random); m > 0; --m)
      text = testing::mutate(text, random);
    const Reading r = readText(path, text);
    if (r.errors > 0)
    {
      ++errors;
      // one message, naming the file, and nothing half-read left in the output
      const bool clear = r.errors == 1 && r.message.find("OFF file '" + path + "'") != std::string::npos &&
        r.output->GetNumberOfPoints() == 0 && r.output->GetNumberOfCells() == 0;
      if (!clear && unclear++ < 5)
        std::printf("unclear error on file %d (%d messages, %lld points): %s\n", f, r.errors, static_cast<long long>(r.output->GetNumberOfPoints()),
          r.message.c_str());
    }
    else
    {
      ++read;
      if (!valid(r.output) && broken++ < 5)
        std::printf("file %d read without error into an invalid mesh\n", f);
    }
  }
  std::printf("%d mutated files: %d errors, %d read as valid meshes\n", files, errors, read);
  CHECK(unclear == 0);
  CHECK(broken == 0);
  // the mutations reach both outcomes (a fuzzer that only produced errors would test less)
  CHECK(errors > files / 2 && read > 0);
}

TEST_MAIN
