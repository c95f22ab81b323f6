// vtkMeshFileReader and vtkMeshVariantWriter on Abaqus/CalculiX decks: VTK's cells in VTK's
// orientation, the sets as arrays, a variant written from a deformation, data from elsewhere
// refused; the AVS UCD reader declines decks.
#include "../TestHarness.h"
#include "FormatFiles.h"
#include "vtkAVSucdReaderUnlessDeck.h"
#include "vtkMeshFileReader.h"
#include "vtkMeshVariantWriter.h"

#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkCellTypes.h>
#include <vtkCellValidator.h>
#include <vtkCommand.h>
#include <vtkDataArray.h>
#include <vtkFieldData.h>
#include <vtkIdTypeArray.h>
#include <vtkNew.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>

#include <Eigen/Dense>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace fs = std::filesystem;

namespace
{
using mlsformats::readFile;
using testing::writeFile;

std::string folder(const std::string& name)
{
  return testing::freshFolder("meshfile", name);
}

struct Messages : vtkCommand
{
  static Messages* New() { return new Messages; }
  void Execute(vtkObject*, unsigned long, void* message) override
  {
    ++count;
    text += static_cast<const char*>(message);
    std::printf("expected message: %s\n", static_cast<const char*>(message));
  }
  int count = 0;
  std::string text;
};

// The determinant of the cell's Jacobian (d x / d parametric) at its parametric centre.
double centreJacobian(vtkCell* cell)
{
  const int n = cell->GetNumberOfPoints();
  double centre[3];
  cell->GetParametricCenter(centre);
  std::vector<double> derivatives(3 * n);
  cell->InterpolateDerivs(centre, derivatives.data());
  Eigen::Matrix3d jacobian = Eigen::Matrix3d::Zero();
  for (int k = 0; k < n; ++k)
  {
    double x[3];
    cell->GetPoints()->GetPoint(k, x);
    for (int a = 0; a < 3; ++a)
    {
      for (int b = 0; b < 3; ++b)
      {
        jacobian(a, b) += derivatives[a * n + k] * x[b];
      }
    }
  }
  return jacobian.determinant();
}

// A unit prism (triangle (0,0) (1,0) (0,1), z 0 to 1) as C3D6 and C3D15, and a C3D8 and C3D20
// unit cube beside it, in Abaqus' node order (the bottom turning counter-clockwise seen from the
// top, as Abaqus and Gmsh write it).
std::string solidsDeck(const std::string& dir)
{
  std::string text = "*NODE\n";
  const double corners[][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 0, 1, 1 } };
  const int edges[][2] = { { 0, 1 }, { 1, 2 }, { 2, 0 }, { 3, 4 }, { 4, 5 }, { 5, 3 }, { 0, 3 }, { 1, 4 }, { 2, 5 } };
  std::vector<std::array<double, 3>> prism;
  for (const auto& c : corners)
  {
    prism.push_back({ c[0], c[1], c[2] });
  }
  for (const auto& e : edges)
  {
    prism.push_back({ (corners[e[0]][0] + corners[e[1]][0]) / 2, (corners[e[0]][1] + corners[e[1]][1]) / 2,
      (corners[e[0]][2] + corners[e[1]][2]) / 2 });
  }
  const double cube[][3] = { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } };
  const int cubeEdges[][2] = { { 0, 1 }, { 1, 2 }, { 2, 3 }, { 3, 0 }, { 4, 5 }, { 5, 6 }, { 6, 7 }, { 7, 4 }, { 0, 4 }, { 1, 5 },
    { 2, 6 }, { 3, 7 } };
  std::vector<std::array<double, 3>> hexahedron;
  for (const auto& c : cube)
  {
    hexahedron.push_back({ c[0] + 2, c[1], c[2] });
  }
  for (const auto& e : cubeEdges)
  {
    hexahedron.push_back({ (cube[e[0]][0] + cube[e[1]][0]) / 2 + 2, (cube[e[0]][1] + cube[e[1]][1]) / 2, (cube[e[0]][2] + cube[e[1]][2]) / 2 });
  }
  int id = 1;
  for (const auto& x : prism)
  {
    text += std::to_string(id++) + ", " + std::to_string(x[0]) + ", " + std::to_string(x[1]) + ", " + std::to_string(x[2]) + "\n";
  }
  for (const auto& x : hexahedron)
  {
    text += std::to_string(id++) + ", " + std::to_string(x[0]) + ", " + std::to_string(x[1]) + ", " + std::to_string(x[2]) + "\n";
  }
  text += "*ELEMENT, TYPE=C3D6, ELSET=linear\n1, 1, 2, 3, 4, 5, 6\n";
  text += "*ELEMENT, TYPE=C3D15, ELSET=quadratic\n2, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15\n";
  text += "*ELEMENT, TYPE=C3D8R, ELSET=linear\n3, 16, 17, 18, 19, 20, 21, 22, 23\n";
  text += "*ELEMENT, TYPE=C3D20R, ELSET=quadratic\n4";
  for (int k = 16; k <= 35; ++k)
  {
    text += (k == 31 ? ",\n" : ", ") + std::to_string(k); // continued after 15 nodes, as Abaqus writes it
  }
  text += "\n*NSET, NSET=bottom\n1, 2, 3, 7, 8, 9\n*SURFACE, NAME=side\nquadratic, S3\n";
  return writeFile(dir + "/solids.inp", text);
}
} // namespace

TEST(CellsInVTKsOrientation)
{
  const std::string dir = folder("solids");
  vtkNew<vtkMeshFileReader> reader;
  reader->SetFileName(solidsDeck(dir).c_str());
  reader->Update();
  vtkUnstructuredGrid* grid = reader->GetOutput();
  CHECK(grid->GetNumberOfPoints() == 35);
  CHECK(grid->GetNumberOfCells() == 4);
  CHECK(grid->GetCellType(0) == VTK_WEDGE && grid->GetCellType(1) == VTK_QUADRATIC_WEDGE);
  CHECK(grid->GetCellType(2) == VTK_HEXAHEDRON && grid->GetCellType(3) == VTK_QUADRATIC_HEXAHEDRON);
  // the linear cells pass VTK's validator (its faces point outwards); each quadratic cell's
  // Jacobian has the sign of its linear twin's (the validator misjudges quadratic faces)
  vtkNew<vtkCellValidator> validator;
  validator->SetInputConnection(reader->GetOutputPort());
  validator->Update();
  vtkDataArray* state = validator->GetOutput()->GetCellData()->GetArray("ValidityState");
  CHECK(state->GetTuple1(0) == 0 && state->GetTuple1(2) == 0);
  const double wedge = centreJacobian(grid->GetCell(0)), quadraticWedge = centreJacobian(grid->GetCell(1));
  const double hexahedron = centreJacobian(grid->GetCell(2)), quadraticHexahedron = centreJacobian(grid->GetCell(3));
  // exact: the quadratic cells' midside nodes are at their edges' middles, so they map as the linear ones
  CHECK_NEAR(quadraticWedge, wedge, 1e-12);
  CHECK_NEAR(quadraticHexahedron, hexahedron, 1e-12);
  CHECK(std::abs(wedge) > 0.1);
  // the sets
  vtkDataArray* bottom = grid->GetPointData()->GetArray("bottom");
  CHECK(bottom && bottom->GetTuple1(0) == 1 && bottom->GetTuple1(6) == 1 && bottom->GetTuple1(3) == 0);
  vtkDataArray* linear = grid->GetCellData()->GetArray("linear");
  CHECK(linear && linear->GetTuple1(0) == 1 && linear->GetTuple1(1) == 0 && linear->GetTuple1(2) == 1 && linear->GetTuple1(3) == 0);
  // face S3 of the C3D15 (1-4-5-2 with its midside nodes 7, 10, 13, 14) and of the C3D20 (1-5-6-2: 16, 20, 21, 17, 24, 28, 32, 33)
  vtkDataArray* side = grid->GetPointData()->GetArray("side");
  int count = 0;
  for (vtkIdType i = 0; side && i < 35; ++i)
  {
    count += side->GetTuple1(i) != 0;
  }
  CHECK(count == 16);
  for (const int id : { 1, 4, 5, 2, 7, 10, 13, 14, 16, 20, 21, 17, 24, 28, 32, 33 })
  {
    CHECK(side && side->GetTuple1(id - 1) == 1);
  }
  vtkDataArray* nodeIds = grid->GetPointData()->GetArray("NodeId");
  CHECK(nodeIds && nodeIds->GetTuple1(34) == 35);
  vtkDataArray* elementIds = grid->GetCellData()->GetArray("ElementId");
  CHECK(elementIds && elementIds->GetTuple1(3) == 4);
  vtkStringArray* source = vtkStringArray::SafeDownCast(grid->GetFieldData()->GetAbstractArray("SourceFile"));
  CHECK(source && source->GetValue(0) == dir + "/solids.inp");
}

TEST(VariantOfADeformation)
{
  const std::string dir = folder("variant");
  const std::string deck = solidsDeck(dir);
  vtkNew<vtkMeshFileReader> reader;
  reader->SetFileName(deck.c_str());
  reader->Update();
  // a deformation: the points moved, the point data kept (as MLS Deform's output)
  vtkNew<vtkUnstructuredGrid> moved;
  moved->DeepCopy(reader->GetOutput());
  double x[3];
  moved->GetPoint(4, x);
  x[2] += 0.25;
  moved->GetPoints()->SetPoint(4, x);
  vtkNew<vtkMeshVariantWriter> writer;
  writer->SetInputData(moved);
  writer->SetFileName((dir + "/variant/solids.inp").c_str());
  CHECK(writer->Write() == 1);
  CHECK(writer->GetErrorCode() == 0);
  std::string expected = readFile(deck);
  expected.replace(expected.find("5, 1.000000, 0.000000, 1.000000"), 31, "5, 1.000000, 0.000000, 1.25");
  CHECK(readFile(dir + "/variant/solids.inp") == expected);
  vtkNew<vtkMeshFileReader> again;
  again->SetFileName((dir + "/variant/solids.inp").c_str());
  again->Update();
  CHECK(again->GetOutput()->GetPoint(4)[2] == 1.25);

  // data from elsewhere: a point less, another id, no NodeId, the source itself, an existing file
  vtkNew<Messages> errors;
  writer->AddObserver(vtkCommand::ErrorEvent, errors);
  vtkNew<vtkUnstructuredGrid> fewer;
  vtkNew<vtkPoints> points;
  points->SetNumberOfPoints(34);
  fewer->SetPoints(points);
  vtkNew<vtkIdTypeArray> ids;
  ids->SetName("NodeId");
  ids->SetNumberOfValues(34);
  for (vtkIdType i = 0; i < 34; ++i)
  {
    ids->SetValue(i, i + 1);
  }
  fewer->GetPointData()->AddArray(ids);
  writer->SetInputData(fewer);
  writer->SetSourceFile(deck.c_str());
  writer->SetFileName((dir + "/fewer.inp").c_str());
  writer->Write();
  CHECK(errors->count == 1 && errors->text.find("34 points") != std::string::npos && !fs::exists(dir + "/fewer.inp"));
  CHECK(writer->GetErrorCode() != 0);
  writer->SetSourceFile("");
  vtkIdTypeArray::SafeDownCast(moved->GetPointData()->GetArray("NodeId"))->SetValue(3, 99);
  writer->SetInputData(moved);
  writer->SetFileName((dir + "/other.inp").c_str());
  writer->Write();
  CHECK(errors->count == 2 && errors->text.find("node 99 is not in") != std::string::npos && !fs::exists(dir + "/other.inp"));
  moved->GetPointData()->RemoveArray("NodeId");
  writer->Write();
  CHECK(errors->count == 3 && errors->text.find("has no node ids (point data NodeId") != std::string::npos);
  writer->SetInputData(again->GetOutput()); // read from the variant: the variant is its source
  writer->SetFileName((dir + "/variant/solids.inp").c_str());
  writer->OverwriteOn();
  writer->Write();
  CHECK(errors->count == 4 && errors->text.find("is a file of the source") != std::string::npos);
  CHECK(again->GetOutput()->GetPoint(4)[2] == 1.25);
  writer->OverwriteOff();
  writer->SetInputData(reader->GetOutput());
  writer->Write();
  CHECK(errors->count == 5 && errors->text.find("exists already") != std::string::npos);
  CHECK(readFile(dir + "/variant/solids.inp") == expected);
}

TEST(ErrorsNameTheFileAndLineAndLeaveAnEmptyOutput)
{
  const std::string dir = folder("errors");
  vtkNew<vtkMeshFileReader> reader;
  vtkNew<Messages> errors, warnings;
  reader->AddObserver(vtkCommand::ErrorEvent, errors);
  reader->AddObserver(vtkCommand::WarningEvent, warnings);
  reader->SetFileName(writeFile(dir + "/bad.inp", "*NODE\n1, 0, 0, 0\n2, x, 0, 0\n").c_str());
  reader->Update();
  CHECK(errors->count == 1 && errors->text.find("bad.inp:3: node 2's coordinate \"x\"") != std::string::npos);
  CHECK(reader->GetOutput()->GetNumberOfPoints() == 0);
  reader->SetFileName(writeFile(dir + "/beam.inp", "*NODE\n1, 0, 0, 0\n2, 1, 0, 0\n*ELEMENT, TYPE=SPRINGA\n1, 1, 2\n").c_str());
  reader->Update();
  CHECK(warnings->count == 1 && warnings->text.find("beam.inp:4: element type SPRINGA is not supported") != std::string::npos);
  CHECK(reader->GetOutput()->GetNumberOfPoints() == 2 && reader->GetOutput()->GetNumberOfCells() == 0);
  // a missing file, a folder, a file of no format read: each said as what it is
  reader->SetFileName((dir + "/none.inp").c_str());
  reader->Update();
  CHECK(errors->count == 2 && std::string(reader->GetLastError()).find("none.inp' does not exist") != std::string::npos);
  reader->SetFileName(dir.c_str());
  reader->Update();
  CHECK(errors->count == 3 && std::string(reader->GetLastError()).find("is a folder: name the mesh file in it") != std::string::npos);
  reader->SetFileName(writeFile(dir + "/box.geo", "Box(1) = {0, 0, 0, 1, 1, 1};\n").c_str());
  reader->Update();
  CHECK(errors->count == 4 && std::string(reader->GetLastError()).find("box.geo' is of none of the formats read") != std::string::npos);
}

TEST(AVSReaderDeclinesDecksOnly)
{
  const std::string dir = folder("avs");
  const std::string deck = writeFile(dir + "/deck.inp", "** a comment first\n*NODE\n1, 0, 0, 0\n");
  const std::string avs = writeFile(dir + "/ucd.inp", "# AVS UCD\n3 1 0 0 0\n1 0 0 0\n2 1 0 0\n3 0 1 0\n1 1 tri 1 2 3\n");
  vtkNew<vtkAVSucdReaderUnlessDeck> ucd;
  CHECK(ucd->CanReadFile(deck.c_str()) == 0 && ucd->CanReadFile(avs.c_str()) == 1);
  CHECK(vtkMeshFileReader::CanReadFile(deck.c_str()) == 1 && vtkMeshFileReader::CanReadFile(avs.c_str()) == 0);
  ucd->SetFileName(avs.c_str());
  ucd->Update();
  CHECK(ucd->GetOutput()->GetNumberOfCells() == 1);
}

TEST_MAIN
