#include "vtkMeshVariantWriter.h"

#include "SourceFile.h"
#include "VariantInput.h"

#include <vtkAlgorithm.h>
#include <vtkCompositeDataSet.h>
#include <vtkInformation.h>
#include <vtkObjectFactory.h>

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
  info->Append(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkCompositeDataSet");
  return 1;
}

void vtkMeshVariantWriter::WriteData()
{
  vtkDataObject* input = this->GetInput();
  this->LastError.clear();
  this->SetErrorCode(0);
  try
  {
    const std::string source = this->FindSourceFile();
    if (source.empty())
    {
      throw std::runtime_error("the input does not name its source file (no field data SourceFile, and no reader of ParaView's "
                               "up the pipeline names one): set SourceFile, or deform what the Mesh File reader read");
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
    const std::shared_ptr<const mlsformats::SourceFile> layout = layoutCache().get(source, *format);
    std::vector<std::int64_t> ids;
    std::vector<double> xyz;
    mlsformats::variantNodesOf(input, layout->mesh, source, ids, xyz);
    layout->writeVariant(this->FileName, ids.data(), xyz.data(), ids.size(), this->Overwrite != 0);
  }
  catch (const std::exception& e)
  {
    this->LastError = "No variant written to '" + this->FileName + "': " + e.what();
    vtkErrorMacro(<< this->LastError);
    this->SetErrorCode(1);
  }
}

std::string vtkMeshVariantWriter::FindSourceFile()
{
  return this->SourceFile.empty() ? mlsformats::sourceFileOf(this, this->GetInput()) : this->SourceFile;
}

bool vtkMeshVariantWriter::FindSourceIsFem()
{
  const std::string source = this->FindSourceFile();
  const mlsformats::Format* format = source.empty() ? nullptr : mlsformats::formatOf(source);
  return format && format->fem;
}

void vtkMeshVariantWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n";
  os << indent << "SourceFile: " << this->SourceFile << "\n";
  os << indent << "Overwrite: " << this->Overwrite << "\n";
}
