#include "Session/MeshQualityReport.h"

#include "Adapters/CaseFaces.h"
#include "Adapters/CasePath.h"
#include "Session/SolutionReport.h"

#include <vtkDataArray.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkPoints.h>
#include <vtkPointSet.h>
#include <vtkStringArray.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <string>

using namespace mlsdeform;

namespace mlsvtk
{
namespace
{
// Whether two sets' points hold the same values, bit for bit.
bool samePoints(vtkPointSet* a, vtkPointSet* b)
{
  vtkDataArray* x = a->GetPoints() ? a->GetPoints()->GetData() : nullptr;
  vtkDataArray* y = b->GetPoints() ? b->GetPoints()->GetData() : nullptr;
  if (!x || !y || x->GetDataType() != y->GetDataType() || x->GetNumberOfValues() != y->GetNumberOfValues() ||
    !x->HasStandardMemoryLayout() || !y->HasStandardMemoryLayout())
  {
    return false;
  }
  return x == y ||
    std::memcmp(x->GetVoidPointer(0), y->GetVoidPointer(0), static_cast<std::size_t>(x->GetNumberOfValues()) * x->GetDataTypeSize()) == 0;
}

// The points of sets, for PieceInterfaces.
PieceInterfaces::PointOf pointsOf(const std::vector<vtkPointSet*>& sets)
{
  return [&sets](std::size_t s, long id) {
    double x[3];
    sets[s]->GetPoint(id, x);
    return Vec3(x[0], x[1], x[2]);
  };
}

// The largest measures of the faces between pieces, as a summary to add.
QualitySummary summaryOf(const PieceInterfaces::Measures& m)
{
  QualitySummary summary;
  for (double q : m.nonOrthogonality)
  {
    summary.maxNonOrthogonality = std::max(summary.maxNonOrthogonality, q);
  }
  for (double q : m.skewness)
  {
    summary.maxSkewness = std::max(summary.maxSkewness, q);
  }
  return summary;
}
}

Stamp MeshQualityReport::stampOf(const std::vector<vtkPointSet*>& inSets)
{
  Stamp stamp = cellsStamp(inSets);
  const Stamp points = pointsStamp(inSets);
  stamp.objects.insert(stamp.objects.end(), points.objects.begin(), points.objects.end());
  return stamp;
}

void MeshQualityReport::readAhead(const std::vector<vtkPointSet*>& inSets, const std::string& casePath) const
{
  if (!casePath.empty() && stampOf(inSets) != Measured)
  {
    for (vtkPointSet* set : inSets)
    {
      readCaseFacesAhead(casePath, vtkUnstructuredGrid::SafeDownCast(set));
    }
  }
}

void MeshQualityReport::report(const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets, vtkFieldData* field,
  const std::string& casePath, bool femSource, const Collective& group, vtkObject* owner)
{
  Stamp stamp = stampOf(inSets);
  if (group.any(stamp != Measured))
  {
    Quality.clear();
    Original = QualitySummary();
    std::string problem;
    try
    {
      for (vtkPointSet* set : inSets)
      {
        auto* grid = vtkUnstructuredGrid::SafeDownCast(set);
        // a structural solver's mesh file gets the FEM solver's verdict (its elements), a case and
        // a finite-volume solver's mesh checkMesh's
        const QualityVerdict verdict = femSource || femVerdictOf(set) ? QualityVerdict::FemSolver : QualityVerdict::CheckMesh;
        Quality.push_back(grid ? std::make_unique<VolumeMeshQuality>(grid, casePath, verdict) : nullptr);
      }
    }
    catch (const std::exception& e)
    {
      problem = e.what();
    }
    problem = group.firstError(problem);
    if (!problem.empty())
    {
      // the deformation stands; this mesh's quality is not reported (said once per mesh)
      Quality.clear();
      Interfaces = PieceInterfaces();
      Problem = problem + ". (ParaView's OpenFOAM reader with Decompose polyhedra on makes such cells: turn it off to measure "
                          "OpenFOAM's own cells.)";
      vtkWarningWithObjectMacro(owner, << "The mesh quality is not reported: " << Problem);
    }
    else
    {
      Problem.clear();
      std::vector<VolumeMeshQuality*> sets;
      for (const auto& quality : Quality)
      {
        sets.push_back(quality.get());
      }
      Interfaces.find(sets, pointsOf(inSets), group);
      for (const auto& quality : Quality)
      {
        if (quality && quality->hasCells())
        {
          Original.add(quality->original());
        }
      }
      Original.add(summaryOf(Interfaces.measure(pointsOf(inSets), group)));
    }
    Quality.resize(inSets.size());
    Measured = std::move(stamp);
  }
  if (!Problem.empty())
  {
    // why there are no figures, for whoever reads them (a design of experiments' error)
    vtkNew<vtkStringArray> why;
    why->SetName("MeshQualityProblem");
    why->InsertNextValue(Problem);
    field->AddArray(why);
  }
  Starts.assign(1, 0);
  for (vtkPointSet* set : inSets)
  {
    Starts.push_back(Starts.back() + set->GetNumberOfPoints());
  }
  QualitySummary deformed;
  bool measured = false;
  for (std::size_t s = 0; s < outSets.size(); ++s)
  {
    if (Quality[s] && Quality[s]->hasCells())
    {
      // points that did not move (a zero motion: the set-up's first update, a design at p = 0)
      // have the original's measures: no pass over the cells
      deformed.add(samePoints(inSets[s], outSets[s]) ? Quality[s]->original()
                                                     : Quality[s]->summary(vtkUnstructuredGrid::SafeDownCast(outSets[s])));
      measured = true;
    }
  }
  deformed.add(summaryOf(Interfaces.measure(pointsOf(outSets), group)));
  if (!group.any(measured))
  {
    return;
  }
  for (auto [prefix, q] : { std::make_pair("", deformed), std::make_pair("Original", Original) })
  {
    std::vector<std::int64_t> inverted{ q.inverted };
    group.sum(inverted);
    std::vector<double> largest{ q.maxNonOrthogonality, q.maxSkewness, -q.minScaledJacobian };
    group.maximum(largest);
    addField(field, (std::string(prefix) + "InvertedCells").c_str(), static_cast<double>(inverted[0]));
    if (group.any(q.faceMeasures)) // checkMesh's figures; none on a solver's mesh file
    {
      addField(field, (std::string(prefix) + "MaxNonOrthogonality").c_str(), largest[0]);
      addField(field, (std::string(prefix) + "MaxSkewness").c_str(), largest[1]);
    }
    if (std::isfinite(largest[2])) // the FEM verdict, where some process has elements
    {
      addField(field, (std::string(prefix) + "MinScaledJacobian").c_str(), -largest[2]);
    }
  }
}

MeshQualityReport::Aggregate MeshQualityReport::aggregate(
  const PointList& points, long pointsKey, QualityMeasure measure, double rho, const Collective& group, std::vector<double>* gradient)
{
  auto meshPoints = [&](std::size_t s) {
    return PointList(points.begin() + Starts[s], points.begin() + Starts[s + 1]);
  };
  // the scaled Jacobian: KS of -sj over the FEM meshes' elements, returned negated (a lower bound of the least)
  const bool elements = measure == QualityMeasure::ScaledJacobian;
  std::vector<PointList> measured(Quality.size());
  AggregatePart local;
  agree(group, [&] {
    if (Starts.empty() || static_cast<long>(points.size()) != Starts.back())
    {
      throw InvalidInputException("the mesh quality was not measured on these points: update the filter with MeshQuality on");
    }
    for (std::size_t s = 0; s < Quality.size(); ++s)
    {
      if (Quality[s] && (elements ? Quality[s]->hasElementMeasures() : Quality[s]->hasFaceMeasures()))
      {
        measured[s] = meshPoints(s);
        local.add(elements ? Quality[s]->elements().aggregatePart(measured[s], rho) : Quality[s]->aggregatePart(measured[s], pointsKey, measure, rho), rho);
      }
    }
  });
  if (!elements)
  {
    // the faces between pieces, after this process's own
    const PieceInterfaces::Measures& shared = Interfaces.measure([&](std::size_t s, long id) { return points[Starts[s] + id]; }, group);
    local.add(aggregatePart(measure == QualityMeasure::NonOrthogonality ? shared.nonOrthogonality : shared.skewness, rho), rho);
  }
  // every process's part, combined in process order: the same on every process
  const std::vector<double> parts = group.gather(std::vector<double>{ local.largest, local.sum, static_cast<double>(local.count) });
  AggregatePart whole;
  for (std::size_t r = 0; r + 2 < parts.size(); r += 3)
  {
    whole.add(AggregatePart{ parts[r], parts[r + 1], static_cast<long>(parts[r + 2]) }, rho);
  }
  if (whole.count == 0)
  {
    throw InvalidInputException(!Problem.empty() ? "the mesh quality is not measured: " + Problem
        : elements ? std::string("no volume mesh gets an FEM solver's verdict (the scaled Jacobian of its elements: a structural "
                                 "solver's mesh file); a CFD mesh has the non-orthogonality and skewness")
                   : std::string("no volume mesh has checkMesh's face measures (interior faces of 3D cells; "
                                 "an FEM solver's mesh gets the scaled Jacobian instead)"));
  }
  if (gradient)
  {
    gradient->assign(3 * points.size(), 0.0);
    for (std::size_t s = 0; s < Quality.size(); ++s)
    {
      if (!measured[s].empty())
      {
        PointList g(measured[s].size(), Vec3::Zero());
        if (elements)
        {
          Quality[s]->elements().addAggregateGradient(measured[s], rho, whole, g);
        }
        else
        {
          Quality[s]->addAggregateGradient(measured[s], measure, rho, whole, g);
        }
        for (std::size_t i = 0; i < g.size(); ++i)
        {
          for (int c = 0; c < 3; ++c)
          {
            (*gradient)[3 * (Starts[s] + i) + c] = elements ? -g[i][c] : g[i][c];
          }
        }
      }
    }
    if (!elements)
    {
      for (const PieceInterfaces::Term& t : Interfaces.aggregateGradient(measure, rho, whole, group))
      {
        for (int c = 0; c < 3; ++c)
        {
          (*gradient)[3 * (Starts[t.set] + t.point) + c] += t.value[c];
        }
      }
    }
  }
  return { elements ? -whole.value(rho) : whole.value(rho), whole.count };
}
} // namespace mlsvtk
