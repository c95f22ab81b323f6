// vtkOFFReader: OFF, COFF, NOFF headers, comments, polygons of any size, malformed files.
#include "../TestHarness.h"
#include "vtkOFFReader.h"

#include <vtkCellArray.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>

#include <cstdio>
#include <fstream>
#include <string>

namespace
{
std::string writeFile(const std::string& name, const std::string& text)
{
  const std::string path = std::string(TEST_OUTPUT_DIR) + "/" + name;
  std::ofstream(path) << text;
  return path;
}

struct ErrorCount : vtkCommand
{
  static ErrorCount* New() { return new ErrorCount; }
  void Execute(vtkObject*, unsigned long, void* message) override
  {
    ++count;
    std::printf("expected error: %s\n", static_cast<const char*>(message));
  }
  int count = 0;
};

vtkPolyData* read(vtkOFFReader* reader, const std::string& path, ErrorCount* errors)
{
  reader->SetFileName(path.c_str());
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->Update();
  return reader->GetOutput();
}
}

TEST(PlainOFFWithCommentsAndMixedPolygons)
{
  // a unit cube's bottom quad, a triangle and a pentagon; comments everywhere, counts on the header line
  const std::string path = writeFile("mixed.off", "OFF # header comment\n"
                                                  "# a full-line comment\n"
                                                  "6 3 0\n"
                                                  "0 0 0\n1 0 0  # trailing comment\n1 1 0\n0 1 0\n0.5 1.5 0\n-0.5 0.5 0\n"
                                                  "4 0 1 2 3\n"
                                                  "3 2 4 3 255 0 0\n" // a face color is skipped
                                                  "5 0 1 2 4 5\n");
  vtkNew<vtkOFFReader> reader;
  vtkNew<ErrorCount> errors;
  vtkPolyData* out = read(reader, path, errors);
  CHECK(errors->count == 0);
  CHECK(out->GetNumberOfPoints() == 6);
  CHECK(out->GetNumberOfPolys() == 3);
  CHECK(out->GetCell(0)->GetNumberOfPoints() == 4);
  CHECK(out->GetCell(1)->GetNumberOfPoints() == 3);
  CHECK(out->GetCell(2)->GetNumberOfPoints() == 5);
  CHECK_NEAR(out->GetPoint(4)[1], 1.5, 0); // 1.5 is exact in binary (float and double): parsed exactly
  CHECK(out->GetCell(1)->GetPointId(1) == 4);
  CHECK(vtkOFFReader::CanReadFile(path.c_str()) == 1);
}

TEST(ColorAndNormalHeaders)
{
  const std::string coff = writeFile("colored.off", "COFF\n3 1 0\n0 0 0 255 0 0 255\n1 0 0 0 255 0 255\n0 1 0 0 0 1.0 1.0\n3 0 1 2\n");
  vtkNew<vtkOFFReader> reader;
  vtkNew<ErrorCount> errors;
  vtkPolyData* out = read(reader, coff, errors);
  CHECK(errors->count == 0);
  vtkDataArray* colors = out->GetPointData()->GetArray("Colors");
  CHECK(colors && colors->GetNumberOfComponents() == 4);
  CHECK(colors && colors->GetComponent(0, 0) == 255 && colors->GetComponent(1, 1) == 255 && colors->GetComponent(2, 2) == 255);

  const std::string noff = writeFile("normals.off", "NOFF\n3 1 0\n0 0 0 0 0 1\n1 0 0 0 0 1\n0 1 0 0 0 1\n3 0 1 2\n");
  vtkNew<vtkOFFReader> normalsReader;
  out = read(normalsReader, noff, errors);
  CHECK(errors->count == 0);
  CHECK(out->GetPointData()->GetNormals() && out->GetPointData()->GetNormals()->GetComponent(2, 2) == 1.0);
  CHECK(out->GetNumberOfPolys() == 1);
}

TEST(MalformedFilesGiveClearErrors)
{
  struct Case
  {
    const char* name;
    const char* text;
  };
  for (const Case& c : { Case{ "noheader.off", "3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n" },
         Case{ "truncated.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n" },
         Case{ "badindex.off", "OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n" },
         Case{ "notanumber.off", "OFF\n3 1 0\n0 0 x\n1 0 0\n0 1 0\n3 0 1 2\n" } })
  {
    vtkNew<vtkOFFReader> reader;
    vtkNew<ErrorCount> errors;
    vtkPolyData* out = read(reader, writeFile(c.name, c.text), errors);
    CHECK(errors->count == 1);
    CHECK(out->GetNumberOfPoints() == 0);
  }
  vtkNew<vtkOFFReader> reader;
  vtkNew<ErrorCount> errors;
  read(reader, "/nonexistent/file.off", errors);
  CHECK(errors->count == 1);
  CHECK(vtkOFFReader::CanReadFile("/nonexistent/file.off") == 0);
}

TEST_MAIN
