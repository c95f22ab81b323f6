#include "vtkPrimitiveDetector.h"

#include "Primitives/EfficientRansac.h"
#include "Primitives/FaceSamples.h"
#include "Adapters/AlgorithmProgress.h"
#include "Adapters/FailurePolicy.h"
#include "Adapters/ReportArrays.h"
#include "Common/BoundingBox.h"
#include "Vocabulary/FieldNames.h"

#include <vtkCellArray.h>
#include <vtkCellArrayIterator.h>
#include <vtkCellData.h>
#include <vtkDataSetSurfaceFilter.h>
#include <vtkDoubleArray.h>
#include <vtkErrorCode.h>
#include <vtkFieldData.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTable.h>

#include <cmath>
#include <limits>

vtkStandardNewMacro(vtkPrimitiveDetector);

namespace
{
using mlsdeform::DetectedPrimitive;
using mlsdeform::PrimitiveType;

constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

vtkSmartPointer<vtkIntArray> intArray(const char* name, vtkIdType tuples, int components, int value)
{
  auto array = vtkSmartPointer<vtkIntArray>::New();
  array->SetName(name);
  array->SetNumberOfComponents(components);
  array->SetNumberOfTuples(tuples);
  array->Fill(value);
  return array;
}

// One row per primitive: identity, support, fit and parameters (NaN where the type has none).
vtkSmartPointer<vtkTable> primitiveTable(const std::vector<DetectedPrimitive>& found, const std::vector<double>& area)
{
  const char* numeric[] = { "TypeCode", "Faces", "Area", "RMSDistance", "MaxDistance", "NormalX", "NormalY", "NormalZ", "Offset", "AxisX",
    "AxisY", "AxisZ", "CenterX", "CenterY", "CenterZ", "Radius", "ApexX", "ApexY", "ApexZ", "Angle" };
  auto table = vtkSmartPointer<vtkTable>::New();
  vtkNew<vtkIntArray> id;
  id->SetName("Id");
  vtkNew<vtkStringArray> type;
  type->SetName("Type");
  table->AddColumn(id);
  table->AddColumn(type);
  std::vector<vtkSmartPointer<vtkDoubleArray>> columns;
  for (const char* name : numeric)
  {
    columns.push_back(vtkSmartPointer<vtkDoubleArray>::New());
    columns.back()->SetName(name);
    table->AddColumn(columns.back());
  }
  for (std::size_t p = 0; p < found.size(); ++p)
  {
    const mlsdeform::Primitive& s = found[p].shape;
    double faceArea = 0;
    for (int f : found[p].members)
    {
      faceArea += area[f];
    }
    std::vector<double> row(columns.size(), NaN);
    row[0] = static_cast<double>(s.type);
    row[1] = static_cast<double>(found[p].members.size());
    row[2] = faceArea;
    row[3] = found[p].rmsDistance;
    row[4] = found[p].maxDistance;
    auto put = [&](int first, const mlsdeform::Vec3& v) {
      for (int d = 0; d < 3; ++d)
      {
        row[first + d] = v[d];
      }
    };
    switch (s.type)
    {
      case PrimitiveType::Plane:
        put(5, s.axis);
        row[8] = s.offset;
        break;
      case PrimitiveType::Cylinder:
        put(9, s.axis);
        [[fallthrough]];
      case PrimitiveType::Sphere:
        put(12, s.center);
        row[15] = s.radius;
        break;
      case PrimitiveType::Cone:
        put(9, s.axis);
        put(16, s.center);
        row[19] = s.angle * 180 / M_PI;
        break;
    }
    id->InsertNextValue(static_cast<int>(p));
    type->InsertNextValue(mlsdeform::primitiveTypeName(s.type));
    for (std::size_t c = 0; c < columns.size(); ++c)
    {
      columns[c]->InsertNextValue(row[c]);
    }
  }
  return table;
}
}

vtkPrimitiveDetector::vtkPrimitiveDetector()
{
  this->SetNumberOfOutputPorts(2);
  this->SetProgressText("Primitive Detector");
}

int vtkPrimitiveDetector::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataSet");
  return 1;
}

int vtkPrimitiveDetector::FillOutputPortInformation(int port, vtkInformation* info)
{
  info->Set(vtkDataObject::DATA_TYPE_NAME(), port == 0 ? "vtkPolyData" : "vtkTable");
  return 1;
}

namespace
{
// The surface to detect on: the input's polygons, or a volume's boundary faces.
void surfaceOf(vtkDataSet* input, vtkPolyData* output)
{
  if (auto* surface = vtkPolyData::SafeDownCast(input))
  {
    output->ShallowCopy(surface);
  }
  else
  {
    vtkNew<vtkDataSetSurfaceFilter> boundary;
    boundary->SetInputData(input);
    boundary->Update();
    output->ShallowCopy(boundary->GetOutput());
  }
  if (!output->GetPolys() || output->GetPolys()->GetNumberOfCells() == 0)
  {
    throw mlsdeform::InvalidInputException("the input has no faces (polygons): primitives are detected on face barycenters and "
                                           "face normals, so a point cloud or a line set cannot be used");
  }
}

// The surface's polygons as lists of point ids.
std::vector<std::vector<int>> polygonsOf(vtkPolyData* surface)
{
  std::vector<std::vector<int>> faces;
  faces.reserve(surface->GetPolys()->GetNumberOfCells());
  auto iterator = vtk::TakeSmartPointer(surface->GetPolys()->NewIterator());
  for (iterator->GoToFirstCell(); !iterator->IsDoneWithTraversal(); iterator->GoToNextCell())
  {
    vtkIdType size;
    const vtkIdType* ids;
    iterator->GetCurrentCell(size, ids);
    faces.emplace_back(ids, ids + size);
  }
  return faces;
}

// The primitives as cell arrays (faces -> cells: polygons come after vertices and lines), point
// arrays (a vertex belongs to every primitive of its faces) and the field data of their types.
void addPrimitiveArrays(vtkPolyData* output, const std::vector<DetectedPrimitive>& found, const std::vector<std::vector<int>>& faces,
  const mlsdeform::PointList& vertices)
{
  const vtkIdType firstPolygon = output->GetNumberOfVerts() + output->GetNumberOfLines();
  auto primitiveId = intArray(mlsvtk::fields::PrimitiveId, output->GetNumberOfCells(), 1, -1);
  auto primitiveType = intArray(mlsvtk::fields::PrimitiveType, output->GetNumberOfCells(), 1, -1);
  std::vector<std::vector<int>> membership(vertices.size());
  auto types = intArray(mlsvtk::fields::PrimitiveTypes, static_cast<vtkIdType>(found.size()), 1, 0);
  for (std::size_t p = 0; p < found.size(); ++p)
  {
    types->SetValue(static_cast<vtkIdType>(p), static_cast<int>(found[p].shape.type));
    for (int f : found[p].members)
    {
      primitiveId->SetValue(firstPolygon + f, static_cast<int>(p));
      primitiveType->SetValue(firstPolygon + f, static_cast<int>(found[p].shape.type));
      for (int v : faces[f])
      {
        if (membership[v].empty() || membership[v].back() != static_cast<int>(p))
        {
          membership[v].push_back(static_cast<int>(p));
        }
      }
    }
  }
  std::size_t most = 1;
  for (auto& ids : membership)
  {
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    most = std::max(most, ids.size());
  }
  auto count = intArray(mlsvtk::fields::PrimitiveCount, static_cast<vtkIdType>(vertices.size()), 1, 0);
  auto ids = intArray(mlsvtk::fields::PrimitiveIds, static_cast<vtkIdType>(vertices.size()), static_cast<int>(most), -1);
  for (std::size_t v = 0; v < vertices.size(); ++v)
  {
    count->SetValue(static_cast<vtkIdType>(v), static_cast<int>(membership[v].size()));
    for (std::size_t a = 0; a < membership[v].size(); ++a)
    {
      ids->SetTypedComponent(static_cast<vtkIdType>(v), static_cast<int>(a), membership[v][a]);
    }
  }
  output->GetCellData()->AddArray(primitiveId);
  output->GetCellData()->AddArray(primitiveType);
  output->GetPointData()->AddArray(count);
  output->GetPointData()->AddArray(ids);
  output->GetFieldData()->AddArray(types);
}

// The detector's properties as RANSAC's parameters for a surface of that diagonal.
mlsdeform::RansacParameters ransacParameters(vtkPrimitiveDetector* detector, double diagonal)
{
  mlsdeform::RansacParameters p;
  p.planes = detector->GetDetectPlanes();
  p.cylinders = detector->GetDetectCylinders();
  p.spheres = detector->GetDetectSpheres();
  p.cones = detector->GetDetectCones();
  p.epsilon = detector->GetEpsilon() * diagonal;
  p.clusterEpsilon = detector->GetClusterEpsilon() * diagonal;
  p.normalThreshold = detector->GetNormalThreshold() * M_PI / 180;
  p.minimumSupport = detector->GetMinimumSupport();
  p.probability = detector->GetProbability();
  p.seed = static_cast<std::uint64_t>(detector->GetRandomSeed());
  return p;
}
}

int vtkPrimitiveDetector::RequestData(vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  const mlsvtk::ReportArrays reports(inputVector[0], outputVector); // its field data: reports, not fields
  vtkDataSet* input = vtkDataSet::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkTable* table = vtkTable::GetData(outputVector, 1);
  this->SetErrorCode(vtkErrorCode::NoError);
  try
  {
    surfaceOf(input, output);
    mlsdeform::SampleFaces mesh{ polygonsOf(output), mlsdeform::PointList(output->GetNumberOfPoints()) };
    mlsdeform::PointList& vertices = mesh.vertices;
    for (vtkIdType i = 0; i < output->GetNumberOfPoints(); ++i)
    {
      output->GetPoint(i, vertices[i].data());
    }
    mlsdeform::requireFinite(vertices, "surface points");
    const mlsdeform::FaceSamples samples = mlsdeform::faceSamples(vertices, mesh.faces); // one oriented sample per polygon (Fig. 7)
    const double diagonal = mlsdeform::boundingBox(vertices).size().norm();
    if (!(diagonal > 0))
    {
      throw mlsdeform::InvalidInputException("the surface has zero extent");
    }
    const std::vector<DetectedPrimitive> found =
      mlsdeform::detectPrimitives(samples.barycenters, samples.normals, ransacParameters(this, diagonal), &mesh, mlsvtk::progressOf(this));
    mlsvtk::checkAbort(this);
    addPrimitiveArrays(output, found, mesh.faces, vertices);
    table->ShallowCopy(primitiveTable(found, samples.areas));
  }
  catch (const std::exception& e)
  {
    output->Initialize();
    table->Initialize();
    this->SetErrorCode(vtkErrorCode::UserError);
    return mlsvtk::reportFailure(this, outputVector, e, "The outputs are empty.");
  }
  return 1;
}


void vtkPrimitiveDetector::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "DetectPlanes: " << this->DetectPlanes << "\n"
     << indent << "DetectCylinders: " << this->DetectCylinders << "\n"
     << indent << "DetectSpheres: " << this->DetectSpheres << "\n"
     << indent << "DetectCones: " << this->DetectCones << "\n"
     << indent << "Epsilon: " << this->Epsilon << "\n"
     << indent << "ClusterEpsilon: " << this->ClusterEpsilon << "\n"
     << indent << "NormalThreshold: " << this->NormalThreshold << "\n"
     << indent << "MinimumSupport: " << this->MinimumSupport << "\n"
     << indent << "Probability: " << this->Probability << "\n"
     << indent << "RandomSeed: " << this->RandomSeed << "\n";
}
