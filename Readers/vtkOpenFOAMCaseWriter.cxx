#include "vtkOpenFOAMCaseWriter.h"

#include "FoamPointsFile.h"

#include <vtkCharArray.h>
#include <vtkCompositeDataIterator.h>
#include <vtkCompositeDataSet.h>
#include <vtkDataArray.h>
#include <vtkErrorCode.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <unistd.h>

namespace fs = std::filesystem;

vtkStandardNewMacro(vtkOpenFOAMCaseWriter);

namespace
{
// The OpenFOAM reader's internal mesh: the input itself, or its block named internalMesh.
vtkPointSet* internalMesh(vtkDataObject* input)
{
  if (auto* set = vtkPointSet::SafeDownCast(input))
  {
    return set;
  }
  auto* composite = vtkCompositeDataSet::SafeDownCast(input);
  if (composite)
  {
    vtkSmartPointer<vtkCompositeDataIterator> it = vtkSmartPointer<vtkCompositeDataIterator>::Take(composite->NewIterator());
    for (it->InitTraversal(); !it->IsDoneWithTraversal(); it->GoToNextItem())
    {
      vtkInformation* meta = it->GetCurrentMetaData();
      if (meta && meta->Has(vtkCompositeDataSet::NAME()) && std::string(meta->Get(vtkCompositeDataSet::NAME())) == "internalMesh")
      {
        return vtkPointSet::SafeDownCast(it->GetCurrentDataObject());
      }
    }
  }
  throw std::runtime_error("the input has no internalMesh block: select internalMesh in the OpenFOAM reader's Mesh Regions");
}

// The reader's field data CasePath (a char array, or a string array), on the input or its mesh.
std::string casePath(vtkDataObject* input, vtkPointSet* mesh)
{
  for (vtkDataObject* data : { input, static_cast<vtkDataObject*>(mesh) })
  {
    vtkAbstractArray* array = data->GetFieldData()->GetAbstractArray("CasePath");
    if (auto* strings = vtkStringArray::SafeDownCast(array))
    {
      if (strings->GetNumberOfValues() > 0)
      {
        return strings->GetValue(0);
      }
    }
    if (auto* chars = vtkCharArray::SafeDownCast(array))
    {
      std::string path;
      for (vtkIdType i = 0; i < chars->GetNumberOfValues() && chars->GetValue(i) != '\0'; ++i)
      {
        path += chars->GetValue(i);
      }
      return path;
    }
  }
  throw std::runtime_error("the input did not come from an OpenFOAM case: it has no CasePath field data (read the case with "
                           "ParaView's OpenFOAM reader, or set SourceCase)");
}

bool isTimeName(const std::string& name)
{
  char* end = nullptr;
  std::strtod(name.c_str(), &end);
  return !name.empty() && *end == '\0';
}

// The source case's folders a new case needs: system, constant, the earliest time and 0.orig.
std::vector<fs::path> caseFolders(const fs::path& source)
{
  std::vector<fs::path> folders;
  for (const char* name : { "system", "constant" })
  {
    if (!fs::is_directory(source / name))
    {
      throw std::runtime_error(source.string() + " is not an OpenFOAM case: it has no " + name + " folder");
    }
    folders.push_back(source / name);
  }
  fs::path earliest;
  double earliestTime = std::numeric_limits<double>::infinity();
  for (const fs::directory_entry& entry : fs::directory_iterator(source))
  {
    const std::string name = entry.path().filename().string();
    if (entry.is_directory() && isTimeName(name) && std::strtod(name.c_str(), nullptr) < earliestTime)
    {
      earliestTime = std::strtod(name.c_str(), nullptr);
      earliest = entry.path();
    }
  }
  if (!earliest.empty())
  {
    if (fs::exists(earliest / "polyMesh"))
    {
      throw std::runtime_error("the case's mesh is in " + (earliest / "polyMesh").string() +
        " (a moved mesh); only cases with their mesh in constant/polyMesh are supported");
    }
    folders.push_back(earliest);
  }
  if (fs::is_directory(source / "0.orig"))
  {
    folders.push_back(source / "0.orig");
  }
  return folders;
}

// Copies folder into target, except the points file of constant/polyMesh.
void copyFolder(const fs::path& folder, const fs::path& target, const fs::path& skipped)
{
  fs::create_directory(target);
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
  {
    const fs::path to = target / entry.path().filename();
    if (entry.is_directory())
    {
      copyFolder(entry.path(), to, skipped);
    }
    else if (entry.path().parent_path() != skipped || (entry.path().filename() != "points" && entry.path().filename() != "points.gz"))
    {
      fs::copy_file(entry.path(), to);
    }
  }
}
}

int vtkOpenFOAMCaseWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

void vtkOpenFOAMCaseWriter::WriteData()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  fs::path partial;
  try
  {
    if (this->FileName.empty())
    {
      throw std::runtime_error("no FileName: give the new case's .foam file, e.g. variant/case.foam");
    }
    vtkDataObject* input = this->GetInput();
    vtkPointSet* mesh = internalMesh(input);
    const fs::path source = fs::absolute(this->SourceCase.empty() ? casePath(input, mesh) : this->SourceCase).lexically_normal();
    const fs::path foam = fs::absolute(this->FileName).lexically_normal();
    const fs::path target = foam.parent_path();
    if (fs::exists(target) && fs::exists(source) && fs::equivalent(target, source))
    {
      throw std::runtime_error("the target " + target.string() + " is the source case itself; write the variant to a new folder");
    }
    if (fs::exists(target) && !this->Overwrite)
    {
      throw std::runtime_error(target.string() + " exists; choose a new folder or set Overwrite");
    }
    const std::vector<fs::path> folders = caseFolders(source);
    const fs::path polyMesh = source / "constant" / "polyMesh";
    mlsdeform::FoamPointsFile points = mlsdeform::readFoamPoints(polyMesh.string());
    this->UpdateProgress(0.2);

    // The input must be this case's mesh: as many points at least (Decompose polyhedra appends
    // cell centres), each point of the input before deformation, out - Displacement, within
    // float round-off of the source's double: |fl(x) - x| <= eps_f / 2 |x| on reading and
    // |fl(fl(x) + d) - (fl(x) + d)| <= eps_f / 2 |fl(x) + d| on writing the moved point (a
    // whole eps_f covers the double round-off of the subtraction).
    const std::size_t n = points.size();
    vtkDataArray* displacement = mesh ? mesh->GetPointData()->GetArray("Displacement") : nullptr;
    if (auto* failure = vtkStringArray::SafeDownCast(input->GetFieldData()->GetAbstractArray("DeformationError")))
    {
      throw std::runtime_error("the deformation failed (" + failure->GetValue(0) + ")");
    }
    if (!mesh || !displacement || displacement->GetNumberOfComponents() != 3)
    {
      throw std::runtime_error("the internal mesh has no point array Displacement: write MLS Deform's output");
    }
    if (static_cast<std::size_t>(mesh->GetNumberOfPoints()) < n)
    {
      throw std::runtime_error("the internal mesh has " + std::to_string(mesh->GetNumberOfPoints()) + " points but " +
        points.path + " has " + std::to_string(n) + ": the input did not come from this case");
    }
    const double epsilon = std::numeric_limits<float>::epsilon();
    for (std::size_t i = 0; i < n; ++i)
    {
      double moved[3], d[3];
      mesh->GetPoint(static_cast<vtkIdType>(i), moved);
      displacement->GetTuple(static_cast<vtkIdType>(i), d);
      for (int c = 0; c < 3; ++c)
      {
        const double x = points.xyz[3 * i + c];
        if (!(std::abs(moved[c] - d[c] - x) <= epsilon * (std::abs(x) + std::abs(moved[c]))))
        {
          throw std::runtime_error("point " + std::to_string(i) + " of the input is not point " + std::to_string(i) + " of " +
            points.path + ": the input did not come from this case (or its points were reordered)");
        }
        points.xyz[3 * i + c] = x + d[c];
      }
    }
    points.xyz.resize(3 * n);
    this->UpdateProgress(0.4);

    // Assemble the case next to the target, then rename it into place.
    const fs::path parent = target.parent_path();
    if (!fs::is_directory(parent))
    {
      throw std::runtime_error("the folder " + parent.string() + " does not exist");
    }
    partial = parent / (target.filename().string() + ".writing-" + std::to_string(::getpid()));
    fs::remove_all(partial);
    if (!fs::create_directory(partial))
    {
      throw std::runtime_error("cannot create " + partial.string());
    }
    for (const fs::path& folder : folders)
    {
      copyFolder(folder, partial / folder.filename(), polyMesh);
    }
    this->UpdateProgress(0.6);
    mlsdeform::writeFoamPoints((partial / "constant" / "polyMesh").string(), points, points.xyz);
    if (!std::ofstream(partial / foam.filename()))
    {
      throw std::runtime_error("cannot create " + (partial / foam.filename()).string());
    }
    this->UpdateProgress(0.9);
    if (fs::exists(target))
    {
      const fs::path replaced = parent / (target.filename().string() + ".replaced-" + std::to_string(::getpid()));
      fs::rename(target, replaced);
      fs::rename(partial, target);
      fs::remove_all(replaced);
    }
    else
    {
      fs::rename(partial, target);
    }
    partial.clear();
    this->UpdateProgress(1.0);
  }
  catch (const std::exception& e)
  {
    std::error_code ignored;
    if (!partial.empty())
    {
      fs::remove_all(partial, ignored);
    }
    this->SetErrorCode(vtkErrorCode::UserError);
    vtkErrorMacro(<< "Cannot write the OpenFOAM case " << this->FileName << ": " << e.what() << ". Nothing was written.");
  }
}

void vtkOpenFOAMCaseWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n"
     << indent << "SourceCase: " << this->SourceCase << "\n"
     << indent << "Overwrite: " << this->Overwrite << "\n";
}
