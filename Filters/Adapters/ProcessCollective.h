// The core's Collective over VTK's global vtkMultiProcessController: ParaView's MPI ranks under
// pvbatch or pvserver; one process alone when there is no controller.
#pragma once

#include "Common/Collective.h"
#include "MLSDeformFiltersModule.h"

class vtkMultiProcessController;

namespace mlsvtk
{
class MLSDEFORMFILTERS_EXPORT ProcessCollective : public mlsdeform::Collective
{
public:
  /// The global controller's processes (one process when there is none).
  ProcessCollective();

  int size() const override;
  int rank() const override;
  std::vector<double> gather(const std::vector<double>& local) const override;
  std::vector<std::int64_t> gather(const std::vector<std::int64_t>& local) const override;
  std::vector<double> gatherOnFirst(const std::vector<double>& local) const override;
  void maximum(std::vector<double>& values) const override;
  void sum(std::vector<std::int64_t>& values) const override;
  std::string firstError(const std::string& local) const override;

private:
  vtkMultiProcessController* Controller = nullptr; // null: one process
};
}
