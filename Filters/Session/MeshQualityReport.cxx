#include "Session/MeshQualityReport.h"

#include "Session/SolutionReport.h"

#include <vtkObject.h>
#include <vtkPointSet.h>
#include <vtkUnstructuredGrid.h>

#include <cstdint>
#include <string>

using namespace mlsdeform;

namespace mlsvtk
{
void MeshQualityReport::report(const std::vector<vtkPointSet*>& inSets, const std::vector<vtkPointSet*>& outSets, vtkFieldData* field,
  const Collective& group, vtkObject* owner)
{
  Stamp stamp = cellsStamp(inSets);
  const Stamp points = pointsStamp(inSets);
  stamp.objects.insert(stamp.objects.end(), points.objects.begin(), points.objects.end());
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
        Quality.push_back(grid ? std::make_unique<VolumeMeshQuality>(grid) : nullptr);
        if (Quality.back() && Quality.back()->hasCells())
        {
          Original.add(Quality.back()->original());
        }
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
      vtkWarningWithObjectMacro(owner, << "The mesh quality is not reported: " << problem
                                       << ". (ParaView's OpenFOAM reader with Decompose polyhedra on makes such cells; turn it off to "
                                          "measure OpenFOAM's own cells.)");
    }
    Quality.resize(inSets.size());
    Measured = std::move(stamp);
  }
  QualitySummary deformed;
  bool measured = false;
  for (std::size_t s = 0; s < outSets.size(); ++s)
  {
    if (Quality[s] && Quality[s]->hasCells())
    {
      deformed.add(Quality[s]->summary(vtkUnstructuredGrid::SafeDownCast(outSets[s])));
      measured = true;
    }
  }
  if (!group.any(measured))
  {
    return;
  }
  for (auto [prefix, q] : { std::make_pair("", deformed), std::make_pair("Original", Original) })
  {
    std::vector<std::int64_t> inverted{ q.inverted };
    group.sum(inverted);
    std::vector<double> largest{ q.maxNonOrthogonality, q.maxSkewness };
    group.maximum(largest);
    addField(field, (std::string(prefix) + "InvertedCells").c_str(), static_cast<double>(inverted[0]));
    addField(field, (std::string(prefix) + "MaxNonOrthogonality").c_str(), largest[0]);
    addField(field, (std::string(prefix) + "MaxSkewness").c_str(), largest[1]);
  }
}
} // namespace mlsvtk
