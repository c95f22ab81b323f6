#include "Adapters/VolumeMeshQuality.h"

#include "Adapters/CaseFaces.h"
#include "Adapters/CellFaces.h"
#include "Adapters/MeshCells.h"
#include "Adapters/PointSets.h"
#include "Common/BoundingBox.h"

#include <vtkCell.h>
#include <vtkGenericCell.h>
#include <vtkIdList.h>
#include <vtkLogger.h>
#include <vtkMeshQuality.h>
#include <vtkNew.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>
#include <vtkUnstructuredGrid.h>
#include <vtkDataSetAttributes.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>

namespace mlsvtk
{
namespace
{
// Whether cell c is another process's, held here as a ghost (measured there).
bool ghostCell(vtkUnsignedCharArray* ghosts, vtkIdType c)
{
  return ghosts && (ghosts->GetValue(c) & vtkDataSetAttributes::DUPLICATECELL);
}
}

mlsdeform::CellFaceList cellFaces(vtkUnstructuredGrid* grid)
{
  vtkUnsignedCharArray* ghosts = grid->GetCellGhostArray();
  return mlsdeform::CellFaceList::build(static_cast<int>(grid->GetNumberOfCells()), [&]() {
    // per thread: GetCellPoints' thread-safe variant's list, a face's points
    return [&, scratch = vtkSmartPointer<vtkIdList>::New(), polygon = std::vector<vtkIdType>()](int c, auto add) mutable {
      if (ghostCell(ghosts, c))
      {
        return; // no faces: its neighbours' faces are between pieces (PieceInterfaces)
      }
      const int type = grid->GetCellType(c);
      if (type == VTK_POLYHEDRON)
      {
        visitPolyhedronFaces(grid, c, [&](const vtkIdType* face, vtkIdType n) { add(face, static_cast<std::size_t>(n)); });
        return;
      }
      const LocalFaces& local = cellTypeFaces(type);
      vtkIdType n = 0;
      const vtkIdType* points = nullptr;
      if (!local.empty())
      {
        grid->GetCellPoints(c, n, points, scratch);
      }
      for (const std::vector<int>& face : local)
      {
        polygon.resize(face.size());
        for (std::size_t i = 0; i < face.size(); ++i)
        {
          polygon[i] = points[face[i]];
        }
        add(polygon.data(), polygon.size());
      }
    };
  });
}

std::optional<mlsdeform::ElementShape> elementShape(int vtkCellType)
{
  using mlsdeform::ElementShape;
  switch (vtkCellType)
  {
    case VTK_TETRA:
      return ElementShape::Tetra4;
    case VTK_QUADRATIC_TETRA:
      return ElementShape::Tetra10;
    case VTK_HEXAHEDRON:
      return ElementShape::Hexa8;
    case VTK_QUADRATIC_HEXAHEDRON:
      return ElementShape::Hexa20;
    case VTK_WEDGE:
      return ElementShape::Wedge6;
    case VTK_QUADRATIC_WEDGE:
      return ElementShape::Wedge15;
    default:
      return std::nullopt;
  }
}

std::vector<double> scaledJacobians(vtkUnstructuredGrid* grid)
{
  std::vector<double> jacobians(grid->GetNumberOfCells(), std::numeric_limits<double>::quiet_NaN());
  CellsByType byType;
  vtkNew<vtkIdList> ids;
  mlsdeform::PointList nodes;
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    const int type = grid->GetCellType(c);
    if (const std::optional<mlsdeform::ElementShape> shape = elementShape(type))
    {
      grid->GetCellPoints(c, ids);
      nodes.resize(ids->GetNumberOfIds());
      for (vtkIdType i = 0; i < ids->GetNumberOfIds(); ++i)
      {
        grid->GetPoint(ids->GetId(i), nodes[i].data());
      }
      jacobians[c] = mlsdeform::elementJacobian(*shape, nodes.data()).minScaled;
    }
    else if (type == VTK_PYRAMID)
    {
      jacobians[c] = vtkMeshQuality::PyramidScaledJacobian(byType.get(grid, c)->GetRepresentativeCell());
    }
  }
  return jacobians;
}

Elements::Elements(vtkUnstructuredGrid* grid, ElementSet set)
  : CellCount(static_cast<std::size_t>(grid->GetNumberOfCells()))
{
  using mlsdeform::ElementShape;
  vtkNew<vtkIdList> ids;
  vtkUnsignedCharArray* ghosts = grid->GetCellGhostArray();
  Start.push_back(0);
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    if (ghostCell(ghosts, c))
    {
      continue;
    }
    const std::optional<ElementShape> shape = elementShape(grid->GetCellType(c));
    const bool quadratic = shape == ElementShape::Tetra10 || shape == ElementShape::Hexa20 || shape == ElementShape::Wedge15;
    if (shape && (quadratic || set == ElementSet::All))
    {
      grid->GetCellPoints(c, ids);
      Cells.push_back(static_cast<int>(c));
      Shapes.push_back(*shape);
      Points.insert(Points.end(), ids->GetPointer(0), ids->GetPointer(0) + ids->GetNumberOfIds());
      Start.push_back(Points.size());
    }
  }
}

double Elements::measure(const mlsdeform::PointList& points, std::vector<unsigned char>& inverted) const
{
  const long count = static_cast<long>(Cells.size());
  inverted.resize(std::max(inverted.size(), CellCount), 0);
  double least = std::numeric_limits<double>::infinity();
#pragma omp parallel for schedule(static) reduction(min : least)
  for (long e = 0; e < count; ++e)
  {
    mlsdeform::Vec3 nodes[20];
    for (std::size_t i = Start[e]; i < Start[e + 1]; ++i)
    {
      nodes[i - Start[e]] = points[Points[i]];
    }
    const mlsdeform::ElementJacobian j = mlsdeform::elementJacobian(Shapes[e], nodes);
    least = std::min(least, j.minScaled);
    if (j.inverted)
    {
      inverted[Cells[e]] = 1; // one element a cell: no two threads write the same byte
    }
  }
  return least;
}

mlsdeform::AggregatePart Elements::aggregatePart(const mlsdeform::PointList& points, double rho)
{
  // each element's values into its own buffer in parallel, then in element order
  const long count = static_cast<long>(Shapes.size());
  std::vector<std::vector<double>> values(Shapes.size());
#pragma omp parallel
  {
    mlsdeform::PointList nodes;
#pragma omp for schedule(dynamic, 1024)
    for (long e = 0; e < count; ++e)
    {
      nodes.resize(Start[e + 1] - Start[e]);
      for (std::size_t n = 0; n < nodes.size(); ++n)
      {
        nodes[n] = points[Points[Start[e] + n]];
      }
      mlsdeform::scaledJacobians(Shapes[e], nodes.data(), values[e]);
    }
  }
  Negated.clear();
  FrameStart.assign(1, 0);
  for (const std::vector<double>& v : values)
  {
    for (double sj : v)
    {
      Negated.push_back(-sj);
    }
    FrameStart.push_back(Negated.size());
  }
  return mlsdeform::aggregatePart(Negated, rho);
}

void Elements::addAggregateGradient(
  const mlsdeform::PointList& points, double rho, const mlsdeform::AggregatePart& whole, mlsdeform::PointList& gradient) const
{
  // KS(-sj): dKS/dX = -sum_j w_j d(sj_j)/dX over the elements with a point of weight >= 1e-20
  std::vector<long> heavy;
  for (long e = 0; e + 1 < static_cast<long>(FrameStart.size()); ++e)
  {
    for (std::size_t j = FrameStart[e]; j < FrameStart[e + 1]; ++j)
    {
      if (std::exp(rho * (Negated[j] - whole.largest)) / whole.sum >= mlsdeform::LeastAggregateWeight)
      {
        heavy.push_back(e);
        break;
      }
    }
  }
  std::vector<mlsdeform::PointList> terms(heavy.size());
#pragma omp parallel for schedule(dynamic, 16)
  for (long h = 0; h < static_cast<long>(heavy.size()); ++h)
  {
    const long e = heavy[h];
    mlsdeform::PointList nodes(Start[e + 1] - Start[e]);
    for (std::size_t n = 0; n < nodes.size(); ++n)
    {
      nodes[n] = points[Points[Start[e] + n]];
    }
    std::vector<double> weights;
    for (std::size_t j = FrameStart[e]; j < FrameStart[e + 1]; ++j)
    {
      weights.push_back(-std::exp(rho * (Negated[j] - whole.largest)) / whole.sum);
    }
    terms[h].assign(nodes.size(), mlsdeform::Vec3::Zero());
    mlsdeform::addScaledJacobianGradient(Shapes[e], nodes.data(), weights.data(), terms[h].data());
  }
  for (std::size_t h = 0; h < heavy.size(); ++h) // in element order: the same bits for any thread count
  {
    for (std::size_t n = 0; n < terms[h].size(); ++n)
    {
      gradient[Points[Start[heavy[h]] + n]] += terms[h][n];
    }
  }
}

void gridPoints(vtkUnstructuredGrid* grid, const char* what, mlsdeform::PointList& out)
{
  out.resize(grid->GetNumberOfPoints());
  copyPoints(grid, out.data());
  mlsdeform::requireFinite(out, what);
}

mlsdeform::PointList gridPoints(vtkUnstructuredGrid* grid, const char* what)
{
  mlsdeform::PointList points;
  gridPoints(grid, what, points);
  return points;
}

VolumeMeshQuality::VolumeMeshQuality(vtkUnstructuredGrid* rest, const std::string& casePath, QualityVerdict verdict)
  : JacobianElements(rest, verdict == QualityVerdict::FemSolver ? ElementSet::All : ElementSet::Quadratic)
  , Verdict(verdict)
{
  if (verdict == QualityVerdict::FemSolver)
  {
    Has3DCells = !JacobianElements.empty();
    if (Has3DCells)
    {
      gridPoints(rest, "the mesh's points", Points);
      Original = summarizeMeasures();
    }
    return;
  }
  std::optional<CaseMesh> own = casePath.empty() ? std::nullopt : caseFaces(casePath, rest);
  mlsdeform::CellFaceList cells;
  if (own)
  {
    Mesh = std::move(own->faces);
  }
  else
  {
    vtkLogScopeF(TRACE, "mesh quality: the cells' faces");
    cells = cellFaces(rest);
  }
  Has3DCells = (own ? Mesh.cells : cells).faces() > 0;
  Measures.perFace = false; // the summary's maxima only
  if (Has3DCells)
  {
    gridPoints(rest, "the mesh's points", Points);
    if (!own)
    {
      vtkLogScopeF(TRACE, "mesh quality: interior and boundary faces");
      Mesh = mlsdeform::meshFaces(std::move(cells));
    }
    vtkLogScopeF(TRACE, "mesh quality: the undeformed mesh's figures");
    if (own && own->points == Points)
    {
      vtkLogF(TRACE, "mesh quality: the case's points are the grid's, their figures read with the faces");
      Orientation = std::move(own->orientation);
      Measures = std::move(own->measures);
      Work = std::move(own->work);
    }
    else
    {
      Orientation = mlsdeform::faceOrientation(Points, Mesh, Work, Measures);
    }
    Original = summarizeMeasures();
  }
}

QualitySummary VolumeMeshQuality::summary(vtkUnstructuredGrid* grid)
{
  gridPoints(grid, "the mesh's points", Points);
  if (Verdict == QualityVerdict::CheckMesh)
  {
    mlsdeform::faceMeasures(Points, Mesh, Orientation, Work, Measures);
  }
  return summarizeMeasures();
}

mlsdeform::AggregatePart VolumeMeshQuality::aggregatePart(
  const mlsdeform::PointList& points, long pointsKey, mlsdeform::QualityMeasure measure, double rho)
{
  if (pointsKey != TailKey || measure != TailMeasure || rho != TailRho)
  {
    Tail = mlsdeform::aggregateFaces(points, Mesh, Orientation, measure, rho, TailWork);
    TailKey = pointsKey;
    TailMeasure = measure;
    TailRho = rho;
  }
  return Tail.part;
}

void VolumeMeshQuality::addAggregateGradient(const mlsdeform::PointList& points, mlsdeform::QualityMeasure measure, double rho,
  const mlsdeform::AggregatePart& whole, mlsdeform::PointList& gradient) const
{
  mlsdeform::addAggregateGradient(points, Mesh, Orientation, TailWork, Tail.tail, measure, rho, whole, gradient);
}

std::vector<std::uint64_t> VolumeMeshQuality::boundaryKeys() const
{
  // the rest points: Points until the first summary of another grid, which comes after this
  return hasFaceMeasures() ? mlsdeform::boundaryKeys(Points, Mesh.cells, Mesh.boundary) : std::vector<std::uint64_t>();
}

void VolumeMeshQuality::leaveOutBoundaryFaces(const std::vector<std::uint64_t>& between)
{
  if (hasFaceMeasures() && mlsdeform::leaveOutFaces(Mesh.boundary, boundaryKeys(), between) > 0)
  {
    mlsdeform::faceMeasures(Points, Mesh, Orientation, Work, Measures);
    Original = summarizeMeasures();
    TailKey = -1;
  }
}

QualitySummary VolumeMeshQuality::summarizeMeasures()
{
  const bool checkMesh = Verdict == QualityVerdict::CheckMesh;
  QualitySummary summary{ Measures.invertedCells, Measures.maxNonOrthogonality, Measures.maxSkewness };
  summary.faceMeasures = checkMesh;
  if (!JacobianElements.empty())
  {
    // checkMesh's: the faces' inverted cells and the quadratic elements folded between their
    // corners; the FEM solver's: every element with det J <= 0 at one of its points
    if (checkMesh)
    {
      Inverted = Measures.inverted;
    }
    else
    {
      Inverted.assign(Inverted.size(), 0);
    }
    const double least = JacobianElements.measure(Points, Inverted);
    if (!checkMesh)
    {
      summary.minScaledJacobian = least; // the FEM verdict's figure; checkMesh has none
    }
    summary.inverted = static_cast<long>(std::count(Inverted.begin(), Inverted.end(), 1));
  }
  return summary;
}
} // namespace mlsvtk
