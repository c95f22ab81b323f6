#include "Adapters/MeshVolume.h"

#include "Adapters/MeshCells.h"
#include "Adapters/VolumeMeshQuality.h"
#include "Quality/FaceQuality.h"

#include <vtkUnstructuredGrid.h>
#include <vtkUnsignedCharArray.h>
#include <vtkDataSetAttributes.h>

#include <algorithm>
#include <cstdint>
#include <optional>

namespace mlsvtk
{
namespace
{
using mlsdeform::Vec3;

// The CalculiX element of an ElementJacobian shape (both in VTK's node order).
mlsdeform::SolidElement solidElement(mlsdeform::ElementShape shape)
{
  using mlsdeform::ElementShape;
  using mlsdeform::SolidElement;
  switch (shape)
  {
    case ElementShape::Tetra4: return SolidElement::C3D4;
    case ElementShape::Tetra10: return SolidElement::C3D10;
    case ElementShape::Hexa8: return SolidElement::C3D8;
    case ElementShape::Hexa20: return SolidElement::C3D20;
    case ElementShape::Wedge6: return SolidElement::C3D6;
    case ElementShape::Wedge15: break;
  }
  return SolidElement::C3D15;
}
}

MeshVolume::MeshVolume(vtkUnstructuredGrid* grid, const mlsdeform::PointList& rest, const std::vector<char>& selected, bool fem, int offset)
{
  std::vector<vtkIdType> others; // the cells measured by their faces
  std::vector<int> nodes;
  vtkUnsignedCharArray* ghosts = grid->GetCellGhostArray(); // another process's cells: measured there
  for (vtkIdType c = 0; c < grid->GetNumberOfCells(); ++c)
  {
    const int type = grid->GetCellType(c);
    if ((!selected.empty() && !selected[static_cast<std::size_t>(c)]) || cellDimension(type) != 3 ||
      (ghosts && (ghosts->GetValue(c) & vtkDataSetAttributes::DUPLICATECELL)))
    {
      continue;
    }
    ++Cells;
    const std::optional<mlsdeform::ElementShape> shape = fem ? elementShape(type) : std::nullopt;
    if (!shape)
    {
      others.push_back(c);
      continue;
    }
    vtkIdType n = 0;
    const vtkIdType* ids = nullptr;
    grid->GetCellPoints(c, n, ids);
    nodes.assign(ids, ids + n);
    for (int& node : nodes)
    {
      node += offset;
    }
    Elements.add(solidElement(*shape), nodes.data(), 0);
  }
  if (others.empty())
  {
    return;
  }
  // the other cells' faces, each once: a face two of them share (the same points) bounds neither
  const mlsdeform::CellFaceList faces = cellFaces(grid); // indexed by cell id
  // a record a face: a hash of its points (their number, least, largest and sum: equal for equal
  // faces) and the face, 16 bytes for each of a 1M-cell mesh's 7M faces
  std::vector<std::pair<std::uint64_t, long>> records;
  for (const vtkIdType c : others)
  {
    for (long f = faces.firstFace(static_cast<int>(c)); f < faces.firstFace(static_cast<int>(c) + 1); ++f)
    {
      const int* p = faces.face(f);
      const std::size_t n = faces.faceSize(f);
      std::uint64_t sum = 0;
      for (std::size_t k = 0; k < n; ++k)
      {
        sum += static_cast<std::uint64_t>(p[k]);
      }
      const auto least = static_cast<std::uint64_t>(*std::min_element(p, p + n));
      const auto largest = static_cast<std::uint64_t>(*std::max_element(p, p + n));
      records.emplace_back(((sum * 1000003u + least) * 1000003u + largest) * 31u + n, f);
    }
  }
  std::sort(records.begin(), records.end());
  const auto samePoints = [&](long f, long g) { // (a face has a few points: no sorting, no allocation)
    return faces.faceSize(f) == faces.faceSize(g) && std::is_permutation(faces.face(f), faces.face(f) + faces.faceSize(f), faces.face(g));
  };
  std::vector<char> shared(records.size(), 0);
  for (std::size_t i = 0; i < records.size();)
  {
    std::size_t j = i + 1;
    while (j < records.size() && records[j].first == records[i].first)
    {
      ++j;
    }
    for (std::size_t a = i; a < j; ++a)
    {
      for (std::size_t b = a + 1; b < j && !shared[a]; ++b)
      {
        if (!shared[b] && samePoints(records[a].second, records[b].second))
        {
          shared[a] = shared[b] = 1;
        }
      }
    }
    i = j;
  }
  // the bounding faces in the cells' order (a face's cell: the one whose faces hold it)
  std::vector<std::pair<vtkIdType, long>> bounding;
  for (std::size_t r = 0; r < records.size(); ++r)
  {
    if (!shared[r])
    {
      const long f = records[r].second;
      const auto c = std::upper_bound(others.begin(), others.end(), f,
                       [&](long face, vtkIdType cell) { return face < faces.firstFace(static_cast<int>(cell)); }) - 1;
      bounding.emplace_back(*c, f);
    }
  }
  std::vector<std::pair<std::uint64_t, long>>().swap(records);
  std::sort(bounding.begin(), bounding.end());
  // each oriented out of its cell on the rest points: S_f . (C_f - C) > 0, C the cell's estimate
  // (its face centres' mean, as FaceQuality's)
  std::vector<long> faceStart{ 0 };
  std::vector<int> facePoints;
  vtkIdType cell = -1;
  Vec3 centre = Vec3::Zero();
  for (const auto& [c, f] : bounding)
  {
    if (c != cell)
    {
      cell = c;
      centre = Vec3::Zero();
      const long first = faces.firstFace(static_cast<int>(c)), last = faces.firstFace(static_cast<int>(c) + 1);
      for (long g = first; g < last; ++g)
      {
        centre += mlsdeform::faceGeometry(rest, faces.face(g), faces.faceSize(g)).centre;
      }
      centre /= static_cast<double>(std::max<long>(1, last - first));
    }
    const int* p = faces.face(f);
    const std::size_t n = faces.faceSize(f);
    const mlsdeform::FaceGeometry g = mlsdeform::faceGeometry(rest, p, n);
    const std::size_t start = facePoints.size();
    for (std::size_t k = 0; k < n; ++k)
    {
      facePoints.push_back(offset + p[k]);
    }
    if (g.area.dot(g.centre - centre) < 0)
    {
      std::reverse(facePoints.begin() + static_cast<long>(start), facePoints.end());
    }
    faceStart.push_back(static_cast<long>(facePoints.size()));
  }
  Faces = mlsdeform::PolygonSurface(faceStart, facePoints);
}

double MeshVolume::volume(const mlsdeform::PointList& points, std::vector<int>* rows, mlsdeform::PointList* gradient) const
{
  // V = sum_f S_f . C_f / 3 over the bounding faces
  mlsdeform::PointList faceGradient;
  const double faces = Faces.volume(points, Eigen::Matrix3d::Identity(), 1.0 / 3, rows ? &faceGradient : nullptr);
  if (!Elements.elements())
  {
    if (rows)
    {
      *rows = Faces.points();
      *gradient = std::move(faceGradient);
    }
    return faces;
  }
  mlsdeform::PointList dense; // the elements' gradient, at every point
  const double elements = mlsdeform::meshVolume(Elements, points, { 1.0 }, rows ? &dense : nullptr);
  if (rows)
  {
    for (std::size_t i = 0; i < faceGradient.size(); ++i)
    {
      dense[static_cast<std::size_t>(Faces.points()[i])] += faceGradient[i];
    }
    rows->clear();
    gradient->clear();
    for (std::size_t i = 0; i < dense.size(); ++i)
    {
      if (!dense[i].isZero(0))
      {
        rows->push_back(static_cast<int>(i));
        gradient->push_back(dense[i]);
      }
    }
  }
  return elements + faces;
}
} // namespace mlsvtk
