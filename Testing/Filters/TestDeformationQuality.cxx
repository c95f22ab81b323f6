// vtkDeformationQuality: the scaled Jacobian and OpenFOAM's face measures against exact values.
#include "../TestHarness.h"
#include "FilterTestUtilities.h"
#include "vtkDeformationQuality.h"

#include <vtkCell.h>
#include <vtkCellData.h>
#include <vtkMeshQuality.h>
#include <vtkPolyData.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>

namespace
{
vtkSmartPointer<vtkUnstructuredGrid> singleCell(int type, const std::vector<std::array<double, 3>>& corners)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  std::vector<vtkIdType> ids;
  for (const auto& c : corners)
    ids.push_back(points->InsertNextPoint(c.data()));
  grid->SetPoints(points);
  grid->InsertNextCell(type, static_cast<vtkIdType>(ids.size()), ids.data());
  return grid;
}

/// cells x 1 x 1 unit hexahedra in a row along x, then y += shear * x.
vtkSmartPointer<vtkUnstructuredGrid> hexRow(int cells, double shear, bool polyhedra = false)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  vtkNew<vtkPoints> points;
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 2; ++j)
      for (int i = 0; i <= cells; ++i)
        points->InsertNextPoint(i, j + shear * i, k);
  grid->SetPoints(points);
  const vtkIdType row = cells + 1;
  for (vtkIdType i = 0; i < cells; ++i)
  {
    auto v = [&](int a, int b, int c) { return i + a + row * b + 2 * row * c; };
    const vtkIdType hex[8] = { v(0, 0, 0), v(1, 0, 0), v(1, 1, 0), v(0, 1, 0), v(0, 0, 1), v(1, 0, 1), v(1, 1, 1), v(0, 1, 1) };
    if (!polyhedra)
    {
      grid->InsertNextCell(VTK_HEXAHEDRON, 8, hex);
      continue;
    }
    const vtkIdType faces[30] = { 4, hex[0], hex[3], hex[2], hex[1], 4, hex[4], hex[5], hex[6], hex[7], 4, hex[0], hex[1],
      hex[5], hex[4], 4, hex[1], hex[2], hex[6], hex[5], 4, hex[2], hex[3], hex[7], hex[6], 4, hex[3], hex[0], hex[4], hex[7] };
    grid->InsertNextCell(VTK_POLYHEDRON, 8, hex, 6, faces);
  }
  return grid;
}

double cellValue(vtkDataSet* data, const char* name, vtkIdType cell = 0)
{
  vtkDataArray* array = data->GetCellData()->GetArray(name);
  return array ? array->GetTuple1(cell) : std::numeric_limits<double>::quiet_NaN();
}

double scaledJacobian(vtkUnstructuredGrid* grid)
{
  vtkNew<vtkDeformationQuality> quality;
  quality->SetInputData(grid);
  quality->Update();
  return cellValue(quality->GetOutput(), "ScaledJacobian");
}

/// The summary table's value for a measure (row) and statistic (column).
double summaryValue(vtkDeformationQuality* quality, const std::string& measure, const char* column)
{
  auto* table = vtkTable::SafeDownCast(quality->GetOutputDataObject(2));
  auto* names = vtkStringArray::SafeDownCast(table->GetColumnByName("Measure"));
  vtkDataArray* values = vtkDataArray::SafeDownCast(table->GetColumnByName(column));
  for (vtkIdType r = 0; names && values && r < names->GetNumberOfValues(); ++r)
    if (names->GetValue(r) == measure)
      return values->GetTuple1(r);
  return std::numeric_limits<double>::quiet_NaN();
}

/// The points of a block of cells^3 unit cubes, each moved along each axis by up to jitter (a fixed
/// pseudo-random pattern: std::mt19937's sequence is the same on every platform).
vtkSmartPointer<vtkPoints> blockPoints(int cells, double jitter)
{
  auto points = vtkSmartPointer<vtkPoints>::New();
  std::mt19937 random(1);
  auto offset = [&] { return jitter * (2.0 * random() / std::mt19937::max() - 1); };
  for (int k = 0; k <= cells; ++k)
    for (int j = 0; j <= cells; ++j)
      for (int i = 0; i <= cells; ++i)
      {
        const double x = i + offset(), y = j + offset(), z = k + offset();
        points->InsertNextPoint(x, y, z);
      }
  return points;
}

/// The cells of blockPoints(cells, ...) on points, as VTK_VOXEL or as VTK_HEXAHEDRON cells (the
/// voxel's points 0, 1, 3, 2, 4, 5, 7, 6 in a hexahedron's order).
vtkSmartPointer<vtkUnstructuredGrid> block(vtkPoints* points, int cells, int type)
{
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  grid->SetPoints(points);
  const vtkIdType row = cells + 1;
  for (vtkIdType k = 0; k < cells; ++k)
    for (vtkIdType j = 0; j < cells; ++j)
      for (vtkIdType i = 0; i < cells; ++i)
      {
        auto v = [&](int a, int b, int c) { return i + a + row * (j + b) + row * row * (k + c); };
        const vtkIdType voxel[8] = { v(0, 0, 0), v(1, 0, 0), v(0, 1, 0), v(1, 1, 0), v(0, 0, 1), v(1, 0, 1), v(0, 1, 1), v(1, 1, 1) };
        const vtkIdType hex[8] = { voxel[0], voxel[1], voxel[3], voxel[2], voxel[4], voxel[5], voxel[7], voxel[6] };
        grid->InsertNextCell(type, 8, type == VTK_VOXEL ? voxel : hex);
      }
  return grid;
}
}

TEST(ScaledJacobianOfIdealAndInvertedElements)
{
  const double cube = scaledJacobian(singleCell(VTK_HEXAHEDRON,
    { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } }));
  const double s = std::sqrt(3.0) / 2, h = std::sqrt(2.0 / 3);
  const std::vector<std::array<double, 3>> regular = { { 0, 0, 0 }, { 1, 0, 0 }, { 0.5, s, 0 }, { 0.5, s / 3, h } };
  const double tet = scaledJacobian(singleCell(VTK_TETRA, regular));
  // the same tetrahedron with two corners swapped is inside out
  const double inverted = scaledJacobian(singleCell(VTK_TETRA, { regular[1], regular[0], regular[2], regular[3] }));
  std::printf("unit cube %.15g, regular tetrahedron %.15g, inverted %.15g\n", cube, tet, inverted);
  // Every bound below is round-off: the corners are exact (dyadic or the given doubles) and the
  // measures are a few dozen operations on values <= 2, a few ulps (eps = 2.2e-16); 1e-14 = 45 eps.
  CHECK_NEAR(cube, 1.0, 1e-14);
  // verdict normalizes tetrahedra with a rounded sqrt(2) constant: 1 only to 5e-8, twice that allowed
  CHECK_NEAR(tet, 1.0, 1e-7);
  CHECK_NEAR(inverted, -1.0, 1e-7);
  // wedges and pyramids are measured (an undistorted prism and a square pyramid are valid)
  // VTK 9.2's wedge: (0, 1, 2) turns away from (3, 4, 5), as its faces and its OpenFOAM reader have it
  const double wedge = scaledJacobian(singleCell(VTK_WEDGE, { { 0, 0, 0 }, { 0.5, s, 0 }, { 1, 0, 0 }, { 0, 0, 1 }, { 0.5, s, 1 }, { 1, 0, 1 } }));
  const double pyramid = scaledJacobian(singleCell(VTK_PYRAMID, { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0.5, 0.5, std::sqrt(0.5) } }));
  std::printf("prism %.15g, pyramid %.15g\n", wedge, pyramid);
  // both are ideal (right prism, equilateral faces): 1 up to verdict's rounded constants, as for
  // the tetrahedron (1e-7), and never above 1 beyond round-off
  CHECK(wedge > 1 - 1e-7 && wedge <= 1 + 1e-14);
  CHECK(pyramid > 1 - 1e-7 && pyramid <= 1 + 1e-14);
  // a polygon has no scaled Jacobian
  CHECK(std::isnan(scaledJacobian(singleCell(VTK_TRIANGLE, { { 0, 0, 0 }, { 1, 0, 0 }, { 0, 1, 0 } }))));
}

TEST(ShearedHexahedraAgainstHandValues)
{
  // y += h x maps every unit cube onto a parallelepiped: at each corner the edge vectors are
  // (1, h, 0), (0, 1, 0), (0, 0, 1), so the scaled Jacobian is 1 / sqrt(1 + h^2). The shared
  // faces stay in the planes x = i while the centres move by h per cell: non-orthogonality
  // atan(h), and the line between the centres passes through the face centre: skewness 0.
  const double shear = 0.5;
  vtkSmartPointer<vtkUnstructuredGrid> original = hexRow(3, 0), sheared = hexRow(3, shear);
  vtkNew<vtkDeformationQuality> quality;
  quality->SetInputData(sheared);
  quality->SetOriginalData(original);
  quality->Update();
  const double expectedJacobian = 1 / std::sqrt(1 + shear * shear), expectedAngle = std::atan(shear) * 180 / M_PI;
  for (vtkIdType c = 0; c < 3; ++c)
  {
    CHECK_NEAR(cellValue(quality->GetOutput(), "ScaledJacobian", c), expectedJacobian, 1e-14); // round-off
    CHECK_NEAR(cellValue(quality->GetOutput(), "OriginalScaledJacobian", c), 1.0, 1e-14);
  }
  auto* faces = vtkPolyData::SafeDownCast(quality->GetOutputDataObject(1));
  CHECK(faces->GetNumberOfCells() == 2);
  for (vtkIdType f = 0; f < 2; ++f)
  {
    // the angle through acos: a few ulps of the cosine times d(acos)/d(cos) = 1/sin(26.6 deg) = 2.2
    // times 180/pi: 3e-14 degrees per ulp, 1e-12 allows 30 ulps; near 0 acos turns a cosine k ulps
    // below 1 into sqrt(2 k eps) rad, 1.7e-6 degrees for k = 2 (see TestFaceQuality)
    CHECK_NEAR(cellValue(faces, "NonOrthogonality", f), expectedAngle, 1e-12);
    CHECK_NEAR(cellValue(faces, "Skewness", f), 0.0, 1e-14);
    CHECK_NEAR(cellValue(faces, "OriginalNonOrthogonality", f), 0.0, 2e-6);
    CHECK(cellValue(faces, "Neighbour", f) == cellValue(faces, "Owner", f) + 1);
  }
  CHECK_NEAR(summaryValue(quality, "ScaledJacobian", "Min"), expectedJacobian, 1e-14); // the same values as above
  CHECK_NEAR(summaryValue(quality, "ScaledJacobian", "OriginalMax"), 1.0, 1e-14);
  CHECK_NEAR(summaryValue(quality, "NonOrthogonality", "Max"), expectedAngle, 1e-12);
  CHECK_NEAR(summaryValue(quality, "NonOrthogonality", "OriginalMean"), 0.0, 2e-6);
  CHECK(summaryValue(quality, "InvertedCells", "Max") == 0);
  // the cells' worst faces: the middle cell has two, the end cells one
  CHECK_NEAR(cellValue(quality->GetOutput(), "MaxNonOrthogonality", 1), expectedAngle, 1e-12);
  // the input is not modified
  CHECK(sheared->GetCellData()->GetNumberOfArrays() == 0);
}

TEST(PolyhedraHaveFaceMeasures)
{
  // The same sheared row as vtkPolyhedron cells: the face measures are those of the hexahedra,
  // the scaled Jacobian is not defined.
  const double shear = 0.5;
  vtkNew<vtkDeformationQuality> quality;
  quality->SetInputData(hexRow(3, shear, true));
  quality->SetOriginalData(hexRow(3, 0, true));
  quality->Update();
  auto* faces = vtkPolyData::SafeDownCast(quality->GetOutputDataObject(1));
  CHECK(faces->GetNumberOfCells() == 2);
  CHECK_NEAR(cellValue(faces, "NonOrthogonality", 0), std::atan(shear) * 180 / M_PI, 1e-12); // as for the hexahedra
  CHECK(std::isnan(cellValue(quality->GetOutput(), "ScaledJacobian")));
  CHECK(std::isnan(summaryValue(quality, "ScaledJacobian", "Min")));
}

TEST(InvertedCellsAreCounted)
{
  // push the middle layer of points of a 2-cell row past the far end: the first cell turns
  // inside out
  vtkSmartPointer<vtkUnstructuredGrid> original = hexRow(2, 0), folded = hexRow(2, 0);
  for (vtkIdType i = 0; i < folded->GetNumberOfPoints(); ++i)
  {
    double p[3];
    folded->GetPoint(i, p);
    if (p[0] == 0)
      folded->GetPoints()->SetPoint(i, 3, p[1], p[2]);
  }
  vtkNew<vtkDeformationQuality> quality;
  quality->SetInputData(folded);
  quality->SetOriginalData(original);
  quality->Update();
  CHECK(cellValue(quality->GetOutput(), "ScaledJacobian", 0) < 0);
  CHECK(summaryValue(quality, "InvertedCells", "Min") == 1);
  CHECK(summaryValue(quality, "InvertedCells", "OriginalMin") == 0);
  CHECK(quality->GetOutput()->GetFieldData()->GetArray("InvertedCells")->GetTuple1(0) == 1);
}

TEST(BadInputIsReported)
{
  vtkNew<vtkDeformationQuality> quality;
  auto messages = MessageCollector::watch(quality);
  quality->SetInputData(vtkSmartPointer<vtkUnstructuredGrid>::New());
  quality->Update();
  CHECK(messages->errorContains("no cells"));

  vtkSmartPointer<vtkUnstructuredGrid> broken = hexRow(2, 0);
  broken->GetPoints()->SetPoint(0, std::nan(""), 0, 0);
  quality->SetInputData(broken);
  quality->Update();
  CHECK(messages->errorContains("NaN"));

  quality->SetInputData(hexRow(2, 0));
  quality->SetOriginalData(hexRow(3, 0));
  quality->Update();
  CHECK(messages->errorContains("same mesh before and after"));
  CHECK(quality->GetOutput()->GetNumberOfCells() == 2); // the input passes through
}

TEST(VoxelsAreMeasuredAsHexahedra)
{
  // A jittered 3 x 3 x 3 block, then the same with an interior point pushed out through the far
  // side (4 cells inverted), as voxels and as hexahedra: the same faces, so the same measures. A
  // voxel's faces are pixels, whose points VTK lists in raster order, not around the face: measured
  // as such (self-crossing polygons) the rest block had 25 inverted cells of 27.
  const int cells = 3;
  vtkSmartPointer<vtkPoints> rest = blockPoints(cells, 0.15), folded = blockPoints(cells, 0.15);
  const vtkIdType interior = 1 + (cells + 1) + (cells + 1) * (cells + 1); // the point (1, 1, 1)
  double p[3];
  folded->GetPoint(interior, p);
  folded->SetPoint(interior, p[0] + 2.5, p[1], p[2]);
  vtkNew<vtkDeformationQuality> voxels, hexahedra;
  voxels->SetInputData(block(folded, cells, VTK_VOXEL));
  voxels->SetOriginalData(block(rest, cells, VTK_VOXEL));
  voxels->Update();
  hexahedra->SetInputData(block(folded, cells, VTK_HEXAHEDRON));
  hexahedra->SetOriginalData(block(rest, cells, VTK_HEXAHEDRON));
  hexahedra->Update();
  auto* voxelFaces = vtkPolyData::SafeDownCast(voxels->GetOutputDataObject(1));
  auto* hexFaces = vtkPolyData::SafeDownCast(hexahedra->GetOutputDataObject(1));
  CHECK(voxelFaces->GetNumberOfCells() == 3 * cells * cells * (cells - 1));
  CHECK(hexFaces->GetNumberOfCells() == voxelFaces->GetNumberOfCells());
  // The same polygons from another first point: their centres and areas are sums in another order,
  // equal up to round-off, which acos magnifies for small angles: the largest difference is 4.5e-13
  // degrees (1e-15 in skewness), 1e-11 leaves a margin of 20.
  for (const char* name : { "NonOrthogonality", "Skewness", "OriginalNonOrthogonality", "OriginalSkewness" })
  {
    double largest = 0;
    for (vtkIdType f = 0; f < hexFaces->GetNumberOfCells(); ++f)
    {
      largest = std::max(largest, std::abs(cellValue(voxelFaces, name, f) - cellValue(hexFaces, name, f)));
      CHECK(cellValue(voxelFaces, "Owner", f) == cellValue(hexFaces, "Owner", f));
      CHECK(cellValue(voxelFaces, "Neighbour", f) == cellValue(hexFaces, "Neighbour", f));
    }
    std::printf("%s: largest difference voxel - hexahedron %.3g\n", name, largest);
    CHECK(largest < 1e-11);
  }
  for (const char* measure : { "NonOrthogonality", "Skewness" })
    for (const char* column : { "Max", "OriginalMax" })
    {
      std::printf("%s %s: voxels %.15g, hexahedra %.15g\n", measure, column, summaryValue(voxels, measure, column),
        summaryValue(hexahedra, measure, column));
      CHECK_NEAR(summaryValue(voxels, measure, column), summaryValue(hexahedra, measure, column), 1e-11);
    }
  const double inverted = summaryValue(hexahedra, "InvertedCells", "Max");
  std::printf("inverted cells: voxels %g (before %g), hexahedra %g (before %g)\n", summaryValue(voxels, "InvertedCells", "Max"),
    summaryValue(voxels, "InvertedCells", "OriginalMax"), inverted, summaryValue(hexahedra, "InvertedCells", "OriginalMax"));
  CHECK(inverted > 0);
  CHECK(summaryValue(voxels, "InvertedCells", "Max") == inverted);
  CHECK(summaryValue(voxels, "InvertedCells", "OriginalMax") == 0);
  CHECK(summaryValue(hexahedra, "InvertedCells", "OriginalMax") == 0);
}

TEST(LinearElementsHaveVerdictsScaledJacobian)
{
  // jittered tetrahedra, hexahedra and wedges: the corner Jacobians are verdict's (the wedge's on
  // its mirror image: verdict's wedge turns (0, 1, 2) the other way). Bounds: verdict's rounded sqrt(2)
  // and 2 / sqrt(3) constants (1e-7 relative, as above) on tetrahedra and wedges, round-off on
  // hexahedra.
  std::mt19937 random(7);
  auto jitter = [&] { return 0.15 * (2.0 * random() / std::mt19937::max() - 1); };
  const double s = std::sqrt(3.0) / 2, h = std::sqrt(2.0 / 3);
  const std::vector<std::pair<int, std::vector<std::array<double, 3>>>> ideal = {
    { VTK_TETRA, { { 0, 0, 0 }, { 1, 0, 0 }, { 0.5, s, 0 }, { 0.5, s / 3, h } } },
    { VTK_HEXAHEDRON, { { 0, 0, 0 }, { 1, 0, 0 }, { 1, 1, 0 }, { 0, 1, 0 }, { 0, 0, 1 }, { 1, 0, 1 }, { 1, 1, 1 }, { 0, 1, 1 } } },
    { VTK_WEDGE, { { 0, 0, 0 }, { 0.5, s, 0 }, { 1, 0, 0 }, { 0, 0, 1 }, { 0.5, s, 1 }, { 1, 0, 1 } } },
  };
  for (int trial = 0; trial < 50; ++trial)
  {
    for (const auto& element : ideal)
    {
      std::vector<std::array<double, 3>> corners = element.second;
      for (auto& c : corners)
        for (double& x : c)
          x += jitter();
      vtkSmartPointer<vtkUnstructuredGrid> grid = singleCell(element.first, corners);
      vtkCell* cell = grid->GetCell(0);
      const double ours = scaledJacobian(grid);
      switch (element.first)
      {
        case VTK_TETRA:
          CHECK_NEAR(ours, vtkMeshQuality::TetScaledJacobian(cell), 1e-7);
          break;
        case VTK_HEXAHEDRON:
          CHECK_NEAR(ours, vtkMeshQuality::HexScaledJacobian(cell), 1e-14);
          break;
        default:
        {
          vtkSmartPointer<vtkUnstructuredGrid> mirror =
            singleCell(VTK_WEDGE, { corners[0], corners[2], corners[1], corners[3], corners[5], corners[4] });
          CHECK_NEAR(ours, vtkMeshQuality::WedgeScaledJacobian(mirror->GetCell(0)), 1e-7);
        }
      }
      CHECK(ours > 0);
    }
  }
}

TEST(QuadraticTetrahedraFoldedBetweenTheirCorners)
{
  // two quadratic tetrahedra sharing the face (0, 1, 2), midside nodes shared on its edges
  const double s = std::sqrt(3.0) / 2, h = std::sqrt(2.0 / 3);
  std::vector<std::array<double, 3>> points = { { 0, 0, 0 }, { 1, 0, 0 }, { 0.5, s, 0 }, { 0.5, s / 3, h }, { 0.5, s / 3, -h } };
  std::map<std::pair<vtkIdType, vtkIdType>, vtkIdType> midsides;
  auto midside = [&](vtkIdType a, vtkIdType b) {
    const auto key = std::minmax(a, b);
    if (!midsides.count(key))
    {
      midsides[key] = static_cast<vtkIdType>(points.size());
      points.push_back({ (points[a][0] + points[b][0]) / 2, (points[a][1] + points[b][1]) / 2, (points[a][2] + points[b][2]) / 2 });
    }
    return midsides[key];
  };
  auto quadratic = [&](std::array<vtkIdType, 4> c) {
    return std::array<vtkIdType, 10>{ c[0], c[1], c[2], c[3], midside(c[0], c[1]), midside(c[1], c[2]), midside(c[2], c[0]),
      midside(c[0], c[3]), midside(c[1], c[3]), midside(c[2], c[3]) };
  };
  const std::array<vtkIdType, 10> above = quadratic({ 0, 1, 2, 3 }), below = quadratic({ 0, 2, 1, 4 });
  auto grid = [&](double s03) { // node 7 of the first element at corner 0 + s03 (corner 3 - corner 0)
    std::vector<std::array<double, 3>> moved = points;
    for (int d = 0; d < 3; ++d)
      moved[above[7]][d] = points[0][d] + s03 * (points[3][d] - points[0][d]);
    auto out = vtkSmartPointer<vtkUnstructuredGrid>::New();
    vtkNew<vtkPoints> vtkpoints;
    vtkpoints->SetDataTypeToDouble();
    for (const auto& p : moved)
      vtkpoints->InsertNextPoint(p.data());
    out->SetPoints(vtkpoints);
    out->InsertNextCell(VTK_QUADRATIC_TETRA, 10, above.data());
    out->InsertNextCell(VTK_QUADRATIC_TETRA, 10, below.data());
    return out;
  };
  vtkNew<vtkDeformationQuality> quality;
  quality->SetInputData(grid(0.5));
  quality->Update();
  // straight-sided regular tetrahedra (to verdict's 1e-7, the corners' value): valid, one interior
  // face, met at right angles by the line between the centres
  CHECK_NEAR(cellValue(quality->GetOutput(), "ScaledJacobian", 0), 1.0, 1e-12);
  CHECK_NEAR(cellValue(quality->GetOutput(), "ScaledJacobian", 1), 1.0, 1e-12);
  CHECK(summaryValue(quality, "InvertedCells", "Min") == 0);
  CHECK(quality->GetOutputDataObject(1) && vtkPolyData::SafeDownCast(quality->GetOutputDataObject(1))->GetNumberOfCells() == 1);
  CHECK_NEAR(summaryValue(quality, "NonOrthogonality", "Max"), 0.0, 1e-6);
  // node 7 (edge (0, 3), not shared) above a quarter of its edge keeps the element, below a quarter
  // folds it at corner 0 (the Jacobian along the edge there is (4 s - 1)(x3 - x0)); the corners
  // stay where they were
  quality->SetInputData(grid(0.3));
  quality->Update();
  CHECK(cellValue(quality->GetOutput(), "ScaledJacobian", 0) > 0);
  CHECK(summaryValue(quality, "InvertedCells", "Min") == 0);
  quality->SetInputData(grid(0.2));
  quality->Update();
  CHECK(cellValue(quality->GetOutput(), "ScaledJacobian", 0) < 0);
  CHECK_NEAR(cellValue(quality->GetOutput(), "ScaledJacobian", 1), 1.0, 1e-12);
  CHECK(summaryValue(quality, "InvertedCells", "Min") == 1);
}

TEST_MAIN
