#include "vtkMeshVariantWriter.h"

#include "SourceFile.h"

#include <vtkAlgorithm.h>
#include <vtkDataArray.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkObjectFactory.h>
#include <vtkIdTypeArray.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>

vtkStandardNewMacro(vtkMeshVariantWriter);

namespace
{
// The layouts of the sources written last, by path and modification time: the variants of one
// source (a design of experiments) read it once. A source changed since is read again (and one
// changed within its time's resolution is refused by writeVariant, which compares its content).
struct LayoutCache
{
  std::mutex lock;
  std::map<std::string, std::pair<std::filesystem::file_time_type, std::shared_ptr<const mlsformats::SourceFile>>> layouts;

  std::shared_ptr<const mlsformats::SourceFile> get(const std::string& path, const mlsformats::Format& format)
  {
    const auto time = std::filesystem::last_write_time(path);
    std::lock_guard<std::mutex> guard(this->lock);
    const auto found = this->layouts.find(path);
    if (found != this->layouts.end() && found->second.first == time)
    {
      return found->second.second;
    }
    if (this->layouts.size() >= 4)
    {
      this->layouts.clear();
    }
    std::shared_ptr<const mlsformats::SourceFile> layout(format.read(path, true));
    this->layouts[path] = { time, layout };
    return layout;
  }
};

LayoutCache& layoutCache()
{
  static LayoutCache cache;
  return cache;
}
} // namespace

int vtkMeshVariantWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkPointSet");
  return 1;
}

void vtkMeshVariantWriter::WriteData()
{
  vtkPointSet* input = vtkPointSet::SafeDownCast(this->GetInput());
  this->LastError.clear();
  this->SetErrorCode(0);
  try
  {
    if (!input || input->GetNumberOfPoints() == 0)
    {
      throw std::runtime_error("the input has no points");
    }
    std::string source = this->SourceFile;
    vtkStringArray* named = vtkStringArray::SafeDownCast(input->GetFieldData()->GetAbstractArray("SourceFile"));
    if (source.empty() && named && named->GetNumberOfValues() > 0)
    {
      source = named->GetValue(0);
    }
    if (source.empty())
    {
      throw std::runtime_error("the input does not name its source file (no field data SourceFile): set SourceFile, or deform "
                               "what the Mesh File reader read");
    }
    vtkDataArray* nodeIds = input->GetPointData()->GetArray("NodeId");
    if (!nodeIds || nodeIds->GetNumberOfComponents() != 1)
    {
      throw std::runtime_error("the input has no point array NodeId (the source's node ids, which the Mesh File reader gives): "
                               "it did not come from " + source);
    }
    if (this->FileName.empty())
    {
      throw std::runtime_error("no FileName to write the variant to");
    }
    const mlsformats::Format* format = mlsformats::formatOf(source);
    if (!format)
    {
      throw std::runtime_error(source + " cannot be read or is of no format a variant can be written of");
    }
    vtkIdTypeArray* integerIds = vtkIdTypeArray::SafeDownCast(nodeIds);
    const vtkIdType count = input->GetNumberOfPoints();
    std::vector<std::int64_t> ids(count);
    std::vector<double> xyz(3 * count);
    for (vtkIdType i = 0; i < count; ++i)
    {
      // as integers: a double holds ids only up to 2^53
      ids[i] = integerIds ? static_cast<std::int64_t>(integerIds->GetValue(i)) : static_cast<std::int64_t>(nodeIds->GetTuple1(i));
      input->GetPoint(i, xyz.data() + 3 * i);
    }
    layoutCache().get(source, *format)->writeVariant(this->FileName, ids.data(), xyz.data(), ids.size(), this->Overwrite != 0);
  }
  catch (const std::exception& e)
  {
    this->LastError = "No variant written to '" + this->FileName + "': " + e.what();
    vtkErrorMacro(<< this->LastError);
    this->SetErrorCode(1);
  }
}

void vtkMeshVariantWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "SourceFile: " << this->SourceFile << "\n";
  os << indent << "Overwrite: " << this->Overwrite << "\n";
}
