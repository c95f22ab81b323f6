// vtkPrimitiveDetector and Constraint Region's Primitive mode (paper section 6.3): arrays and
// table, fandisk, joint and couplingdown from CGAL's data, the joint scene of Fig. 10, and bad input.
#include "../TestHarness.h"
#include "FilterTestUtilities.h"
#include "Primitives/Primitives.h"
#include "vtkOFFReader.h"
#include "vtkPrimitiveDetector.h"

#include <vtkAppendFilter.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIntArray.h>
#include <vtkPoints.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include <cmath>
#include <map>
#include <set>

namespace
{
vtkSmartPointer<vtkPolyData> readOFF(const char* name)
{
  vtkNew<vtkOFFReader> reader;
  reader->SetFileName((std::string(MLSDEFORM_DATA_DIR) + "/" + name).c_str());
  reader->Update();
  return reader->GetOutput();
}

struct Row
{
  std::string type;
  double faces, radius, angle, rms;
  mlsdeform::Vec3 normal, axis;
};

std::vector<Row> rows(vtkTable* table)
{
  std::vector<Row> result;
  auto get = [&](vtkIdType r, const char* column) { return table->GetValueByName(r, column).ToDouble(); };
  for (vtkIdType r = 0; r < table->GetNumberOfRows(); ++r)
  {
    result.push_back({ table->GetValueByName(r, "Type").ToString(), get(r, "Faces"), get(r, "Radius"), get(r, "Angle"), get(r, "RMSDistance"),
      mlsdeform::Vec3(get(r, "NormalX"), get(r, "NormalY"), get(r, "NormalZ")), mlsdeform::Vec3(get(r, "AxisX"), get(r, "AxisY"), get(r, "AxisZ")) });
  }
  return result;
}

// A detector run on an input, with its outputs.
struct Detection
{
  vtkNew<vtkPrimitiveDetector> detector;
  vtkPolyData* surface = nullptr;
  vtkTable* table = nullptr;
  std::vector<Row> found;
  explicit Detection(vtkDataObject* input)
  {
    detector->SetInputData(input);
    detector->Update();
    surface = detector->GetOutput();
    table = vtkTable::SafeDownCast(detector->GetOutputDataObject(1));
    found = rows(table);
  }
};

// The fraction of the polygons that belong to a primitive.
double coverage(vtkPolyData* surface)
{
  vtkDataArray* id = surface->GetCellData()->GetArray("PrimitiveId");
  long covered = 0;
  for (vtkIdType c = 0; c < id->GetNumberOfTuples(); ++c)
    covered += id->GetTuple1(c) >= 0;
  return static_cast<double>(covered) / id->GetNumberOfTuples();
}

// The primitive ids of the faces whose vertices all satisfy on(x).
std::set<int> primitivesOfFaces(vtkPolyData* surface, const std::function<bool(const double*)>& on, long& faces)
{
  std::set<int> ids;
  faces = 0;
  vtkDataArray* id = surface->GetCellData()->GetArray("PrimitiveId");
  for (vtkIdType c = 0; c < surface->GetNumberOfCells(); ++c)
  {
    vtkIdList* points = surface->GetCell(c)->GetPointIds();
    bool all = true;
    for (vtkIdType a = 0; a < points->GetNumberOfIds(); ++a)
      all = all && on(surface->GetPoint(points->GetId(a)));
    if (all)
    {
      ++faces;
      ids.insert(static_cast<int>(id->GetTuple1(c)));
    }
  }
  return ids;
}

bool parallel(const mlsdeform::Vec3& a, const mlsdeform::Vec3& b, double degrees)
{
  return std::abs(a.normalized().dot(b.normalized())) >= std::cos(degrees * M_PI / 180);
}

// A box [0,2] x [0,1] x [0,1] of unit-spaced voxels (n per unit) as an unstructured grid.
vtkSmartPointer<vtkUnstructuredGrid> voxelBox(int n)
{
  vtkNew<vtkAppendFilter> append;
  append->AddInputData(boxImage(n));
  append->Update();
  return append->GetOutput();
}
}

TEST(VolumeMeshBoundaryGivesSixPlanesWithTheirParameters)
{
  const Detection d(voxelBox(8));
  vtkPolyData* surface = d.surface;
  vtkTable* table = d.table;
  const std::vector<Row>& found = d.found;
  CHECK(found.size() == 6);
  CHECK_NEAR(coverage(surface), 1.0, 1e-12); // a ratio of face counts: one uncovered face of 640 is 1.6e-3
  double faces = 0;
  for (const Row& r : found)
  {
    CHECK(r.type == "Plane");
    // exact axis-aligned faces: normals exact up to a few eps; 1e-6 degrees = 1.7e-8 rad = sqrt(eps),
    // the finest angle a cosine resolves
    CHECK(parallel(r.normal, mlsdeform::Vec3::UnitX(), 1e-6) || parallel(r.normal, mlsdeform::Vec3::UnitY(), 1e-6) ||
      parallel(r.normal, mlsdeform::Vec3::UnitZ(), 1e-6));
    // exactly coplanar barycenters: distances are the fit's round-off, n eps |x| = 128 x 2.2e-16 x 2 = 6e-14
    CHECK(r.rms < 1e-12 && std::isnan(r.radius) && std::isnan(r.axis.x()));
    faces += r.faces;
  }
  CHECK_NEAR(faces, surface->GetNumberOfCells(), 0);
  // areas sum to the box's surface 2 (2 + 2 + 1) = 10; offsets are 0, 1 or 2
  double area = 0;
  for (vtkIdType r = 0; r < table->GetNumberOfRows(); ++r)
  {
    area += table->GetValueByName(r, "Area").ToDouble();
    const double offset = std::abs(table->GetValueByName(r, "Offset").ToDouble());
    CHECK(std::abs(offset) < 1e-12 || std::abs(offset - 1) < 1e-12 || std::abs(offset - 2) < 1e-12); // round-off as for rms
  }
  CHECK_NEAR(area, 10.0, 1e-11); // 640 face areas summing to 10: 640 eps 10 = 1.4e-12
  // a corner vertex belongs to three planes, an edge vertex to two, a face vertex to one
  vtkDataArray* count = surface->GetPointData()->GetArray("PrimitiveCount");
  vtkDataArray* ids = surface->GetPointData()->GetArray("PrimitiveIds");
  CHECK(ids->GetNumberOfComponents() == 3);
  std::map<int, int> histogram;
  for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
  {
    const double* x = surface->GetPoint(i);
    int extremes = 0;
    for (int d = 0; d < 3; ++d)
      extremes += x[d] == 0 || x[d] == (d == 0 ? 2 : 1);
    CHECK(count->GetTuple1(i) == extremes);
    ++histogram[static_cast<int>(count->GetTuple1(i))];
  }
  CHECK(histogram[3] == 8);
  // every face's primitive is among its vertices' ids
  vtkDataArray* cellId = surface->GetCellData()->GetArray("PrimitiveId");
  bool consistent = true;
  for (vtkIdType c = 0; c < surface->GetNumberOfCells(); ++c)
  {
    vtkIdList* points = surface->GetCell(c)->GetPointIds();
    for (vtkIdType a = 0; a < points->GetNumberOfIds(); ++a)
    {
      bool listed = false;
      for (int k = 0; k < 3; ++k)
        listed = listed || ids->GetComponent(points->GetId(a), k) == cellId->GetTuple1(c);
      consistent = consistent && listed;
    }
  }
  CHECK(consistent);
}

TEST(FandiskLargePlanesAndCylindersAreFound)
{
  const vtkSmartPointer<vtkPolyData> fandisk = readOFF("fandisk.off");
  const vtkMTimeType before = fandisk->GetMTime();
  const Detection d(fandisk);
  vtkPolyData* surface = d.surface;
  const std::vector<Row>& found = d.found;
  std::printf("fandisk: %zu primitives, %.1f%% of the faces\n", found.size(), 100 * coverage(surface));
  // the detection issue's requirement: "at least 95% of faces assigned to the right primitive"
  CHECK(coverage(surface) > 0.95);
  CHECK(fandisk->GetMTime() == before && !fandisk->GetCellData()->GetArray("PrimitiveId")); // input untouched
  // the flat back (y = max): all its faces in one plane with normal y
  double bounds[6];
  fandisk->GetBounds(bounds);
  long faces = 0;
  const std::set<int> back = primitivesOfFaces(surface, [&](const double* x) { return x[1] > bounds[3] - 1e-6; }, faces);
  CHECK(faces > 2000 && back.size() == 1 && *back.begin() >= 0);
  if (back.size() == 1 && *back.begin() >= 0)
    CHECK(found[*back.begin()].type == "Plane" && parallel(found[*back.begin()].normal, mlsdeform::Vec3::UnitY(), 0.01));
  // the fan's cylinders: at least four of 100+ faces, radius below the part; "on fandisk and
  // joint the large planes and cylinders are found" is the detection issue's requirement. Their
  // fit: every face kept lies within Epsilon x the diagonal of its primitive (the detector's
  // inlier test), and the final least-squares fit only lowers the RMS below that (was 3e-3).
  const double diagonal = std::sqrt(std::pow(bounds[1] - bounds[0], 2) + std::pow(bounds[3] - bounds[2], 2) + std::pow(bounds[5] - bounds[4], 2));
  const double inlier = d.detector->GetEpsilon() * diagonal;
  int cylinders = 0;
  for (const Row& r : found)
    cylinders += r.type == "Cylinder" && r.faces >= 100 && r.rms < inlier && r.radius < 1;
  std::printf("fandisk: %d cylinders of 100+ faces within the inlier distance %.3g\n", cylinders, inlier);
  CHECK(cylinders >= 4);
}

TEST(CouplingdownCoverageOverSeeds)
{
  // issue 31: "back to at least 0.94 on couplingdown", where the seeds once ranged over 0.84 -
  // 0.96 (a primitive the draws missed); for each of five seeds
  const vtkSmartPointer<vtkPolyData> part = readOFF("couplingdown.off");
  for (int seed = 0; seed < 5; ++seed)
  {
    vtkNew<vtkPrimitiveDetector> detector;
    detector->SetInputData(part);
    detector->SetRandomSeed(seed);
    detector->Update();
    const double covered = coverage(detector->GetOutput());
    std::printf("couplingdown, seed %d: %.2f%% of the faces\n", seed, 100 * covered);
    CHECK(covered >= 0.94);
  }
}

TEST(JointPlanesAndCylindersAreFound)
{
  const vtkSmartPointer<vtkPolyData> joint = readOFF("joint.off");
  const Detection d(joint);
  vtkPolyData* surface = d.surface;
  const std::vector<Row>& found = d.found;
  std::printf("joint: %zu primitives, %.1f%% of the faces\n", found.size(), 100 * coverage(surface));
  CHECK(coverage(surface) > 0.95); // the detection issue's requirement, as for fandisk (was 0.9)
  // top (y = max) and bottom (y = min) faces: one plane each
  double bounds[6];
  joint->GetBounds(bounds);
  for (double y : { bounds[2], bounds[3] })
  {
    long faces = 0;
    const std::set<int> ids = primitivesOfFaces(surface, [&](const double* x) { return std::abs(x[1] - y) < 1e-6; }, faces);
    CHECK(faces >= 40 && ids.size() == 1 && *ids.begin() >= 0);
  }
  // the vertical bore and the horizontal hole: cylinders along y and x, fit to round-off
  bool vertical = false, horizontal = false;
  for (const Row& r : found)
  {
    vertical = vertical || (r.type == "Cylinder" && parallel(r.axis, mlsdeform::Vec3::UnitY(), 0.01) && r.faces >= 40 && r.rms < 1e-5);
    horizontal = horizontal || (r.type == "Cylinder" && parallel(r.axis, mlsdeform::Vec3::UnitX(), 0.01) && r.faces >= 40 && r.rms < 1e-5);
  }
  CHECK(vertical && horizontal);
}

TEST(ConstraintRegionSelectsAPrimitiveWithItsRole)
{
  vtkNew<vtkPrimitiveDetector> detector;
  detector->SetInputData(voxelBox(4));
  vtkNew<vtkConstraintRegion> region;
  region->SetInputConnection(detector->GetOutputPort());
  region->SetSelectionMode(vtkConstraintRegion::Primitive);
  region->SetRole(vtkConstraintRegion::FromPrimitive);
  region->SetPrimitiveId(2);
  region->Update();
  // a face of the box: (n + 1)^2 or (2n + 1)(n + 1) vertices, edges included (multi-membership)
  const vtkIdType selected = region->GetOutput()->GetNumberOfPoints();
  CHECK(selected == 25 || selected == 45);
  CHECK(fieldValue(region->GetOutput(), "Role") == vtkConstraintRegion::Planarity);
  // errors: an id the detector did not find, a role that needs the Primitive mode, an input
  // without the detector's arrays
  region->SetPrimitiveId(6);
  auto messages = MessageCollector::watch(region);
  region->Update();
  CHECK(messages->errorContains("There is no primitive 6"));
  region->SetPrimitiveId(0);
  region->SetSelectionMode(vtkConstraintRegion::AllPoints);
  region->Update();
  CHECK(messages->errorContains("FromPrimitive needs SelectionMode Primitive"));
  region->SetSelectionMode(vtkConstraintRegion::Primitive);
  region->SetInputData(voxelBox(2));
  region->Update();
  CHECK(messages->errorContains("needs a Primitive Detector's output"));
}

TEST(CylinderPrimitiveGivesTheCylinderRole)
{
  const vtkSmartPointer<vtkPolyData> joint = readOFF("joint.off");
  const Detection d(joint);
  const std::vector<Row>& found = d.found;
  int cylinder = -1;
  for (std::size_t p = 0; p < found.size() && cylinder < 0; ++p)
    if (found[p].type == "Cylinder")
      cylinder = static_cast<int>(p);
  CHECK(cylinder >= 0);
  vtkNew<vtkConstraintRegion> region;
  region->SetInputConnection(d.detector->GetOutputPort());
  region->SetSelectionMode(vtkConstraintRegion::Primitive);
  region->SetRole(vtkConstraintRegion::FromPrimitive);
  region->SetPrimitiveId(cylinder);
  region->Update();
  CHECK(fieldValue(region->GetOutput(), "Role") == vtkConstraintRegion::Cylinder);
  // its vertices are those of its faces
  std::set<vtkIdType> vertices;
  vtkPolyData* surface = d.surface;
  vtkDataArray* id = surface->GetCellData()->GetArray("PrimitiveId");
  for (vtkIdType c = 0; c < surface->GetNumberOfCells(); ++c)
    if (id->GetTuple1(c) == cylinder)
      for (vtkIdType a = 0; a < surface->GetCell(c)->GetNumberOfPoints(); ++a)
        vertices.insert(surface->GetCell(c)->GetPointId(a));
  CHECK(region->GetOutput()->GetNumberOfPoints() == static_cast<vtkIdType>(vertices.size()));
}

TEST(JointSceneOfFigure10KeepsTheDetectedPrimitives)
{
  // bottom fixed, the top lifted as the handle, every detected primitive kept with the role of
  // its type: the deformation meets the handle and keeps each primitive, which it does not do
  // without the constraints
  const vtkSmartPointer<vtkPolyData> joint = readOFF("joint.off");
  double b[6];
  joint->GetBounds(b);
  const Detection d(joint);
  vtkPolyData* surface = d.surface;
  const std::vector<Row>& found = d.found;
  const double lift = 0.15, bottom[6] = { b[0] - 1, b[1] + 1, b[2] - 1, b[2] + 0.05, b[4] - 1, b[5] + 1 },
               top[6] = { b[0] - 1, b[1] + 1, b[3] - 0.2, b[3] + 1, b[4] - 1, b[5] + 1 };
  auto fixed = boxRegion(d.detector->GetOutputPort(), vtkConstraintRegion::Fixed, bottom);
  auto handle = boxRegion(d.detector->GetOutputPort(), vtkConstraintRegion::Handle, top);
  handle->SetTranslation(0, lift, 0);
  std::vector<vtkSmartPointer<vtkConstraintRegion>> kept;
  for (std::size_t p = 0; p < found.size(); ++p)
  {
    kept.push_back(vtkSmartPointer<vtkConstraintRegion>::New());
    kept.back()->SetInputConnection(d.detector->GetOutputPort());
    kept.back()->SetSelectionMode(vtkConstraintRegion::Primitive);
    kept.back()->SetRole(vtkConstraintRegion::FromPrimitive);
    kept.back()->SetPrimitiveId(static_cast<int>(p));
  }
  vtkNew<vtkMLSDeformFilter> free, constrained;
  for (vtkMLSDeformFilter* deform : { free.Get(), constrained.Get() })
  {
    deform->SetInputConnection(d.detector->GetOutputPort());
    deform->AddRegionConnection(fixed->GetOutputPort());
    deform->AddRegionConnection(handle->GetOutputPort());
  }
  for (auto& region : kept)
    constrained->AddRegionConnection(region->GetOutputPort());
  free->Update();
  constrained->Update();
  vtkPointSet* out = vtkPointSet::SafeDownCast(constrained->GetOutputDataObject(0));
  CHECK(fieldValue(out, "HandleResidual") < 0.01 * lift);
  vtkDataArray* converged = out->GetFieldData()->GetArray("ConstraintConverged");
  vtkDataArray* residual = out->GetFieldData()->GetArray("ConstraintResidual");
  CHECK(converged && converged->GetNumberOfTuples() == static_cast<vtkIdType>(found.size()));
  // each kept primitive still passes the detector's inlier test: its largest distance from its
  // projection, a fraction of the diagonal like Epsilon, below Epsilon (was 1e-3)
  for (vtkIdType c = 0; converged && c < converged->GetNumberOfTuples(); ++c)
    CHECK(converged->GetTuple1(c) == 1 && residual->GetTuple1(c) < d.detector->GetEpsilon());
  // the cylinders of the deformed parts, fit anew: RMS distance of their vertices
  vtkDataArray* ids = surface->GetPointData()->GetArray("PrimitiveIds");
  auto cylinderRms = [&](vtkPointSet* deformed, int primitive) {
    mlsdeform::PointList x;
    std::vector<int> all;
    for (vtkIdType i = 0; i < surface->GetNumberOfPoints(); ++i)
      for (int k = 0; k < ids->GetNumberOfComponents(); ++k)
        if (ids->GetComponent(i, k) == primitive)
        {
          x.emplace_back(deformed->GetPoint(i));
          all.push_back(static_cast<int>(all.size()));
        }
    mlsdeform::Primitive start;
    start.type = mlsdeform::PrimitiveType::Cylinder;
    start.axis = found[primitive].axis;
    start.radius = found[primitive].radius;
    for (const auto& p : x)
      start.center += p / static_cast<double>(x.size());
    const mlsdeform::Primitive fit = mlsdeform::fitLeastSquares(start, x, all);
    double squared = 0;
    for (const auto& p : x)
      squared += std::pow(fit.distance(p), 2);
    return std::sqrt(squared / x.size());
  };
  vtkPointSet* unconstrained = vtkPointSet::SafeDownCast(free->GetOutputDataObject(0));
  // Every cylinder stays one by the detector's own inlier test (its RMS within Epsilon x the
  // diagonal; was 0.5% of the lift). One that the free deformation bends by more than its targets'
  // misfit, (gamma_s + gamma_b) / gamma_f of the lift (TestShapeConstraints' checkKept; was 0.5% of
  // the lift), is kept within the penalty balance gamma_b / gamma_c of its free RMS (was 0.2 x).
  const double inlier = d.detector->GetEpsilon() * std::sqrt(std::pow(b[1] - b[0], 2) + std::pow(b[3] - b[2], 2) + std::pow(b[5] - b[4], 2));
  const double balance = constrained->GetBendWeight() / constrained->GetConstraintWeight();
  const double misfit = (free->GetStretchWeight() + free->GetBendWeight()) / free->GetFixWeight() * lift;
  int cylinders = 0, bent = 0;
  for (std::size_t p = 0; p < found.size(); ++p)
  {
    if (found[p].type != "Cylinder")
      continue;
    ++cylinders;
    const double kept = cylinderRms(out, static_cast<int>(p)), loose = cylinderRms(unconstrained, static_cast<int>(p));
    std::printf("cylinder %zu: RMS distance from its refit %.2e kept, %.2e free\n", p, kept, loose);
    CHECK(kept < inlier);
    if (loose > misfit)
    {
      ++bent;
      CHECK(kept < balance * loose);
    }
  }
  CHECK(cylinders >= 2 && bent >= 1);
}

TEST(BadInputGivesClearErrors)
{
  vtkNew<vtkPrimitiveDetector> detector;
  auto messages = MessageCollector::watch(detector);
  // empty
  vtkNew<vtkPolyData> empty;
  detector->SetInputData(empty);
  detector->Update();
  CHECK(messages->errorContains("no faces"));
  // a point cloud (vertices, no faces, no normals)
  vtkNew<vtkPolyData> cloud;
  vtkNew<vtkPoints> points;
  vtkNew<vtkCellArray> verts;
  for (int i = 0; i < 20; ++i)
  {
    const vtkIdType id = points->InsertNextPoint(i, i * i, 0);
    verts->InsertNextCell(1, &id);
  }
  cloud->SetPoints(points);
  cloud->SetVerts(verts);
  messages->Errors.clear();
  detector->SetInputData(cloud);
  detector->Update();
  CHECK(messages->errorContains("no faces"));
  CHECK(detector->GetOutput()->GetNumberOfPoints() == 0);
  // NaN coordinates
  vtkSmartPointer<vtkPolyData> plane = figurePlane();
  plane->GetPoints()->SetPoint(5, std::nan(""), 0, 0);
  messages->Errors.clear();
  detector->SetInputData(plane);
  detector->Update();
  CHECK(messages->errorContains("NaN"));
  // degenerate and zero-area faces (and the vertex cells) belong to no primitive; the rest is found
  vtkSmartPointer<vtkPolyData> withDegenerate = figurePlane();
  vtkCellArray* polys = withDegenerate->GetPolys();
  const vtkIdType sliver[3] = { 0, 1, 2 }, line[2] = { 3, 4 }, collapsed[3] = { 7, 7, 40 };
  polys->InsertNextCell(3, sliver);
  polys->InsertNextCell(2, line);
  polys->InsertNextCell(3, collapsed);
  messages->Errors.clear();
  detector->SetInputData(withDegenerate);
  detector->Update();
  CHECK(messages->Errors.empty());
  vtkDataArray* id = detector->GetOutput()->GetCellData()->GetArray("PrimitiveId");
  const vtkIdType n = id->GetNumberOfTuples();
  CHECK(n == 32 * 32 + 3);
  CHECK(id->GetTuple1(n - 1) == -1 && id->GetTuple1(n - 2) == -1 && id->GetTuple1(n - 3) == -1);
  CHECK(id->GetTuple1(0) == 0);
}

TEST_MAIN
