#include "vtkHandleBoxRepresentation.h"

#include <vtkActor.h>
#include <vtkAssemblyPath.h>
#include <vtkCellPicker.h>
#include <vtkRenderer.h>
#include <vtkObjectFactory.h>
#include <vtkProperty.h>
#include <vtkSphereSource.h>

vtkStandardNewMacro(vtkHandleBoxRepresentation);

namespace
{
// vtkBoxRepresentation's handles: the six face spheres, then the centre one.
constexpr int Centre = 6;
}

vtkHandleBoxRepresentation::vtkHandleBoxRepresentation()
  : CentreProperty(vtkProperty::New())
{
  this->CentreProperty->DeepCopy(this->HandleProperty);
  this->Handle[Centre]->SetProperty(this->CentreProperty);
}

vtkHandleBoxRepresentation::~vtkHandleBoxRepresentation()
{
  this->CentreProperty->Delete();
}

void vtkHandleBoxRepresentation::BuildRepresentation()
{
  this->Superclass::BuildRepresentation();
  // the base class gives an unhighlighted handle the face handles' property
  if (this->CurrentHandle != this->Handle[Centre])
  {
    this->Handle[Centre]->SetProperty(this->CentreProperty);
  }
}

int vtkHandleBoxRepresentation::ComputeInteractionState(int X, int Y, int modify)
{
  if (this->Renderer && this->Renderer->IsInViewport(X, Y) && this->Handle[Centre]->GetVisibility())
  {
    // the centre sphere alone first (the handle picker's list narrowed to it, then restored), so
    // that the pick position the drag moves from is on it
    this->HandlePicker->InitializePickList();
    this->HandlePicker->AddPickList(this->Handle[Centre]);
    const bool centre = this->HandlePicker->Pick(X, Y, 0.0, this->Renderer) && this->HandlePicker->GetPath();
    this->HandlePicker->InitializePickList();
    for (int i = 0; i <= Centre; ++i)
    {
      if (!this->TwoPlaneMode || i < 2 || i == Centre) // (the base class's list)
      {
        this->HandlePicker->AddPickList(this->Handle[i]);
      }
    }
    if (centre)
    {
      this->ValidPick = 1;
      this->LastPicker = this->HandlePicker;
      this->CurrentHandle = this->Handle[Centre];
      this->InteractionState = vtkBoxRepresentation::Translating;
      return this->InteractionState;
    }
  }
  return this->Superclass::ComputeInteractionState(X, Y, modify);
}

void vtkHandleBoxRepresentation::SizeHandles()
{
  this->Superclass::SizeHandles();
  this->HandleGeometry[Centre]->SetRadius(this->CentreScale * this->HandleGeometry[0]->GetRadius());
}

void vtkHandleBoxRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CentreScale: " << this->CentreScale << "\n";
}
