#include "vtkDeformationQuality.h"

#include "Quality/FaceQuality.h"
#include "Adapters/AlgorithmProgress.h"
#include "Adapters/FailurePolicy.h"
#include "Adapters/ProcessCollective.h"
#include "Adapters/VolumeMeshQuality.h"
#include "Adapters/ReportArrays.h"
#include "Sampling/Sampling.h"

#include <vtkCell.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkFieldData.h>
#include <vtkIdList.h>
#include <vtkIdTypeArray.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkUnstructuredGrid.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <exception>
#include <limits>
#include <optional>
#include <string>

vtkStandardNewMacro(vtkDeformationQuality);

namespace
{
using mlsdeform::CellFaceList;
using mlsdeform::FaceMeasures;
using mlsdeform::InteriorFace;
using mlsdeform::InteriorFaces;
using mlsdeform::PointList;

constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

/// The original must have the deformed mesh's cells: same counts, types and point ids.
void requireSameCells(vtkUnstructuredGrid* deformed, vtkUnstructuredGrid* original)
{
  if (original->GetNumberOfPoints() != deformed->GetNumberOfPoints() ||
    original->GetNumberOfCells() != deformed->GetNumberOfCells())
  {
    throw mlsdeform::InvalidInputException("the original mesh has " + std::to_string(original->GetNumberOfPoints()) +
      " points and " + std::to_string(original->GetNumberOfCells()) + " cells, the input " +
      std::to_string(deformed->GetNumberOfPoints()) + " and " + std::to_string(deformed->GetNumberOfCells()) +
      ": they must be the same mesh before and after deformation");
  }
  vtkNew<vtkIdList> a, b;
  for (vtkIdType c = 0; c < deformed->GetNumberOfCells(); ++c)
  {
    deformed->GetCellPoints(c, a);
    original->GetCellPoints(c, b);
    bool same = deformed->GetCellType(c) == original->GetCellType(c) && a->GetNumberOfIds() == b->GetNumberOfIds();
    for (vtkIdType i = 0; same && i < a->GetNumberOfIds(); ++i)
    {
      same = a->GetId(i) == b->GetId(i);
    }
    if (!same)
    {
      throw mlsdeform::InvalidInputException("cell " + std::to_string(c) +
        " differs between the original and the input: they must be the same mesh before and after deformation");
    }
  }
}

/// All measures of one mesh.
struct Measures
{
  std::vector<double> scaledJacobian;
  FaceMeasures faces;
  std::vector<double> maxNonOrthogonality; // per cell, over its interior faces
  std::vector<double> maxSkewness;         // per cell, over its interior and boundary faces
  std::vector<double> skewness;            // per interior face, then per boundary face
  long inverted = 0;
};

Measures measure(vtkUnstructuredGrid* grid, const PointList& points, const mlsdeform::MeshFaces& mesh, const std::vector<int>& orientation)
{
  const CellFaceList& cells = mesh.cells;
  const InteriorFaces& faces = mesh.interior;
  Measures m;
  m.scaledJacobian = mlsvtk::scaledJacobians(grid);
  m.faces = mlsdeform::faceMeasures(points, mesh, orientation);
  // the faces' inverted cells and the quadratic elements folded between their corners
  std::vector<unsigned char> inverted = m.faces.inverted;
  mlsvtk::Elements(grid, mlsvtk::ElementSet::Quadratic).measure(points, inverted);
  m.inverted = static_cast<long>(std::count(inverted.begin(), inverted.end(), 1));
  m.maxNonOrthogonality.assign(cells.cells(), 0);
  m.maxSkewness.assign(cells.cells(), 0);
  for (std::size_t i = 0; i < faces.size(); ++i)
  {
    for (int c : { faces[i].owner, faces[i].neighbour })
    {
      m.maxNonOrthogonality[c] = std::max(m.maxNonOrthogonality[c], m.faces.nonOrthogonality[i]);
      m.maxSkewness[c] = std::max(m.maxSkewness[c], m.faces.skewness[i]);
    }
  }
  for (std::size_t b = 0; b < mesh.boundary.size(); ++b)
  {
    const int c = mesh.boundary[b].owner;
    m.maxSkewness[c] = std::max(m.maxSkewness[c], m.faces.boundarySkewness[b]);
  }
  m.skewness = m.faces.skewness;
  m.skewness.insert(m.skewness.end(), m.faces.boundarySkewness.begin(), m.faces.boundarySkewness.end());
  return m;
}

void addArray(vtkDataSetAttributes* data, const std::string& name, const std::vector<double>& values)
{
  vtkNew<vtkDoubleArray> array;
  array->SetName(name.c_str());
  array->SetNumberOfValues(static_cast<vtkIdType>(values.size()));
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    array->SetValue(static_cast<vtkIdType>(i), values[i]);
  }
  data->AddArray(array);
}

void addMeasures(vtkUnstructuredGrid* grid, vtkPolyData* faces, const Measures& m, const std::string& prefix)
{
  addArray(grid->GetCellData(), prefix + "ScaledJacobian", m.scaledJacobian);
  addArray(grid->GetCellData(), prefix + "MaxNonOrthogonality", m.maxNonOrthogonality);
  addArray(grid->GetCellData(), prefix + "MaxSkewness", m.maxSkewness);
  vtkNew<vtkIdTypeArray> inverted;
  inverted->SetName((prefix + "InvertedCells").c_str());
  inverted->InsertNextValue(m.inverted);
  grid->GetFieldData()->AddArray(inverted);
  addArray(faces->GetCellData(), prefix + "NonOrthogonality", m.faces.nonOrthogonality);
  addArray(faces->GetCellData(), prefix + "Skewness", m.faces.skewness);
}

/// Min, mean and max of the finite values (NaN when there are none).
std::array<double, 3> summarize(const std::vector<double>& values)
{
  double lo = std::numeric_limits<double>::infinity(), hi = -lo, sum = 0;
  std::size_t n = 0;
  for (double v : values)
  {
    if (std::isfinite(v))
    {
      lo = std::min(lo, v);
      hi = std::max(hi, v);
      sum += v;
      ++n;
    }
  }
  return n ? std::array<double, 3>{ lo, sum / n, hi } : std::array<double, 3>{ NaN, NaN, NaN };
}

void addSummaryColumns(vtkTable* table, const Measures& m, const std::string& prefix)
{
  const double inverted = m.inverted;
  const std::array<std::array<double, 3>, 4> rows = { summarize(m.scaledJacobian),
    summarize(m.faces.nonOrthogonality), summarize(m.skewness),
    std::array<double, 3>{ inverted, inverted, inverted } };
  const char* statistics[3] = { "Min", "Mean", "Max" };
  for (int s = 0; s < 3; ++s)
  {
    vtkNew<vtkDoubleArray> column;
    column->SetName((prefix + statistics[s]).c_str());
    for (const auto& row : rows)
    {
      column->InsertNextValue(row[s]);
    }
    table->AddColumn(column);
  }
}
}

vtkDeformationQuality::vtkDeformationQuality()
{
  this->SetNumberOfInputPorts(2);
  this->SetNumberOfOutputPorts(3);
  this->SetProgressText("Deformation Quality");
}

int vtkDeformationQuality::FillInputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkUnstructuredGrid");
  if (port == 1)
  {
    info->Set(vtkAlgorithm::INPUT_IS_OPTIONAL(), 1);
  }
  return 1;
}

int vtkDeformationQuality::FillOutputPortInformation(int port, vtkInformation* info)
{
  const char* types[3] = { "vtkUnstructuredGrid", "vtkPolyData", "vtkTable" };
  info->Set(vtkDataObject::DATA_TYPE_NAME(), types[port]);
  return 1;
}

namespace
{
// The interior faces as polygons on the mesh's points, with their owner and neighbour cells.
void writeFaces(vtkPolyData* faceOutput, vtkPoints* points, const mlsvtk::VolumeMeshQuality& topology)
{
  const CellFaceList& cells = topology.mesh().cells;
  vtkNew<vtkCellArray> polygons;
  vtkNew<vtkIdTypeArray> owners, neighbours;
  owners->SetName("Owner");
  neighbours->SetName("Neighbour");
  for (const InteriorFace& f : topology.mesh().interior)
  {
    polygons->InsertNextCell(static_cast<vtkIdType>(cells.faceSize(f.face)));
    for (std::size_t i = 0; i < cells.faceSize(f.face); ++i)
    {
      polygons->InsertCellPoint(cells.face(f.face)[i]);
    }
    owners->InsertNextValue(f.owner);
    neighbours->InsertNextValue(f.neighbour);
  }
  faceOutput->SetPoints(points);
  faceOutput->SetPolys(polygons);
  faceOutput->GetCellData()->AddArray(owners);
  faceOutput->GetCellData()->AddArray(neighbours);
}

// The summary table's first column: the measures' names.
void addMeasureNames(vtkTable* summary)
{
  vtkNew<vtkStringArray> names;
  names->SetName("Measure");
  for (const char* name : { "ScaledJacobian", "NonOrthogonality", "Skewness", "InvertedCells" })
  {
    names->InsertNextValue(name);
  }
  summary->AddColumn(names);
}
}

int vtkDeformationQuality::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const mlsvtk::ReportArrays reports(inputVector[0], outputVector); // its field data: reports, not fields
  vtkUnstructuredGrid* input = vtkUnstructuredGrid::GetData(inputVector[0]);
  vtkUnstructuredGrid* original = vtkUnstructuredGrid::GetData(inputVector[1]);
  vtkUnstructuredGrid* output = vtkUnstructuredGrid::GetData(outputVector, 0);
  vtkPolyData* faceOutput = vtkPolyData::GetData(outputVector, 1);
  vtkTable* summary = vtkTable::GetData(outputVector, 2);
  output->ShallowCopy(input);
  this->SetErrorCode(vtkErrorCode::NoError);
  PointList points, originalPoints;
  std::optional<mlsvtk::VolumeMeshQuality> faces;
  std::exception_ptr failure;
  try
  {
    if (input->GetNumberOfCells() == 0)
    {
      throw mlsdeform::InvalidInputException("the input has no cells");
    }
    points = mlsvtk::gridPoints(input, "the input mesh's points");
    if (original)
    {
      requireSameCells(input, original);
      originalPoints = mlsvtk::gridPoints(original, "the original mesh's points");
    }
    this->UpdateProgress(0.1);
    // OpenFOAM's face order: out of the owner in the undeformed mesh
    faces.emplace(original ? original : input);
  }
  catch (...)
  {
    failure = std::current_exception();
  }
  // The faces where this grid's pieces (unmerged points) or the processes' pieces touch are on
  // no boundary: left out (this filter has no other piece's cell centres to measure them with).
  // Every process takes part, also one whose input failed.
  std::vector<std::int64_t> keys;
  if (faces)
  {
    for (std::uint64_t key : faces->boundaryKeys())
    {
      keys.push_back(static_cast<std::int64_t>(key));
    }
  }
  const std::vector<std::int64_t> every = mlsvtk::ProcessCollective().gather(keys);
  try
  {
    if (failure)
    {
      std::rethrow_exception(failure);
    }
    mlsvtk::VolumeMeshQuality& topology = *faces;
    topology.leaveOutBoundaryFaces(mlsdeform::repeatedKeys(std::vector<std::uint64_t>(every.begin(), every.end())));
    this->UpdateProgress(0.4);
    mlsvtk::checkAbort(this);
    writeFaces(faceOutput, input->GetPoints(), topology);
    addMeasureNames(summary);
    const Measures after = measure(input, points, topology.mesh(), topology.orientation());
    addMeasures(output, faceOutput, after, "");
    addSummaryColumns(summary, after, "");
    this->UpdateProgress(0.7);
    mlsvtk::checkAbort(this);
    if (original)
    {
      const Measures before = measure(original, originalPoints, topology.mesh(), topology.orientation());
      addMeasures(output, faceOutput, before, "Original");
      addSummaryColumns(summary, before, "Original");
    }
  }
  catch (const std::exception& e)
  {
    output->ShallowCopy(input);
    faceOutput->Initialize();
    summary->Initialize();
    this->SetErrorCode(vtkErrorCode::UserError);
    return mlsvtk::reportFailure(this, outputVector, e, "The mesh output is the unchanged input, the faces and summary are empty.");
  }
  return 1;
}
