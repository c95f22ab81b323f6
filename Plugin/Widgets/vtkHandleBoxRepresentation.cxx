#include "vtkHandleBoxRepresentation.h"

#include <vtkActor.h>
#include <vtkAssemblyPath.h>
#include <vtkCamera.h>
#include <vtkCellPicker.h>
#include <vtkMath.h>
#include <vtkObjectFactory.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderer.h>
#include <vtkSphereSource.h>

vtkStandardNewMacro(vtkHandleBoxRepresentation);

namespace
{
// vtkBoxRepresentation's handles: the six face spheres, then the centre one.
constexpr int Centre = 6;
// The halo's width in pixels: beside each line of the box, and around each sphere.
constexpr double HaloPixels = 1.5;

// A line halo: the box's lines (of `lines`) drawn in the halo's look, pushed behind the lines
// themselves (a coincident-topology offset), so that only its margin shows.
vtkActor* lineHalo(vtkPolyData* lines, vtkProperty* look)
{
  auto* mapper = vtkPolyDataMapper::New();
  mapper->SetInputData(lines);
  mapper->SetRelativeCoincidentTopologyLineOffsetParameters(0.0, 4.0);
  mapper->SetRelativeCoincidentTopologyPolygonOffsetParameters(0.0, 4.0);
  auto* halo = vtkActor::New();
  halo->SetMapper(mapper);
  halo->SetProperty(look);
  halo->PickableOff();
  mapper->Delete();
  return halo;
}
}

vtkHandleBoxRepresentation::vtkHandleBoxRepresentation()
  : CentreProperty(vtkProperty::New())
  , HaloProperty(vtkProperty::New())
{
  this->CentreProperty->DeepCopy(this->HandleProperty);
  this->Handle[Centre]->SetProperty(this->CentreProperty);

  this->HaloProperty->SetColor(0.0, 0.0, 0.0);
  this->HaloProperty->SetRepresentationToWireframe();
  this->HaloProperty->LightingOff();
  this->HaloProperty->SetLineWidth(this->OutlineProperty->GetLineWidth() + 2 * HaloPixels);
  // the edges only: the centre lines, seen end-on along an axis, would put a dark dot on the
  // centre sphere
  this->EdgeHalo = lineHalo(this->HexPolyData, this->HaloProperty);
  // a sphere's halo: the sphere itself, enlarged about its centre (PositionHandles, SizeHandles),
  // its front faces culled, so that its back shows as a ring around the sphere
  for (int i = 0; i <= Centre; ++i)
  {
    this->SphereHalo[i] = vtkActor::New();
    this->SphereHalo[i]->SetMapper(this->HandleMapper[i]);
    this->SphereHalo[i]->GetProperty()->LightingOff();
    this->SphereHalo[i]->GetProperty()->FrontfaceCullingOn();
    this->SphereHalo[i]->PickableOff();
  }
}

vtkHandleBoxRepresentation::~vtkHandleBoxRepresentation()
{
  this->CentreProperty->Delete();
  this->HaloProperty->Delete();
  this->EdgeHalo->Delete();
  for (vtkActor* halo : this->SphereHalo)
  {
    halo->Delete();
  }
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
  // the ring: HaloPixels wide at the box's centre (SizeHandlesInPixels gives factor x HandleSize pixels)
  double* centre = this->HandleGeometry[Centre]->GetCenter();
  const double ring = this->SizeHandlesInPixels(HaloPixels / this->HandleSize, centre);
  for (int i = 0; i <= Centre; ++i)
  {
    const double radius = this->HandleGeometry[i]->GetRadius();
    const double scale = radius > 0 ? (radius + ring) / radius : 1.0;
    this->SphereHalo[i]->SetScale(scale, scale, scale);
  }
}

void vtkHandleBoxRepresentation::PositionHandles()
{
  this->Superclass::PositionHandles();
  for (int i = 0; i <= Centre; ++i)
  {
    this->SphereHalo[i]->SetOrigin(this->HandleGeometry[i]->GetCenter()); // enlarged about it
  }
}

void vtkHandleBoxRepresentation::HideFaceSpheresOverCentre()
{
  vtkCamera* camera = this->Renderer ? this->Renderer->GetActiveCamera() : nullptr;
  const bool handlesShown = this->Handle[Centre]->GetVisibility();
  const double* centre = this->HandleGeometry[Centre]->GetCenter();
  double view[3];
  if (camera && camera->GetParallelProjection())
  {
    camera->GetDirectionOfProjection(view);
  }
  else if (camera)
  {
    const double* eye = camera->GetPosition();
    for (int c = 0; c < 3; ++c)
    {
      view[c] = centre[c] - eye[c];
    }
  }
  const bool viewed = camera && vtkMath::Normalize(view) > 0;
  for (int i = 0; i < Centre; ++i)
  {
    if (this->HiddenBehindCentre[i])
    {
      this->HiddenBehindCentre[i] = false; // shown again, unless the base class hides it (HandlesOff, TwoPlaneMode)
      this->Handle[i]->SetVisibility(handlesShown && !(this->TwoPlaneMode && i >= 2));
    }
    if (!viewed || !this->Handle[i]->GetVisibility())
    {
      continue;
    }
    // the face sphere's offset from the centre across the line of sight: the spheres overlap on
    // the screen when it is shorter than their radii together; a click there moves the handle
    // (ComputeInteractionState), so only the centre sphere is drawn there
    double across[3];
    const double* face = this->HandleGeometry[i]->GetCenter();
    for (int c = 0; c < 3; ++c)
    {
      across[c] = face[c] - centre[c];
    }
    const double along = vtkMath::Dot(across, view);
    for (int c = 0; c < 3; ++c)
    {
      across[c] -= along * view[c];
    }
    if (vtkMath::Norm(across) < this->HandleGeometry[i]->GetRadius() + this->HandleGeometry[Centre]->GetRadius())
    {
      this->Handle[i]->VisibilityOff();
      this->HiddenBehindCentre[i] = true;
    }
  }
}

int vtkHandleBoxRepresentation::RenderOpaqueGeometry(vtkViewport* viewport)
{
  this->BuildRepresentation();
  this->HideFaceSpheresOverCentre();
  int count = 0;
  // the halos first: where a halo and its line lie at one depth, the line drawn later wins
  this->EdgeHalo->SetPropertyKeys(this->GetPropertyKeys());
  count += this->EdgeHalo->RenderOpaqueGeometry(viewport);
  for (int i = 0; i <= Centre; ++i)
  {
    if (this->Handle[i]->GetVisibility())
    {
      this->SphereHalo[i]->GetProperty()->SetColor(this->HaloProperty->GetColor());
      this->SphereHalo[i]->SetPropertyKeys(this->GetPropertyKeys());
      count += this->SphereHalo[i]->RenderOpaqueGeometry(viewport);
    }
  }
  return count + this->Superclass::RenderOpaqueGeometry(viewport);
}

void vtkHandleBoxRepresentation::ReleaseGraphicsResources(vtkWindow* window)
{
  this->Superclass::ReleaseGraphicsResources(window);
  this->EdgeHalo->ReleaseGraphicsResources(window);
  for (vtkActor* halo : this->SphereHalo)
  {
    halo->ReleaseGraphicsResources(window);
  }
}

void vtkHandleBoxRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "CentreScale: " << this->CentreScale << "\n";
}
