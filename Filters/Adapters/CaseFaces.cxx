#include "Adapters/CaseFaces.h"

#include "Common/HeapPages.h"
#include "Foam/PolyMeshFiles.h"

#include <vtkIdList.h>
#include <vtkLogger.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <future>
#include <mutex>
#include <omp.h>
#include <vector>

namespace fs = std::filesystem;

namespace mlsvtk
{
namespace
{
// The case folder's name as both callers spell it (the reader's CasePath ends in '/').
std::string caseKey(const std::string& casePath)
{
  std::error_code error;
  fs::path path = fs::weakly_canonical(fs::path(casePath), error);
  if (error)
  {
    path = fs::path(casePath).lexically_normal();
  }
  return (path.has_filename() ? path : path.parent_path()).string();
}

// Whether a time folder of the case has a polyMesh of its own (a mesh that changes its cells).
bool changesCells(const fs::path& folder)
{
  std::error_code error;
  for (const fs::directory_entry& entry : fs::directory_iterator(folder, error))
  {
    if (mlsfoam::isTimeName(entry.path().filename().string()) && !mlsfoam::foamFile((entry.path() / "polyMesh").string(), "faces").empty())
    {
      return true;
    }
  }
  return false;
}

CaseMesh readCaseFaces(const std::string& folder)
{
  vtkLogScopeF(TRACE, "mesh quality: the case's faces, owner and neighbour");
  const std::string polyMesh = (fs::path(folder) / "constant" / "polyMesh").string();
  CaseMesh mesh;
  {
    const mlsfoam::FoamPointsFile points = mlsfoam::readFoamPoints(polyMesh);
    mesh.points.resize(points.size());
    for (std::size_t p = 0; p < points.size(); ++p)
    {
      for (int c = 0; c < 3; ++c)
      {
        mesh.points[p][c] = static_cast<float>(points.xyz[3 * p + c]); // as VTK's reader stores them
      }
    }
  }
  const mlsfoam::FoamFaces faces = mlsfoam::readFoamFaces(polyMesh);
  const std::vector<int> owner = mlsfoam::readFoamIndices(polyMesh, "owner");
  const std::vector<int> neighbour = mlsfoam::readFoamIndices(polyMesh, "neighbour");
  mesh.faces = mlsdeform::ownerNeighbourFaces(faces.start, faces.points, owner, neighbour, static_cast<int>(mesh.points.size()));
  mesh.measures.perFace = false;
  mesh.orientation = mlsdeform::faceOrientation(mesh.points, mesh.faces, mesh.work, mesh.measures);
  return mesh;
}

// Whether grid may be the case's mesh as OpenFOAM numbers it, as known before the faces are read:
// the case's cells are constant/polyMesh's at every time, and the grid has as many points and
// cells (not a process's piece, nor VTK's decomposed polyhedra). Throws when a file is unreadable.
bool sizedAsCase(const std::string& key, vtkUnstructuredGrid* grid)
{
  const mlsfoam::FoamMeshSize size = mlsfoam::readFoamMeshSize((fs::path(key) / "constant" / "polyMesh").string());
  return !changesCells(key) && (size.points < 0 || size.points == grid->GetNumberOfPoints()) &&
    (size.cells < 0 || size.cells == grid->GetNumberOfCells());
}

// The one read ahead: its case folder and its result.
std::mutex ahead;
std::string aheadCase;
std::future<CaseMesh> aheadFaces;

// Whether every cell of grid has the points of the faces' cell of its number.
bool sameCells(const mlsdeform::CellFaceList& cells, vtkUnstructuredGrid* grid)
{
  bool same = true;
#pragma omp parallel reduction(&& : same)
  {
    auto scratch = vtkSmartPointer<vtkIdList>::New();
    std::vector<vtkIdType> own, ofFaces;
#pragma omp for schedule(static)
    for (int c = 0; c < cells.cells(); ++c)
    {
      vtkIdType n = 0;
      const vtkIdType* points = nullptr;
      grid->GetCellPoints(c, n, points, scratch);
      own.assign(points, points + n);
      ofFaces.clear();
      for (long f = cells.firstFace(c); f < cells.firstFace(c + 1); ++f)
      {
        ofFaces.insert(ofFaces.end(), cells.face(f), cells.face(f) + cells.faceSize(f));
      }
      std::sort(own.begin(), own.end());
      std::sort(ofFaces.begin(), ofFaces.end());
      ofFaces.erase(std::unique(ofFaces.begin(), ofFaces.end()), ofFaces.end());
      same = same && own == ofFaces;
    }
  }
  return same;
}
} // namespace

void prefetchCaseFaces(const std::string& casePath)
{
  const std::string key = caseKey(casePath);
  std::lock_guard<std::mutex> lock(ahead);
  if (aheadCase == key && aheadFaces.valid())
  {
    return; // already under way
  }
  aheadCase = key;
  aheadFaces = std::async(std::launch::async, [key] {
    omp_set_num_threads(1); // this thread alone
    // VTK's reader runs on the other core and takes its memory from the heap's reserve (the batch
    // allocator's, mlsdeform/allocator.py) from the low end: the lower half faulted in before the
    // faces are read, so that the reader finds its next pages present, the rest (the set-up's) after
    vtkLogScopeF(TRACE, "mesh quality: the case's faces read ahead, the heap's reserve faulted in");
    mlsdeform::populateHeap(0.5);
    CaseMesh mesh = readCaseFaces(key);
    mlsdeform::populateHeap();
    return mesh;
  });
}

void readCaseFacesAhead(const std::string& casePath, vtkUnstructuredGrid* grid)
{
  try
  {
    if (grid && !casePath.empty() && sizedAsCase(caseKey(casePath), grid))
    {
      prefetchCaseFaces(casePath);
    }
  }
  catch (const std::exception&)
  {
    // not read ahead: caseFaces tells why when it measures
  }
}

std::optional<CaseMesh> caseFaces(const std::string& casePath, vtkUnstructuredGrid* grid)
{
  const std::string key = caseKey(casePath);
  try
  {
    std::future<CaseMesh> prefetched;
    {
      // taken, or dropped when read for another case: a read ahead is for the next measure
      std::lock_guard<std::mutex> lock(ahead);
      if (aheadCase == key)
      {
        prefetched = std::move(aheadFaces);
      }
      aheadFaces = std::future<CaseMesh>();
      aheadCase.clear();
    }
    if (!sizedAsCase(key, grid))
    {
      return std::nullopt;
    }
    CaseMesh read = prefetched.valid() ? prefetched.get() : readCaseFaces(key);
    if (static_cast<vtkIdType>(read.points.size()) != grid->GetNumberOfPoints() || read.faces.cells.cells() != grid->GetNumberOfCells())
    {
      return std::nullopt;
    }
    vtkLogScopeF(TRACE, "mesh quality: the case's cells against the grid's");
    if (!sameCells(read.faces.cells, grid))
    {
      return std::nullopt;
    }
    return read;
  }
  catch (const std::exception& e)
  {
    vtkLogF(TRACE, "mesh quality: the faces of %s are matched by their points: %s", key.c_str(), e.what());
    return std::nullopt;
  }
}
} // namespace mlsvtk
