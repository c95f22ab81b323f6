// Issue 54, point 4: a Constraint Region selects a case's blocks, patches, patch groups and sets
// by name (SelectionMode Blocks, Adapters/BlockSelection.h), on a case-like multiblock: the
// internal mesh of the box [0,2] x [0,1] x [0,1] and its boundary's patches, with a boundary file
// whose inGroups name the two body patches' group.
#include "../TestHarness.h"
#include "FilterTestUtilities.h"
#include "Common/CoreTypes.h"

#include <vtkCellData.h>
#include <vtkCharArray.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkInformation.h>
#include <vtkIntArray.h>
#include <vtkMultiBlockDataSet.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <string>
#include <unistd.h>

namespace
{
const int N = 4; // cells per unit length

// The points of the grid where keep holds, as a patch (vertices).
vtkSmartPointer<vtkPolyData> patch(vtkPointSet* grid, const std::function<bool(const double*)>& keep)
{
  vtkNew<vtkPoints> points;
  for (vtkIdType i = 0; i < grid->GetNumberOfPoints(); ++i)
    if (keep(grid->GetPoint(i)))
      points->InsertNextPoint(grid->GetPoint(i));
  auto p = vtkSmartPointer<vtkPolyData>::New();
  p->SetPoints(points);
  vtkNew<vtkCellArray> vertices;
  for (vtkIdType i = 0; i < points->GetNumberOfPoints(); ++i)
    vertices->InsertNextCell(1, &i);
  p->SetVerts(vertices);
  return p;
}

// The case: internalMesh, boundary/{inlet, outlet, ground, top, front, back, body_left,
// body_right} (the body: the top's left and right halves), CasePath to a folder whose boundary
// file puts body_left and body_right in bodyGroup (and has a patch, wake, that was not read).
struct Case
{
  vtkSmartPointer<vtkUnstructuredGrid> grid = tetrahedralBox(N);
  vtkNew<vtkMultiBlockDataSet> root;
  std::map<std::string, vtkSmartPointer<vtkPolyData>> patches;
  std::string folder;

  Case()
  {
    const double e = 1e-9;
    const std::vector<std::pair<std::string, std::function<bool(const double*)>>> faces = {
      { "inlet", [=](const double* x) { return x[0] < e; } }, { "outlet", [=](const double* x) { return x[0] > 2 - e; } },
      { "ground", [=](const double* x) { return x[2] < e; } }, { "top", [=](const double* x) { return x[2] > 1 - e; } },
      { "front", [=](const double* x) { return x[1] < e; } }, { "back", [=](const double* x) { return x[1] > 1 - e; } },
      { "body_left", [=](const double* x) { return x[2] > 1 - e && x[0] < 1 - e; } },
      { "body_right", [=](const double* x) { return x[2] > 1 - e && x[0] > 1 + e; } } };
    vtkNew<vtkMultiBlockDataSet> boundary;
    boundary->SetNumberOfBlocks(static_cast<unsigned int>(faces.size()));
    for (unsigned int b = 0; b < faces.size(); ++b)
    {
      patches[faces[b].first] = patch(grid, faces[b].second);
      boundary->SetBlock(b, patches[faces[b].first]);
      boundary->GetMetaData(b)->Set(vtkCompositeDataSet::NAME(), faces[b].first.c_str());
    }
    root->SetNumberOfBlocks(2);
    root->SetBlock(0, grid);
    root->GetMetaData(0u)->Set(vtkCompositeDataSet::NAME(), "internalMesh");
    root->SetBlock(1, boundary);
    root->GetMetaData(1u)->Set(vtkCompositeDataSet::NAME(), "boundary");
    // the case folder with its boundary file, named by CasePath as VTK's OpenFOAM reader does
    folder = (std::filesystem::temp_directory_path() / ("mlsdeform-blocks-" + std::to_string(::getpid()))).string();
    std::filesystem::create_directories(folder + "/constant/polyMesh");
    std::ofstream(folder + "/constant/polyMesh/boundary") << "FoamFile { version 2.0; format ascii; class polyBoundaryMesh; }\n"
                                                             "3(\n body_left { type wall; inGroups List<word> 2(wall bodyGroup); }\n"
                                                             " body_right { type wall; inGroups 2(wall bodyGroup); }\n"
                                                             " wake { type patch; }\n)\n"; // a patch not read
    vtkNew<vtkCharArray> path;
    path->SetName("CasePath");
    for (char c : folder)
      path->InsertNextValue(c);
    path->InsertNextValue('\0');
    root->GetFieldData()->AddArray(path);
  }
  ~Case() { std::filesystem::remove_all(folder); }

  std::size_t points(std::initializer_list<const char*> names) const
  {
    std::size_t n = 0;
    for (const char* name : names)
      n += static_cast<std::size_t>(patches.at(name)->GetNumberOfPoints());
    return n;
  }
};

// A region of the given role over the case selecting entries; its output updated.
vtkSmartPointer<vtkConstraintRegion> named(Case& c, int role, std::initializer_list<const char*> entries)
{
  auto region = vtkSmartPointer<vtkConstraintRegion>::New();
  region->SetInputData(c.root);
  region->SetRole(role);
  region->SetSelectionMode(vtkConstraintRegion::Blocks);
  for (const char* entry : entries)
    region->AddBlock(entry);
  region->Update();
  return region;
}

vtkIdType selected(vtkConstraintRegion* region)
{
  return vtkPolyData::SafeDownCast(region->GetOutputDataObject(0))->GetNumberOfPoints();
}
}

TEST(NamesPatternsSelectorsAndGroups)
{
  Case c;
  struct Expectation
  {
    std::initializer_list<const char*> entries;
    std::size_t points;
    const char* what;
  };
  const Expectation expected[] = {
    { { "inlet", "outlet" }, c.points({ "inlet", "outlet" }), "two patches by name" },
    { { "body_.*" }, c.points({ "body_left", "body_right" }), "a pattern of whole names" },
    { { "b.*_left" }, c.points({ "body_left" }), "a pattern matching one name" },
    { { "in.*" }, c.points({ "inlet" }), "a pattern names patches, not the case's internal mesh" },
    { { "b.*" }, c.points({ "back", "body_left", "body_right" }), "a pattern names blocks without children (not the boundary)" },
    { { "bodyGroup" }, c.points({ "body_left", "body_right" }), "a patch group of the case's boundary file" },
    { { "group/bodyGroup" }, c.points({ "body_left", "body_right" }), "group/NAME" },
    { { "patch/inlet" }, c.points({ "inlet" }), "patch/NAME" },
    { { "/Root/boundary/inlet" }, c.points({ "inlet" }), "Extract Block's selector" },
    { { "boundary" }, c.points({ "inlet", "outlet", "ground", "top", "front", "back", "body_left", "body_right" }),
      "a parent block: the patches under it" },
    { { "internalMesh" }, static_cast<std::size_t>(c.grid->GetNumberOfPoints()), "the internal mesh" },
  };
  for (const Expectation& e : expected)
  {
    auto region = named(c, vtkConstraintRegion::Fixed, e.entries);
    std::printf("%s: %lld points, %zu expected\n", e.what, static_cast<long long>(selected(region)), e.points);
    CHECK(region->GetErrorCode() == vtkErrorCode::NoError && static_cast<std::size_t>(selected(region)) == e.points);
  }
  // a name that names nothing: an error that names it and what there is
  auto messages = vtkSmartPointer<MessageCollector>::New();
  auto region = vtkSmartPointer<vtkConstraintRegion>::New();
  region->AddObserver(vtkCommand::ErrorEvent, messages);
  region->SetInputData(c.root);
  region->SetSelectionMode(vtkConstraintRegion::Blocks);
  region->AddBlock("inlet");
  region->AddBlock("hul");
  region->AddBlock("Inlett"); // a typo: the name it most likely means is said
  region->AddBlock("wake");   // a patch of the case the reader did not read: said so
  region->Update();
  CHECK(region->GetErrorCode() == vtkErrorCode::UserError && selected(region) == 0);
  CHECK(messages->errorContains("'hul'") && messages->errorContains("body_left") && messages->errorContains("group/bodyGroup"));
  CHECK(messages->errorContains("'Inlett' (did you mean 'inlet'?)") && !messages->errorContains("'hul' (did you mean"));
  CHECK(messages->errorContains("'wake' (a patch of the case that the reader did not read"));
  CHECK(!messages->errorContains("Sets 'inlet'") && !messages->errorContains(", 'inlet'")); // inlet names a patch
  // patch/ names blocks only, group/ groups only
  for (const char* wrong : { "patch/bodyGroup", "group/inlet" })
  {
    auto r = named(c, vtkConstraintRegion::Fixed, { wrong });
    CHECK(r->GetErrorCode() == vtkErrorCode::UserError);
  }
  // none at all
  auto empty = named(c, vtkConstraintRegion::Fixed, {});
  CHECK(empty->GetErrorCode() == vtkErrorCode::UserError);
}

TEST(SetArraysSelectPointsAndCells)
{
  Case c;
  // a point set (integers, 1 in the set) and a cell set on the internal mesh
  vtkNew<vtkIntArray> corner;
  corner->SetName("corner");
  vtkIdType inCorner = 0;
  for (vtkIdType i = 0; i < c.grid->GetNumberOfPoints(); ++i)
  {
    const double* x = c.grid->GetPoint(i);
    const bool in = x[0] < 0.3 && x[1] < 0.3 && x[2] < 0.3;
    corner->InsertNextValue(in ? 1 : 0);
    inCorner += in ? 1 : 0;
  }
  c.grid->GetPointData()->AddArray(corner);
  vtkNew<vtkCharArray> first;
  first->SetName("firstCell");
  first->SetNumberOfValues(c.grid->GetNumberOfCells());
  first->FillValue(0);
  first->SetValue(0, 1);
  c.grid->GetCellData()->AddArray(first);
  auto points = named(c, vtkConstraintRegion::Fixed, { "corner" });
  CHECK(points->GetErrorCode() == vtkErrorCode::NoError && selected(points) == inCorner);
  auto cells = named(c, vtkConstraintRegion::Fixed, { "firstCell" });
  CHECK(cells->GetErrorCode() == vtkErrorCode::NoError && selected(cells) == c.grid->GetCell(0)->GetNumberOfPoints());
  // a field of doubles is no set
  vtkNew<vtkDoubleArray> pressure;
  pressure->SetName("p");
  pressure->SetNumberOfValues(c.grid->GetNumberOfPoints());
  pressure->FillValue(1);
  c.grid->GetPointData()->AddArray(pressure);
  CHECK(named(c, vtkConstraintRegion::Fixed, { "p" })->GetErrorCode() == vtkErrorCode::UserError);
}

TEST(PatchesOfOneHandleMoveAsOneBody)
{
  // a rotation of the body's two patches in one region turns them about their common centroid
  Case c;
  auto body = named(c, vtkConstraintRegion::Handle, { "bodyGroup" });
  double pivot[3];
  body->GetPivot(pivot);
  mlsdeform::Vec3 centroid = mlsdeform::Vec3::Zero();
  std::size_t n = 0;
  for (const char* name : { "body_left", "body_right" })
    for (vtkIdType i = 0; i < c.patches[name]->GetNumberOfPoints(); ++i, ++n)
      centroid += mlsdeform::Vec3(c.patches[name]->GetPoint(i));
  centroid /= static_cast<double>(n);
  std::printf("pivot (%g, %g, %g), the body's centroid (%g, %g, %g)\n", pivot[0], pivot[1], pivot[2], centroid.x(), centroid.y(), centroid.z());
  CHECK((mlsdeform::Vec3(pivot) - centroid).norm() <= 1e-12);
  CHECK(std::abs(pivot[0] - 1) <= 1e-12); // between the halves, not either one's
}

TEST(SlipRegionOfSeveralPlanes)
{
  // one Slip region over the ground and the side walls (three planes): each block slides within
  // its own plane while the top moves along x; one plane fitted to all three was an error
  Case c;
  auto top = named(c, vtkConstraintRegion::Handle, { "top" });
  const double motion = 0.1;
  top->SetTranslation(motion, 0, 0);
  auto ends = named(c, vtkConstraintRegion::Fixed, { "inlet", "outlet" });
  auto walls = named(c, vtkConstraintRegion::Slip, { "ground", "front", "back" });
  vtkNew<vtkMLSDeformFilter> deform;
  deform->SetInputData(c.root);
  for (auto* r : { top.Get(), ends.Get(), walls.Get() })
    deform->AddRegionConnection(r->GetOutputPort());
  deform->SetNumberOfSamples(300);
  auto messages = MessageCollector::watch(deform);
  deform->Update();
  CHECK(messages->Errors.empty());
  auto* out = vtkMultiBlockDataSet::SafeDownCast(deform->GetOutputDataObject(0));
  auto* boundary = out ? vtkMultiBlockDataSet::SafeDownCast(out->GetBlock(1)) : nullptr;
  CHECK(boundary != nullptr);
  if (!boundary)
    return;
  // ground (block 2): z stays 0; front (4): y stays 0; back (5): y stays 1; the ground slides
  double off = 0, slide = 0;
  for (const auto& [block, axis] : { std::pair<unsigned, int>{ 2, 2 }, { 4, 1 }, { 5, 1 } })
  {
    auto* p = vtkPointSet::SafeDownCast(boundary->GetBlock(block));
    vtkDataArray* d = p->GetPointData()->GetArray("Displacement");
    for (vtkIdType i = 0; i < p->GetNumberOfPoints(); ++i)
    {
      off = std::max(off, std::abs(d->GetComponent(i, axis)));
      slide = std::max(slide, std::abs(d->GetComponent(i, 0)));
    }
  }
  std::printf("walls: normal displacement up to %.3g, sliding up to %.3g of the motion\n", off, slide / motion);
  // the slide removes the normal component: round-off of |d| (a few eps of the box's size)
  CHECK(off <= 1e-12);
  CHECK(slide > 0.1 * motion); // they do slide along with the top
}

TEST_MAIN
