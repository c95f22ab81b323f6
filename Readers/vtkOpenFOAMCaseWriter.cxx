#include "vtkOpenFOAMCaseWriter.h"

#include "Foam/PolyMeshFiles.h"
#include "Adapters/CasePath.h"
#include "Adapters/ProcessCollective.h"
#include "Adapters/TypedPoints.h"
#include "Vocabulary/FieldNames.h"

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
#include <vtkPoints.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>

#include <algorithm>
#include <cctype>
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

// The reader's field data CasePath, on the input or its mesh.
std::string casePath(vtkDataObject* input, vtkPointSet* mesh)
{
  for (vtkDataObject* data : { input, static_cast<vtkDataObject*>(mesh) })
  {
    const std::string path = mlsvtk::casePathOf(data);
    if (!path.empty())
    {
      return path;
    }
  }
  throw std::runtime_error("the input did not come from an OpenFOAM case: it has no CasePath field data (read the case with "
                           "ParaView's OpenFOAM reader, or set SourceCase)");
}

// The folders a new case needs of a case folder (the case, or one of its processor folders): the
// required ones (system and constant, or constant), the earliest time and 0.orig.
std::vector<fs::path> caseFolders(const fs::path& source, const std::vector<std::string>& required)
{
  std::vector<fs::path> folders;
  for (const std::string& name : required)
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
    if (entry.is_directory() && mlsfoam::isTimeName(name) && std::strtod(name.c_str(), nullptr) < earliestTime)
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

// The processor folders of a decomposed case (processor0, processor1, ...) in the order of their
// numbers, as ParaView's OpenFOAM reader takes them; collated ones (processors4) are refused.
std::vector<std::string> processorFolders(const fs::path& source)
{
  std::vector<std::pair<long, std::string>> numbered;
  for (const fs::directory_entry& entry : fs::directory_iterator(source))
  {
    const std::string name = entry.path().filename().string();
    if (!entry.is_directory() || name.compare(0, 9, "processor") != 0)
    {
      continue;
    }
    char* end = nullptr;
    const long number = std::strtol(name.c_str() + 9, &end, 10);
    if (name.size() > 9 && std::isdigit(static_cast<unsigned char>(name[9])) && *end == '\0')
    {
      numbered.emplace_back(number, name);
    }
    else if (name.size() > 10 && name[9] == 's' && std::isdigit(static_cast<unsigned char>(name[10])))
    {
      throw std::runtime_error("the case is decomposed in the collated format (" + name + "), which is not supported");
    }
  }
  std::sort(numbered.begin(), numbered.end());
  std::vector<std::string> names;
  for (const auto& folder : numbered)
  {
    names.push_back(folder.second);
  }
  return names;
}

// Copies folder into target, except the points file of constant/polyMesh.
void copyFolder(const fs::path& folder, const fs::path& target, const fs::path& skipped, bool link)
{
  fs::create_directory(target);
  for (const fs::directory_entry& entry : fs::directory_iterator(folder))
  {
    const fs::path to = target / entry.path().filename();
    if (entry.is_directory())
    {
      copyFolder(entry.path(), to, skipped, link);
    }
    else if (entry.path().parent_path() != skipped || (entry.path().filename() != "points" && entry.path().filename() != "points.gz"))
    {
      if (link)
      {
        fs::create_symlink(fs::canonical(entry.path()), to); // OpenFOAM reads through it
      }
      else
      {
        fs::copy_file(entry.path(), to);
      }
    }
  }
}

// Whether the input's point i, before the deformation (out - Displacement), is the double x
// within float round-off: |fl(x) - x| <= eps_f / 2 |x| on reading and |fl(fl(x) + d) - (fl(x)
// + d)| <= eps_f / 2 |fl(x) + d| on writing the moved point (a whole eps_f covers the double
// round-off of the subtraction).
bool samePoint(const double* x, const double moved[3], const double d[3])
{
  const double epsilon = std::numeric_limits<float>::epsilon();
  for (int c = 0; c < 3; ++c)
  {
    if (!(std::abs(moved[c] - d[c] - x[c]) <= epsilon * (std::abs(x[c]) + std::abs(moved[c]))))
    {
      return false;
    }
  }
  return true;
}

// The internal mesh as read: its points and their Displacement.
struct InputMesh
{
  vtkPointSet* mesh = nullptr;
  vtkDataArray* displacement = nullptr;
  vtkIdType size() const { return mesh ? mesh->GetNumberOfPoints() : 0; }
  void at(vtkIdType i, double moved[3], double d[3]) const
  {
    mesh->GetPoint(i, moved);
    displacement->GetTuple(i, d);
  }
};

// Whether a polyMesh folder holds a mesh (a decomposed case may keep an empty constant/polyMesh).
bool hasPoints(const fs::path& polyMesh)
{
  return !mlsfoam::foamFile(polyMesh.string(), "points").empty();
}

// A mesh file of the case (the reconstructed mesh, processor -1, or a processor's) and the
// displacement of its points.
struct MeshFile
{
  int processor = -1;
  mlsfoam::FoamPointsFile points; // as in the source case
  std::vector<double> displacement; // 3 per point
  std::vector<double> moved() const
  {
    std::vector<double> xyz(points.xyz.size());
    for (std::size_t k = 0; k < xyz.size(); ++k)
    {
      xyz[k] = points.xyz[k] + displacement[k];
    }
    return xyz;
  }
};

// The polyMesh folder of a case folder root (the source, or the variant being assembled): the
// reconstructed mesh's (processor -1) or processor folder `processor`'s.
fs::path polyMeshOf(const fs::path& root, const std::vector<std::string>& processors, int processor)
{
  return (processor < 0 ? root : root / processors[static_cast<std::size_t>(processor)]) / "constant" / "polyMesh";
}

// A mesh file of the source case, its points read, no displacement yet.
MeshFile readMeshFile(const fs::path& source, const std::vector<std::string>& processors, int processor)
{
  return { processor, mlsfoam::readFoamPoints(polyMeshOf(source, processors, processor).string()), {} };
}

// Tuples first, first + 1, ... (3 components) of an array into doubles: from the array's memory
// where it is a plain float or double array (per-point virtual calls took half of a 1M-point
// variant's write), else tuple by tuple.
void copyTuples(vtkDataArray* from, vtkIdType first, std::size_t count, double* to)
{
  if (!mlsvtk::withTypedPoints(from, [&](const auto* values) { std::copy_n(values + 3 * first, 3 * count, to); }))
  {
    for (std::size_t i = 0; i < count; ++i)
    {
      from->GetTuple(first + static_cast<vtkIdType>(i), to + 3 * i);
    }
  }
}

// Takes the Displacement of the input's points offset, offset + 1, ... for the points of a mesh
// file: false when the input's points there are not the file's.
bool displaceBy(MeshFile& file, const InputMesh& input, vtkIdType offset)
{
  const std::size_t n = file.points.size();
  if (offset < 0 || static_cast<std::size_t>(input.size() - offset) < n)
  {
    return false;
  }
  file.displacement.resize(3 * n);
  std::vector<double> moved(3 * n);
  copyTuples(input.mesh->GetPoints()->GetData(), offset, n, moved.data());
  copyTuples(input.displacement, offset, n, file.displacement.data());
  for (std::size_t i = 0; i < n; ++i)
  {
    if (!samePoint(&file.points.xyz[3 * i], &moved[3 * i], &file.displacement[3 * i]))
    {
      return false;
    }
  }
  return true;
}

// How the input holds the case's mesh on this process.
enum class Reading : std::int64_t
{
  Nothing = 0,       // no points here
  Reconstructed = 1, // constant/polyMesh (with cell centres after it for Decompose polyhedra)
  Decomposed = 2     // the processor folders rank, rank + size, ..., each followed by its cell centres
};

// ParaView's OpenFOAM reader reads a reconstructed case on one process, and hands the processor
// folders of a decomposed one out in turn (process r: folders r, r + size, ...), appending each
// folder's points and, with Decompose polyhedra, its cell centres after them.

// The processor folders the reader gave this process (rank, rank + size, ...), matched one after
// the other, each followed by its cell centres: false, with what was tried, when they are not
// the input's points.
bool matchProcessors(const fs::path& source, const std::vector<std::string>& processors, const InputMesh& input,
  const mlsdeform::Collective& group, std::vector<MeshFile>& read, std::string& tried)
{
  std::vector<MeshFile> parts;
  vtkIdType offset = 0;
  for (std::size_t p = static_cast<std::size_t>(group.rank()); p < processors.size(); p += static_cast<std::size_t>(group.size()))
  {
    MeshFile part = readMeshFile(source, processors, static_cast<int>(p));
    // the cell centres of the folder before: the points up to the first that is this folder's
    // first point (a cell centre lies inside its cell, never on a vertex)
    while (!parts.empty() && offset < input.size() && part.points.size() > 0)
    {
      double out[3], d[3];
      input.at(offset, out, d);
      if (samePoint(part.points.xyz.data(), out, d))
      {
        break;
      }
      ++offset;
    }
    if (!displaceBy(part, input, offset))
    {
      tried = part.points.path + " (" + std::to_string(part.points.size()) + " points, from input point " + std::to_string(offset) + ")";
      return false;
    }
    offset += static_cast<vtkIdType>(part.points.size());
    parts.push_back(std::move(part));
  }
  read = std::move(parts);
  return !read.empty();
}

// This process's part of the input matched to the case's mesh files: their displacements.
// The processor folders are tried first, so that a process of a decomposed reading reads only
// its own folders, not the whole mesh.
Reading matchInput(const fs::path& source, const std::vector<std::string>& processors, const InputMesh& input,
  const mlsdeform::Collective& group, std::vector<MeshFile>& read)
{
  if (input.size() == 0)
  {
    return Reading::Nothing;
  }
  std::string tried;
  if (matchProcessors(source, processors, input, group, read, tried))
  {
    return Reading::Decomposed;
  }
  if (hasPoints(polyMeshOf(source, processors, -1)))
  {
    MeshFile whole = readMeshFile(source, processors, -1);
    if (displaceBy(whole, input, 0))
    {
      read.push_back(std::move(whole));
      return Reading::Reconstructed;
    }
    tried += (tried.empty() ? "" : " nor ") + whole.points.path + " (" + std::to_string(whole.points.size()) + " points)";
  }
  throw std::runtime_error("the internal mesh's " + std::to_string(input.size()) + " points are not those of " +
    (tried.empty() ? "any mesh of the case" : tried) + ": the input did not come from this case (or its points were reordered)");
}

// Moves the points of mesh file `to` as those of `from` move, through a processor's
// pointProcAddressing (its point i is point addressing[i] of the whole mesh): from the whole
// mesh to a processor's (toWhole false) or from a processor's to the whole mesh. The two files'
// points must agree within float round-off (a processor folder decomposed from this mesh).
void displaceThrough(const std::vector<std::int64_t>& addressing, const MeshFile& from, bool toWhole, MeshFile& to, std::vector<char>& reached)
{
  const std::size_t n = to.points.size();
  to.displacement.resize(3 * n);
  reached.resize(n);
  const std::size_t processorSize = toWhole ? from.points.size() : n;
  if (addressing.size() != processorSize)
  {
    throw std::runtime_error("the pointProcAddressing of " + (toWhole ? from : to).points.path + " has " + std::to_string(addressing.size()) +
      " labels for " + std::to_string(processorSize) + " points");
  }
  for (std::size_t i = 0; i < addressing.size(); ++i)
  {
    const std::size_t a = static_cast<std::size_t>(addressing[i]);
    const std::size_t target = toWhole ? a : i, source = toWhole ? i : a;
    if (addressing[i] < 0 || a >= (toWhole ? n : from.points.size()))
    {
      throw std::runtime_error("the pointProcAddressing of " + (toWhole ? from : to).points.path + " refers to point " + std::to_string(addressing[i]) + " outside the mesh");
    }
    const double zero[3] = { 0, 0, 0 };
    if (!samePoint(&to.points.xyz[3 * target], &from.points.xyz[3 * source], zero))
    {
      throw std::runtime_error((toWhole ? from : to).points.path + " does not hold the points of the whole mesh (point " + std::to_string(i) +
        " is not point " + std::to_string(a) + "): the processor folders were not decomposed from this mesh");
    }
    std::copy_n(&from.displacement[3 * source], 3, &to.displacement[3 * target]);
    reached[target] = 1;
  }
}

// The pointProcAddressing of processor folder `processor` of the case.
std::vector<std::int64_t> pointAddressing(const fs::path& source, const std::vector<std::string>& processors, int processor)
{
  return mlsfoam::readFoamLabels(polyMeshOf(source, processors, processor).string(), "pointProcAddressing");
}
}

int vtkOpenFOAMCaseWriter::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

// Under MPI (pvbatch, pvserver) every process calls WriteData with its piece: the processes
// agree on each step (a failure on one stops all with its message), process 0 assembles the
// case folder and renames it into place, each process writes the processor folders it read.
void vtkOpenFOAMCaseWriter::WriteData()
{
  this->SetErrorCode(vtkErrorCode::NoError);
  this->LastError.clear();
  const mlsvtk::ProcessCollective group;
  const bool first = group.rank() == 0;
  fs::path partial;
  try
  {
    // 1. the source case, the target and this process's part of the mesh
    InputMesh input;
    std::string localSource = this->SourceCase;
    fs::path source, foam, target;
    std::vector<std::string> processors;
    std::vector<MeshFile> read;
    Reading reading = Reading::Nothing;
    mlsdeform::agree(group, [&] {
      if (this->FileName.empty())
      {
        throw std::runtime_error("no FileName: give the new case's .foam file, e.g. variant/case.foam");
      }
      const std::string extension = fs::path(this->FileName).extension().string();
      if (extension != ".foam" && extension != ".OpenFOAM")
      {
        // its folder becomes the case: a folder named here would have its parent replaced
        throw std::runtime_error("the FileName is not a .foam file: name the new case's .foam file, e.g. " +
          (fs::path(this->FileName) / "case.foam").string());
      }
      vtkDataObject* data = this->GetInput();
      if (auto* failure = vtkStringArray::SafeDownCast(data->GetFieldData()->GetAbstractArray(mlsvtk::fields::Error)))
      {
        throw std::runtime_error("the deformation failed (" + failure->GetValue(0) + ")");
      }
      input.mesh = internalMesh(data);
      input.displacement = input.mesh->GetPointData()->GetArray(mlsvtk::fields::Displacement);
      if (input.size() > 0 && (!input.displacement || input.displacement->GetNumberOfComponents() != 3))
      {
        throw std::runtime_error("the internal mesh has no point array Displacement: write MLS Deform's output");
      }
      if (localSource.empty() && input.size() > 0)
      {
        localSource = casePath(data, input.mesh);
      }
    });
    // a process that read nothing may not have CasePath: the first process's that has one
    const std::string sourceName = group.firstError(localSource);
    mlsdeform::agree(group, [&] {
      if (sourceName.empty())
      {
        throw std::runtime_error("the internal mesh is empty");
      }
      source = fs::absolute(sourceName).lexically_normal();
      foam = fs::absolute(this->FileName).lexically_normal();
      target = foam.parent_path();
      if (fs::exists(target) && fs::exists(source) && fs::equivalent(target, source))
      {
        throw std::runtime_error("the target " + target.string() + " is the source case itself; write the variant to a new folder");
      }
      if (first && fs::exists(target) && !this->Overwrite)
      {
        throw std::runtime_error(target.string() + " exists; choose a new folder or set Overwrite");
      }
      if (first && fs::exists(target) && !fs::exists(target / "system" / "controlDict"))
      {
        throw std::runtime_error(target.string() + " exists and is not an OpenFOAM case (no system/controlDict): it is not "
                                                   "replaced; choose a new folder");
      }
      if (!fs::is_directory(source))
      {
        throw std::runtime_error("the source case " + source.string() + " does not exist");
      }
      processors = processorFolders(source);
      reading = matchInput(source, processors, input, group, read);
    });
    this->UpdateProgress(0.2);

    // 2. the same reading on all processes: a reconstructed mesh on one, or every processor
    // folder on the process the reader gave it to
    const std::vector<std::int64_t> readings = group.gather(std::vector<std::int64_t>{ static_cast<std::int64_t>(reading) });
    const auto count = [&](Reading r) { return std::count(readings.begin(), readings.end(), static_cast<std::int64_t>(r)); };
    if (count(Reading::Reconstructed) > 1 || (count(Reading::Reconstructed) == 1 && count(Reading::Decomposed) > 0))
    {
      throw std::runtime_error("the processes hold the case's mesh in different ways (read it reconstructed on one process, or "
                               "decomposed with Case Type 'Decomposed Case')");
    }
    const bool decomposed = count(Reading::Decomposed) > 0;
    for (int r = 0; decomposed && r < group.size() && static_cast<std::size_t>(r) < processors.size(); ++r)
    {
      if (readings[static_cast<std::size_t>(r)] != static_cast<std::int64_t>(Reading::Decomposed))
      {
        throw std::runtime_error("process " + std::to_string(r) + " holds no points of " + processors[static_cast<std::size_t>(r)] +
          ": the input is not the whole decomposed case");
      }
    }
    this->UpdateProgress(0.3);

    // 3. the case folder, assembled beside the target by the first process
    std::string partialName;
    mlsdeform::agree(group, [&] {
      if (!first)
      {
        return;
      }
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
      partialName = partial.string();
      for (const fs::path& folder : caseFolders(source, { "system", "constant" }))
      {
        copyFolder(folder, partial / folder.filename(), polyMeshOf(source, processors, -1), this->LinkUnchangedFiles);
      }
      for (std::size_t p = 0; p < processors.size(); ++p)
      {
        fs::create_directory(partial / processors[p]);
        for (const fs::path& folder : caseFolders(source / processors[p], { "constant" }))
        {
          copyFolder(folder, partial / processors[p] / folder.filename(), polyMeshOf(source, processors, static_cast<int>(p)),
            this->LinkUnchangedFiles);
        }
      }
      if (!std::ofstream(partial / foam.filename()))
      {
        throw std::runtime_error("cannot create " + (partial / foam.filename()).string());
      }
    });
    const fs::path assembled = group.firstError(partialName);
    this->UpdateProgress(0.5);

    // 4. the mesh files: each process writes those it read, and moves the others through the
    // processors' pointProcAddressing: a reconstructed reading moves every processor folder, a
    // decomposed one the reconstructed mesh (the processes' displacements gathered on the first)
    const auto writeMoved = [&](const MeshFile& file) {
      mlsfoam::writeFoamPoints(polyMeshOf(assembled, processors, file.processor).string(), file.points, file.moved());
    };
    const bool wholeMesh = hasPoints(polyMeshOf(source, processors, -1));
    std::vector<double> displacements; // of this process's processor folders, in their order
    mlsdeform::agree(group, [&] {
      for (const MeshFile& file : read)
      {
        writeMoved(file);
        displacements.insert(displacements.end(), file.displacement.begin(), file.displacement.end());
      }
      for (std::size_t p = 0; reading == Reading::Reconstructed && p < processors.size(); ++p)
      {
        MeshFile part = readMeshFile(source, processors, static_cast<int>(p));
        std::vector<char> reached;
        displaceThrough(pointAddressing(source, processors, static_cast<int>(p)), read.front(), false, part, reached);
        writeMoved(part);
      }
    });
    if (decomposed && wholeMesh)
    {
      const std::vector<double> all = group.gatherOnFirst(displacements);
      mlsdeform::agree(group, [&] {
        if (!first)
        {
          return;
        }
        MeshFile whole = readMeshFile(source, processors, -1);
        std::vector<char> reached;
        std::size_t at = 0;
        // the processes' folders in the order gathered: process r's are r, r + size, ...
        for (int r = 0; r < group.size(); ++r)
        {
          for (std::size_t p = static_cast<std::size_t>(r); p < processors.size(); p += static_cast<std::size_t>(group.size()))
          {
            MeshFile part = readMeshFile(source, processors, static_cast<int>(p));
            part.displacement.assign(all.begin() + static_cast<long>(at), all.begin() + static_cast<long>(at + part.points.xyz.size()));
            at += part.points.xyz.size();
            displaceThrough(pointAddressing(source, processors, static_cast<int>(p)), part, true, whole, reached);
          }
        }
        if (std::count(reached.begin(), reached.end(), 0) > 0)
        {
          throw std::runtime_error("the processor folders do not hold every point of " + whole.points.path);
        }
        writeMoved(whole);
      });
    }
    this->UpdateProgress(0.9);

    // 5. the assembled case renamed into place
    mlsdeform::agree(group, [&] {
      if (!first)
      {
        return;
      }
      if (fs::exists(target))
      {
        const fs::path replaced = target.parent_path() / (target.filename().string() + ".replaced-" + std::to_string(::getpid()));
        fs::rename(target, replaced);
        fs::rename(partial, target);
        fs::remove_all(replaced);
      }
      else
      {
        fs::rename(partial, target);
      }
      partial.clear();
    });
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
    this->LastError = "Cannot write the OpenFOAM case " + this->FileName + ": " + e.what() + ". Nothing was written.";
    vtkErrorMacro(<< this->LastError);
  }
}

void vtkOpenFOAMCaseWriter::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "FileName: " << this->FileName << "\n"
     << indent << "SourceCase: " << this->SourceCase << "\n"
     << indent << "Overwrite: " << this->Overwrite << "\n"
     << indent << "LinkUnchangedFiles: " << this->LinkUnchangedFiles << "\n";
}
