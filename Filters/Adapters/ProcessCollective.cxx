#include "Adapters/ProcessCollective.h"

#include <vtkCommunicator.h>
#include <vtkMultiProcessController.h>

#include <numeric>

namespace mlsvtk
{
namespace
{
// Where each process's values start in the concatenation of all (a gather's displacements: the sum
// of the lengths before it), then the total length.
std::vector<vtkIdType> gatherOffsets(const std::vector<vtkIdType>& lengths)
{
  std::vector<vtkIdType> starts(lengths.size() + 1, 0);
  std::partial_sum(lengths.begin(), lengths.end(), starts.begin() + 1);
  return starts;
}

// Every process's values concatenated in process order (AllGatherV with the lengths gathered first).
template <typename T>
std::vector<T> gatherValues(vtkMultiProcessController* controller, const std::vector<T>& local)
{
  const int n = controller->GetNumberOfProcesses();
  vtkIdType length = static_cast<vtkIdType>(local.size());
  std::vector<vtkIdType> lengths(n);
  controller->AllGather(&length, lengths.data(), 1);
  std::vector<vtkIdType> offsets = gatherOffsets(lengths); // not const: VTK asks for vtkIdType*
  std::vector<T> all(static_cast<std::size_t>(offsets.back()));
  // AllGatherV reads the send buffer even for zero length: give it a valid address
  T none{};
  controller->AllGatherV(local.empty() ? &none : local.data(), all.empty() ? &none : all.data(), length, lengths.data(), offsets.data());
  return all;
}
}

ProcessCollective::ProcessCollective()
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (controller && controller->GetNumberOfProcesses() > 1)
  {
    this->Controller = controller;
  }
}

int ProcessCollective::size() const
{
  return this->Controller ? this->Controller->GetNumberOfProcesses() : 1;
}

int ProcessCollective::rank() const
{
  return this->Controller ? this->Controller->GetLocalProcessId() : 0;
}

std::vector<double> ProcessCollective::gather(const std::vector<double>& local) const
{
  return this->Controller ? gatherValues(this->Controller, local) : local;
}

std::vector<std::int64_t> ProcessCollective::gather(const std::vector<std::int64_t>& local) const
{
  if (!this->Controller)
  {
    return local;
  }
  const std::vector<long long> values(local.begin(), local.end());
  const std::vector<long long> all = gatherValues(this->Controller, values);
  return std::vector<std::int64_t>(all.begin(), all.end());
}

std::vector<double> ProcessCollective::gatherOnFirst(const std::vector<double>& local) const
{
  if (!this->Controller)
  {
    return local;
  }
  const int n = this->Controller->GetNumberOfProcesses();
  vtkIdType length = static_cast<vtkIdType>(local.size());
  std::vector<vtkIdType> lengths(n);
  this->Controller->Gather(&length, lengths.data(), 1, 0);
  std::vector<vtkIdType> offsets = gatherOffsets(lengths); // meaningful on the first process only, which gathered the lengths
  std::vector<double> all(this->rank() == 0 ? static_cast<std::size_t>(offsets.back()) : 0);
  double none = 0; // GatherV reads the buffers even for zero length: give them valid addresses
  this->Controller->GatherV(local.empty() ? &none : local.data(), all.empty() ? &none : all.data(), length, lengths.data(), offsets.data(), 0);
  return all;
}

void ProcessCollective::maximum(std::vector<double>& values) const
{
  if (this->Controller && !values.empty())
  {
    const std::vector<double> local = values;
    this->Controller->AllReduce(local.data(), values.data(), static_cast<vtkIdType>(values.size()), vtkCommunicator::MAX_OP);
  }
}

void ProcessCollective::sum(std::vector<std::int64_t>& values) const
{
  if (this->Controller && !values.empty())
  {
    const std::vector<long long> local(values.begin(), values.end());
    std::vector<long long> total(values.size());
    this->Controller->AllReduce(local.data(), total.data(), static_cast<vtkIdType>(values.size()), vtkCommunicator::SUM_OP);
    values.assign(total.begin(), total.end());
  }
}

std::string ProcessCollective::firstError(const std::string& local) const
{
  if (!this->Controller)
  {
    return local;
  }
  const std::vector<char> mine(local.begin(), local.end());
  const std::vector<long long> lengths = gatherValues(this->Controller, std::vector<long long>{ static_cast<long long>(mine.size()) });
  const std::vector<char> all = gatherValues(this->Controller, mine);
  std::size_t offset = 0;
  for (long long length : lengths)
  {
    if (length > 0)
    {
      return std::string(all.begin() + static_cast<long>(offset), all.begin() + static_cast<long>(offset + length));
    }
    offset += static_cast<std::size_t>(length);
  }
  return std::string();
}
}
