#include "vtkConstraintRegion.h"

#include "MLSGeometry.h"

#include <vtkDataArray.h>
#include <vtkDataObject.h>
#include <vtkDataSetAttributes.h>
#include <vtkDoubleArray.h>
#include <vtkFieldData.h>
#include <vtkImplicitFunction.h>
#include <vtkInformation.h>
#include <vtkInformationVector.h>
#include <vtkIntArray.h>
#include <vtkMath.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkObjectFactory.h>
#include <vtkPointData.h>
#include <vtkPointSet.h>
#include <vtkPolyData.h>
#include <vtkStringArray.h>
#include <vtkTransform.h>


vtkStandardNewMacro(vtkConstraintRegion);

namespace
{
// The points of the sets inside the function (mode ImplicitFunction), with values[s] within range
// (mode ArrayRange) or with primitive among the components of values[s] (mode Primitive; sets
// without the array contribute nothing), or all (mode AllPoints).
mlsdeform::PointList selectPositions(const std::vector<vtkPointSet*>& sets, const std::vector<vtkDataArray*>& values, int mode,
  vtkImplicitFunction* function, bool insideOut, const double range[2], int primitive)
{
  mlsdeform::PointList selected;
  for (std::size_t s = 0; s < sets.size(); ++s)
  {
    if ((mode == vtkConstraintRegion::ArrayRange || mode == vtkConstraintRegion::Primitive) && !values[s])
    {
      continue;
    }
    for (vtkIdType i = 0; i < sets[s]->GetNumberOfPoints(); ++i)
    {
      mlsdeform::Vec3 x;
      sets[s]->GetPoint(i, x.data());
      bool take = true;
      if (mode == vtkConstraintRegion::ImplicitFunction)
      {
        take = (function->FunctionValue(x.data()) <= 0) != insideOut;
      }
      else if (mode == vtkConstraintRegion::ArrayRange)
      {
        const double v = values[s]->GetComponent(i, 0);
        take = v >= range[0] && v <= range[1];
      }
      else if (mode == vtkConstraintRegion::Primitive)
      {
        take = false;
        for (int c = 0; c < values[s]->GetNumberOfComponents(); ++c)
        {
          take = take || values[s]->GetComponent(i, c) == primitive;
        }
      }
      if (take)
      {
        selected.push_back(x);
      }
    }
  }
  return selected;
}

// The role that keeps a primitive of that type (vtkPrimitiveDetector's codes), -1 for none.
int roleOfPrimitive(int type)
{
  switch (type)
  {
    case 0:
      return vtkConstraintRegion::Planarity;
    case 1:
      return vtkConstraintRegion::Cylinder;
    case 2:
    case 3:
      return vtkConstraintRegion::FeatureLine; // similarity: spheres stay spheres, cones keep their angle
    default:
      return -1;
  }
}
}
vtkCxxSetObjectMacro(vtkConstraintRegion, Region, vtkImplicitFunction);

// What a selection depends on: the selection properties (exact values) and the stamps of the
// input points, the selection arrays and the region function.
struct SelectionInputs
{
  int mode = -1;
  bool insideOut = false;
  double range[2] = { 0, 0 };
  int primitive = -1;
  mlsgeometry::Stamp stamp;
  bool operator==(const SelectionInputs& o) const
  {
    return mode == o.mode && insideOut == o.insideOut && range[0] == o.range[0] && range[1] == o.range[1] &&
      primitive == o.primitive && stamp == o.stamp;
  }
};

// The selected positions, what they were selected with, and the output arrays kept from update
// to update: while only the motion or the weight changes, the output shares the same point
// cloud (so a deformation downstream knows by its stamp that the positions did not change)
// and its displacement array is written again when no one else holds it.
struct vtkConstraintRegion::Selection
{
  SelectionInputs inputs;
  bool valid = false;
  mlsdeform::PointList positions;
  vtkSmartPointer<vtkPolyData> cloud;
  vtkSmartPointer<vtkDoubleArray> displacement;
};

vtkConstraintRegion::vtkConstraintRegion()
  : Selected(new Selection)
{
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, vtkDataSetAttributes::SCALARS);
}

vtkConstraintRegion::~vtkConstraintRegion()
{
  this->SetRegion(nullptr);
  delete this->Selected;
}

const char* vtkConstraintRegion::GetRoleName(int role)
{
  static const char* names[] = { "Handle", "Fixed", "Planarity", "Circularity", "Cylinder", "FeatureLine", "Rigid", "FromPrimitive", "Slip" };
  return role >= Handle && role <= Slip ? names[role] : "Unknown";
}

void vtkConstraintRegion::SetSelectionArray(const char* name)
{
  this->SetInputArrayToProcess(0, 0, 0, vtkDataObject::FIELD_ASSOCIATION_POINTS, name);
}

vtkMTimeType vtkConstraintRegion::GetMTime()
{
  vtkMTimeType time = this->Superclass::GetMTime();
  if (this->Region)
  {
    time = std::max(time, this->Region->GetMTime());
  }
  return time;
}

int vtkConstraintRegion::FillInputPortInformation(int, vtkInformation* info)
{
  info->Set(vtkAlgorithm::INPUT_REQUIRED_DATA_TYPE(), "vtkDataObject");
  return 1;
}

int vtkConstraintRegion::RequestData(vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkDataObject* input = vtkDataObject::GetData(inputVector[0], 0);
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  const std::vector<vtkPointSet*> sets = mlsgeometry::pointSets(input);
  if (this->SelectionMode == ImplicitFunction && !this->Region)
  {
    vtkErrorMacro(<< "SelectionMode is ImplicitFunction but no Region function is set.");
    return 0;
  }

  if (this->Role == FromPrimitive && this->SelectionMode != Primitive)
  {
    vtkErrorMacro(<< "Role FromPrimitive needs SelectionMode Primitive (a Primitive Detector's output as input).");
    return 0;
  }
  int role = this->Role;
  std::vector<vtkDataArray*> values;
  for (vtkPointSet* set : sets)
  {
    values.push_back(this->SelectionMode == ArrayRange ? this->GetInputArrayToProcess(0, set)
        : this->SelectionMode == Primitive           ? set->GetPointData()->GetArray("PrimitiveIds")
                                                     : nullptr);
  }
  if (this->SelectionMode == Primitive)
  {
    // the primitive must exist in the detector's output; its type gives the FromPrimitive role
    vtkDataArray* types = nullptr;
    for (vtkPointSet* set : sets)
    {
      types = types ? types : set->GetFieldData()->GetArray("PrimitiveTypes");
    }
    if (!types)
    {
      vtkErrorMacro(<< "SelectionMode Primitive needs a Primitive Detector's output as input (field data PrimitiveTypes and "
                       "point array PrimitiveIds are missing).");
      return 0;
    }
    if (this->PrimitiveId >= types->GetNumberOfTuples())
    {
      vtkErrorMacro(<< "There is no primitive " << this->PrimitiveId << ": the detector found " << types->GetNumberOfTuples()
                    << " (ids 0 to " << types->GetNumberOfTuples() - 1 << ").");
      return 0;
    }
    if (this->Role == FromPrimitive)
    {
      role = roleOfPrimitive(static_cast<int>(types->GetComponent(this->PrimitiveId, 0)));
      if (role < 0)
      {
        vtkErrorMacro(<< "Primitive " << this->PrimitiveId << " has an unknown type.");
        return 0;
      }
    }
  }
  // Select positions, unless only the motion or the weight changed since the last selection.
  SelectionInputs inputs;
  inputs.mode = this->SelectionMode;
  inputs.insideOut = this->InsideOut;
  inputs.range[0] = this->Range[0];
  inputs.range[1] = this->Range[1];
  inputs.primitive = this->PrimitiveId;
  inputs.stamp = mlsgeometry::pointsStamp(sets);
  inputs.stamp.add(this->Region);
  for (vtkDataArray* array : values)
  {
    inputs.stamp.add(array);
  }
  Selection& selection = *this->Selected;
  if (!selection.valid || !(inputs == selection.inputs))
  {
    selection.valid = false;
    selection.positions =
      selectPositions(sets, values, this->SelectionMode, this->Region, this->InsideOut, this->Range, this->PrimitiveId);
    selection.cloud = mlsgeometry::pointCloud(selection.positions, {});
    selection.inputs = std::move(inputs);
    selection.valid = true;
    ++this->NumberOfSelections;
  }
  const mlsdeform::PointList& selected = selection.positions;
  if (selected.empty() && input->GetNumberOfElements(vtkDataObject::POINT) > 0)
  {
    vtkWarningMacro(<< GetRoleName(role) << " region selects no point.");
  }

  // Prescribed displacement of a handle: scale, rotate, translate about the pivot.
  mlsdeform::Vec3 pivot(this->Center);
  if (this->UseCentroid && !selected.empty())
  {
    pivot.setZero();
    for (const auto& x : selected)
    {
      pivot += x / static_cast<double>(selected.size());
    }
  }
  vtkNew<vtkTransform> motion;
  motion->PostMultiply();
  motion->Translate(-pivot.x(), -pivot.y(), -pivot.z());
  motion->Scale(this->Scale);
  motion->RotateX(this->Rotation[0]);
  motion->RotateY(this->Rotation[1]);
  motion->RotateZ(this->Rotation[2]);
  motion->Translate(pivot.x() + this->Translation[0], pivot.y() + this->Translation[1], pivot.z() + this->Translation[2]);
  double matrix[16];
  vtkMatrix4x4::DeepCopy(matrix, motion->GetMatrix());

  output->ShallowCopy(selection.cloud);
  if (!selection.displacement || selection.displacement->GetReferenceCount() > 1)
  {
    selection.displacement = vtkSmartPointer<vtkDoubleArray>::New(); // the last one is still in use downstream
  }
  vtkDoubleArray* displacement = selection.displacement;
  displacement->SetName("PrescribedDisplacement");
  displacement->SetNumberOfComponents(3);
  displacement->SetNumberOfTuples(static_cast<vtkIdType>(selected.size()));
  double* d = displacement->GetPointer(0);
  const bool moves = role == Handle;
  for (std::size_t i = 0; i < selected.size(); ++i)
  {
    const mlsdeform::Vec3& x = selected[i];
    for (int c = 0; c < 3; ++c)
    {
      // (M x + t) - x for the handle; zero for the other roles
      d[3 * i + c] = moves ? matrix[4 * c] * x[0] + matrix[4 * c + 1] * x[1] + matrix[4 * c + 2] * x[2] + matrix[4 * c + 3] - x[c] : 0.0;
    }
  }
  displacement->Modified();
  output->GetPointData()->AddArray(displacement);

  vtkNew<vtkIntArray> roleArray;
  roleArray->SetName("Role");
  roleArray->InsertNextValue(role);
  vtkNew<vtkStringArray> roleName;
  roleName->SetName("RoleName");
  roleName->InsertNextValue(GetRoleName(role));
  vtkNew<vtkDoubleArray> weight;
  weight->SetName("Weight");
  weight->InsertNextValue(this->Weight);
  output->GetFieldData()->AddArray(roleArray);
  output->GetFieldData()->AddArray(roleName);
  output->GetFieldData()->AddArray(weight);
  return 1;
}

void vtkConstraintRegion::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Role: " << GetRoleName(this->Role) << "\n"
     << indent << "SelectionMode: " << this->SelectionMode << "\n"
     << indent << "Region: " << this->Region << "\n"
     << indent << "InsideOut: " << this->InsideOut << "\n"
     << indent << "Range: " << this->Range[0] << " " << this->Range[1] << "\n"
     << indent << "PrimitiveId: " << this->PrimitiveId << "\n"
     << indent << "Translation: " << this->Translation[0] << " " << this->Translation[1] << " " << this->Translation[2] << "\n"
     << indent << "Rotation: " << this->Rotation[0] << " " << this->Rotation[1] << " " << this->Rotation[2] << "\n"
     << indent << "Scale: " << this->Scale[0] << " " << this->Scale[1] << " " << this->Scale[2] << "\n"
     << indent << "Center: " << this->Center[0] << " " << this->Center[1] << " " << this->Center[2] << "\n"
     << indent << "UseCentroid: " << this->UseCentroid << "\n"
     << indent << "Weight: " << this->Weight << "\n";
}
