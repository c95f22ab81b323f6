#include "pqHandleMotionWidget.h"
#include "pqSelectionBoxLabels.h"

#include "Adapters/HandleMotion.h"
#include "Vocabulary/RegionRoles.h"
#include "vtkHandleBoxRepresentation.h"

#include <pqActiveObjects.h>
#include <pqApplicationCore.h>
#include <pqCoreUtilities.h>
#include <pqDataRepresentation.h>
#include <pqDoubleLineEdit.h>
#include <pqPipelineSource.h>
#include <pqProxyWidget.h>
#include <pqServerManagerModel.h>
#include <pqUndoStack.h>
#include <pqView.h>
#include <vtkAbstractWidget.h>
#include <vtkBoundingBox.h>
#include <vtkBoxRepresentation.h>
#include <vtkCommand.h>
#include <vtkMatrix4x4.h>
#include <vtkNew.h>
#include <vtkPVGeneralSettings.h>
#include <vtkProperty.h>
#include <vtkSMNewWidgetRepresentationProxy.h>
#include <vtkSMPropertyGroup.h>
#include <vtkSMPropertyHelper.h>
#include <vtkSMRenderViewProxy.h>
#include <vtkSMUncheckedPropertyHelper.h>
#include <vtkTransform.h>

#include <QButtonGroup>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QLabel>
#include <QRadioButton>
#include <QTimer>

#include <algorithm>
#include <array>
#include <string>

namespace
{
// The group's properties by function (not the box widget's own property names, so that
// ParaView does not link them to the widget unconverted).
const char* const Functions[3] = { "HandleTranslation", "HandleRotation", "HandleScale" };

// The centre sphere's colour: none of the roles' (RegionRoles.h), so that it is not taken for a
// region's point; a hovered handle turns white.
constexpr double CentreColour[3] = { 1.0, 0.85, 0.0 };
constexpr double HoveredColour[3] = { 1.0, 1.0, 1.0 };
// The box's least thickness, a fraction of its largest extent: the face handles stay a quarter of
// the box's half-length or more away from the centre sphere, even around a planar region.
constexpr double LeastAspect = 0.25;
}

pqHandleMotionWidget::pqHandleMotionWidget(vtkSMProxy* proxy, vtkSMPropertyGroup* group, QWidget* parent)
  : Superclass("representations", "HandleBoxWidgetRepresentation", proxy, group, parent)
{
  this->setShowLabel(false);
  this->setChangeAvailableAsChangeFinished(true); // each step of a drag is applied by Auto Apply
  auto* layout = new QGridLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  // as ParaView's group headings, with the box's colour as its legend
  auto* heading = new QLabel(QString("<b>%1</b> (the red box)").arg(group->GetXMLLabel()), this);
  layout->addWidget(heading, 0, 0, 1, 4);
  for (int row = 1; row <= 3; ++row)
  {
    vtkSMProperty* property = group->GetProperty(Functions[row - 1]);
    this->Motion[row - 1] = property;
    // "Handle Translation": the Region's box widget has its own Translation and Rotation
    auto* label = new QLabel(QString("Handle %1").arg(property->GetXMLLabel()), this);
    label->setToolTip(pqPropertyWidget::getTooltip(property));
    layout->addWidget(label, row + 1, 0); // below the choice of box
    for (int c = 0; c < 3; ++c)
    {
      auto* field = new pqDoubleLineEdit(this);
      field->setObjectName(QString("%1_%2").arg(property->GetXMLName()).arg(c));
      field->setToolTip(pqPropertyWidget::getTooltip(property));
      layout->addWidget(field, row + 1, c + 1);
      this->addPropertyLink(field, "text2", SIGNAL(textChangedAndEditingFinished()), property, c);
    }
    pqCoreUtilities::connect(property, vtkCommand::UncheckedPropertyModifiedEvent, this, SLOT(motionEdited()));
    pqCoreUtilities::connect(property, vtkCommand::ModifiedEvent, this, SLOT(motionEdited()));
  }
  // which box the view shows: one at a time, so that a click lands on the box the designer meant
  auto* choices = new QHBoxLayout();
  choices->addWidget(new QLabel("Box in the view:", this));
  this->BoxChoice = new QButtonGroup(this);
  const std::array<std::pair<Box, const char*>, 3> boxes = { { { Box::Handle, "Handle" }, { Box::Selection, "Selection" },
    { Box::None, "None" } } };
  for (const auto& [box, name] : boxes)
  {
    auto* button = new QRadioButton(name, this);
    button->setObjectName(QString("Box%1").arg(name));
    this->BoxChoice->addButton(button, static_cast<int>(box));
    choices->addWidget(button);
  }
  choices->addStretch();
  this->BoxChoice->button(static_cast<int>(Box::Handle))->setToolTip(
    "The handle's box (red): drag its centre sphere (yellow) to move the handle, its faces to rotate it about the pivot, "
    "its face spheres to scale it. Shown once the region has selected its positions (Apply).");
  this->BoxChoice->button(static_cast<int>(Box::Selection))->setToolTip(
    "The region's selection box (its Region function's own widget): edits which positions the region selects.");
  this->BoxChoice->button(static_cast<int>(Box::None))->setToolTip("No box in the view.");
  layout->addLayout(choices, 1, 0, 1, 4); // at the top of the group, seen first
  QObject::connect(this->BoxChoice, &QButtonGroup::idClicked, this, [this](int box) {
    this->Shown = static_cast<Box>(box);
    this->showChosenBox();
  });

  // named so that a script finds it among the view's widgets (Testing/Python/test_gui_handle_widget.py)
  this->widgetProxy()->SetLogName((std::string("handle motion box of ") + proxy->GetLogNameOrDefault()).c_str());
  // drawn in the Handle's colour, its centre sphere in its own (vtkHandleBoxRepresentation)
  if (auto* box = vtkHandleBoxRepresentation::SafeDownCast(this->widgetProxy()->GetRepresentationProxy()->GetClientSideObject()))
  {
    const std::array<double, 3>& colour = mlsvtk::regionRole(mlsvtk::roles::Handle).colour;
    box->GetOutlineProperty()->SetColor(colour[0], colour[1], colour[2]);
    box->GetHandleProperty()->SetColor(colour[0], colour[1], colour[2]);
    box->GetCentreProperty()->SetColor(CentreColour[0], CentreColour[1], CentreColour[2]);
    box->GetSelectedHandleProperty()->SetColor(HoveredColour[0], HoveredColour[1], HoveredColour[2]);
    // picked on its own, not by the picking manager that gives a click to the nearest of the
    // view's widgets (the selection box is hidden while this one shows)
    box->PickingManagedOff();
  }
  if (vtkAbstractWidget* widget = this->widgetProxy()->GetWidget())
  {
    widget->SetPriority(0.6f);
    if (widget->GetEnabled())
    {
      widget->SetEnabled(0); // its observers are added anew, at that priority
      widget->SetEnabled(1);
    }
  }
  this->setDataSource(proxy); // the box surrounds the region's output: the selected positions
  this->connect(this, SIGNAL(interaction()), SLOT(boxMoved()));
  this->connect(this, SIGNAL(endInteraction()), SLOT(boxMoved()));
  this->connect(this, SIGNAL(startInteraction()), SLOT(dragStarted()));
  this->connect(this, SIGNAL(endInteraction()), SLOT(dragEnded()));
  this->connect(&pqActiveObjects::instance(), SIGNAL(dataUpdated()), SLOT(placeWidget()));
  if (vtkSMProperty* role = proxy->GetProperty("Role"))
  {
    pqCoreUtilities::connect(role, vtkCommand::ModifiedEvent, this, SLOT(motionEdited())); // a Handle no longer
    pqCoreUtilities::connect(role, vtkCommand::ModifiedEvent, this, SLOT(showChosenBox()));
  }
  // the region's points shown for the first time (its first Apply) are drawn moved too
  if (auto* source = pqApplicationCore::instance()->getServerManagerModel()->findItem<pqPipelineSource*>(proxy))
  {
    this->connect(source, SIGNAL(representationAdded(pqPipelineSource*, pqDataRepresentation*, int)),
      SLOT(regionShown(pqPipelineSource*, pqDataRepresentation*)));
    // a drag's last motion applied: its undo step closes (dragEnded)
    this->connect(source, SIGNAL(modifiedStateChanged(pqServerManagerModelItem*)), SLOT(dragEnded()));
  }
  this->showOnTop(this->view()); // the base class showed the box in the view it was made in
  if (parent)
  {
    new pqSelectionBoxLabels(parent); // the Region's selection box beside it, in its own words
  }
  // no box before the region has selected its positions; then the chosen one, once the panel's
  // selection box exists
  this->setWidgetVisible(false);
  QTimer::singleShot(0, this, &pqHandleMotionWidget::showChosenBox);
}

pqHandleMotionWidget::~pqHandleMotionWidget()
{
  if (this->Dragging)
  {
    END_UNDO_SET();
  }
  this->removeOnTop();
}

void pqHandleMotionWidget::setView(pqView* view)
{
  this->Superclass::setView(view);
  this->showOnTop(view);
}

void pqHandleMotionWidget::showOnTop(pqView* view)
{
  this->removeOnTop();
  auto* renderView = vtkSMRenderViewProxy::SafeDownCast(view ? view->getViewProxy() : nullptr);
  auto* box = vtkBoxRepresentation::SafeDownCast(this->widgetProxy()->GetRepresentationProxy()->GetClientSideObject());
  vtkRenderWindow* window = renderView ? renderView->GetRenderWindow() : nullptr;
  if (!window || !box)
  {
    return; // a view of another kind, or the box is not on this process
  }
  // one layer above the view's; the box's visibility stays the widget's (the Box in the view choice)
  this->OnTop->SetLayer(window->GetNumberOfLayers());
  window->SetNumberOfLayers(window->GetNumberOfLayers() + 1);
  this->OnTop->SetActiveCamera(renderView->GetActiveCamera());
  this->OnTop->InteractiveOff();
  this->OnTop->AddViewProp(box);
  window->AddRenderer(this->OnTop);
  this->OnTopWindow = window;
}

void pqHandleMotionWidget::removeOnTop()
{
  if (vtkRenderWindow* window = this->OnTopWindow)
  {
    window->RemoveRenderer(this->OnTop);
    if (this->OnTop->GetLayer() == window->GetNumberOfLayers() - 1)
    {
      window->SetNumberOfLayers(window->GetNumberOfLayers() - 1);
    }
  }
  this->OnTop->RemoveAllViewProps();
  this->OnTopWindow = nullptr;
}

void pqHandleMotionWidget::dragStarted()
{
  if (!this->Dragging)
  {
    BEGIN_UNDO_SET(QString("Move Handle of %1").arg(this->proxy()->GetLogNameOrDefault()));
    this->Dragging = true;
  }
  this->DragEnded = false;
  if (vtkPVGeneralSettings::GetInstance()->GetAutoApply())
  {
    this->setRegionDragging(true); // each applied step moves the surface blocks only
  }
}

void pqHandleMotionWidget::setRegionDragging(bool dragging)
{
  vtkSMProxy* region = this->proxy();
  if (region->GetProperty("Dragging") && vtkSMPropertyHelper(region, "Dragging").GetAsInt() != (dragging ? 1 : 0))
  {
    // pushed at once (not left for Apply); inside the drag's undo set, so that undo and redo
    // both end with it off
    vtkSMPropertyHelper(region, "Dragging").Set(dragging ? 1 : 0);
    region->UpdateVTKObjects();
  }
}

void pqHandleMotionWidget::dragEnded()
{
  auto* source = pqApplicationCore::instance()->getServerManagerModel()->findItem<pqPipelineSource*>(this->proxy());
  const bool autoApply = vtkPVGeneralSettings::GetInstance()->GetAutoApply();
  if (this->sender() == this)
  {
    this->DragEnded = true;
    if (vtkSMPropertyHelper(this->proxy(), "Dragging", true).GetAsInt() != 0)
    {
      // released: the volume blocks follow (with the last motion, when Auto Apply has it pending);
      // the box is drawn released now, not once that update has run (seconds on a large case)
      this->setRegionDragging(false);
      if (this->view())
      {
        this->view()->forceRender();
      }
    }
  }
  const bool applyPending = source && source->modifiedState() != pqProxy::UNMODIFIED && autoApply;
  if (this->Dragging && this->DragEnded && !applyPending)
  {
    END_UNDO_SET();
    this->Dragging = false;
  }
}

void pqHandleMotionWidget::hideEvent(QHideEvent* event)
{
  const bool shown = this->isWidgetVisible();
  this->Superclass::hideEvent(event);
  this->VisibleState = shown;
}

void pqHandleMotionWidget::showEvent(QShowEvent* event)
{
  this->Superclass::showEvent(event);
  QTimer::singleShot(0, this, &pqHandleMotionWidget::showChosenBox); // after the selection box's own showEvent
}

QList<pqInteractivePropertyWidget*> pqHandleMotionWidget::selectionBoxes() const
{
  // the region's panel: the proxy widget of this region that holds this widget
  QWidget* panel = this->parentWidget();
  while (panel && !(qobject_cast<pqProxyWidget*>(panel) && qobject_cast<pqProxyWidget*>(panel)->proxy() == this->proxy()))
  {
    panel = panel->parentWidget();
  }
  QList<pqInteractivePropertyWidget*> boxes = panel ? panel->findChildren<pqInteractivePropertyWidget*>() : QList<pqInteractivePropertyWidget*>();
  boxes.removeAll(const_cast<pqHandleMotionWidget*>(this));
  return boxes;
}

void pqHandleMotionWidget::showChosenBox()
{
  const bool handle = vtkSMPropertyHelper(this->proxy(), "Role").GetAsInt() == mlsvtk::roles::Handle;
  const bool selected = this->dataBounds().IsValid(); // the region's positions, after its first Apply
  this->ShowingBoxes = true;
  this->setWidgetVisible(handle && selected && this->Shown == Box::Handle);
  for (pqInteractivePropertyWidget* box : this->selectionBoxes())
  {
    QObject::connect(box, &pqInteractivePropertyWidget::widgetVisibilityToggled, this, &pqHandleMotionWidget::selectionBoxToggled,
      Qt::UniqueConnection);
    if (!handle || !selected)
    {
      // the region's only box: shown, unless the designer chose none
      box->setWidgetVisible(box->isWidgetVisible() || (!handle && this->Shown == Box::Handle));
    }
    else
    {
      box->setWidgetVisible(this->Shown == Box::Selection);
    }
  }
  this->ShowingBoxes = false;
  this->BoxChoice->button(static_cast<int>(this->Shown))->setChecked(true);
}

void pqHandleMotionWidget::selectionBoxToggled(bool shown)
{
  auto* box = qobject_cast<pqInteractivePropertyWidget*>(this->sender());
  // not this widget's own doing, nor a panel shown or hidden: the box's Show Box check box
  if (this->ShowingBoxes || !box || !box->isVisible() || !this->isVisible())
  {
    return;
  }
  // shown: it becomes the choice; hidden: the handle's box comes back (None is chosen in the row)
  if (shown)
  {
    this->Shown = Box::Selection;
  }
  else if (this->Shown == Box::Selection)
  {
    this->Shown = Box::Handle;
  }
  this->showChosenBox();
}

void pqHandleMotionWidget::placeWidget()
{
  vtkSMProxy* region = this->proxy();
  if (vtkSMProperty* pivot = region->GetProperty("PivotInfo"))
  {
    region->UpdatePropertyInformation(pivot);
    vtkSMPropertyHelper(pivot).Get(this->Pivot, 3);
  }
  const vtkBoundingBox selected = this->dataBounds();
  if (!selected.IsValid())
  {
    this->showChosenBox(); // no positions (yet): no handle box
    return;
  }
  // a box centred on the pivot that holds the selected positions, at least LeastAspect of its
  // length thick (a plane's positions would give a flat box whose face handles sit on the centre
  // sphere, and that the widget cannot rotate)
  double halves[3], bounds[6];
  for (int i = 0; i < 3; ++i)
  {
    halves[i] = std::max(this->Pivot[i] - selected.GetMinPoint()[i], selected.GetMaxPoint()[i] - this->Pivot[i]);
  }
  const double least = LeastAspect * std::max({ halves[0], halves[1], halves[2], 1e-300 });
  for (int i = 0; i < 3; ++i)
  {
    const double half = std::max(halves[i], least);
    bounds[2 * i] = this->Pivot[i] - half;
    bounds[2 * i + 1] = this->Pivot[i] + half;
  }
  vtkSMNewWidgetRepresentationProxy* box = this->widgetProxy();
  vtkSMPropertyHelper(box, "PlaceWidget").Set(bounds, 6);
  box->UpdateVTKObjects();
  this->motionEdited();
  this->showChosenBox(); // the first positions: the handle box may show
}

void pqHandleMotionWidget::motionEdited()
{
  if (this->Updating)
  {
    return;
  }
  const mlsvtk::BoxTransform transform = this->motionTransform();
  vtkSMNewWidgetRepresentationProxy* box = this->widgetProxy();
  this->Updating = true;
  vtkSMPropertyHelper(box, "Position").Set(transform.position, 3);
  vtkSMPropertyHelper(box, "Rotation").Set(transform.rotation, 3);
  vtkSMPropertyHelper(box, "Scale").Set(transform.scale, 3);
  box->UpdateVTKObjects();
  this->Updating = false;
  this->moveRegionPoints();
  this->render();
}

mlsvtk::BoxTransform pqHandleMotionWidget::motionTransform() const
{
  mlsvtk::HandleMotion motion;
  vtkSMUncheckedPropertyHelper(this->Motion[0]).Get(motion.translation, 3);
  vtkSMUncheckedPropertyHelper(this->Motion[1]).Get(motion.rotation, 3);
  vtkSMUncheckedPropertyHelper(this->Motion[2]).Get(motion.scale, 3);
  return mlsvtk::boxTransform(motion, this->Pivot);
}

void pqHandleMotionWidget::regionShown(pqPipelineSource*, pqDataRepresentation* representation)
{
  this->moveRegionPoints(representation);
}

void pqHandleMotionWidget::moveRegionPoints(pqDataRepresentation* shown)
{
  // the region's output stays the selected positions at rest (MLS Deform's input); only its
  // representation in the view is moved, by the box's own transform (both are vtkPVTransform's:
  // translate, rotate about Z, X, then Y, scale, about the origin)
  if (!shown)
  {
    auto* source = pqApplicationCore::instance()->getServerManagerModel()->findItem<pqPipelineSource*>(this->proxy());
    shown = source ? source->getRepresentation(pqActiveObjects::instance().activeView()) : nullptr;
  }
  vtkSMProxy* points = shown ? shown->getProxy() : nullptr;
  if (!points || !points->GetProperty("Orientation"))
  {
    return;
  }
  // only a Handle moves; a region whose role was changed is drawn where it is
  const bool handle = vtkSMPropertyHelper(this->proxy(), "Role").GetAsInt() == mlsvtk::roles::Handle;
  const mlsvtk::BoxTransform drawn = handle ? this->motionTransform() : mlsvtk::BoxTransform();
  vtkSMPropertyHelper(points, "Position").Set(drawn.position, 3);
  vtkSMPropertyHelper(points, "Orientation").Set(drawn.rotation, 3);
  vtkSMPropertyHelper(points, "Scale").Set(drawn.scale, 3);
  points->UpdateVTKObjects();
}

void pqHandleMotionWidget::boxMoved()
{
  auto* representation = vtkBoxRepresentation::SafeDownCast(this->widgetProxy()->GetRepresentationProxy()->GetClientSideObject());
  if (this->Updating || !representation)
  {
    return;
  }
  vtkNew<vtkTransform> transform;
  representation->GetTransform(transform);
  double matrix[16];
  vtkMatrix4x4::DeepCopy(matrix, transform->GetMatrix());
  mlsvtk::HandleMotion motion = mlsvtk::handleMotion(matrix, this->Pivot);
  // the round-off of the box's transform (~1e-16 of its size) shown as the exact value it stands
  // for: a box moved straight up reads Translation (0, 0, dz), not (1e-16, -7e-18, dz)
  const double size = std::max(1.0, vtkBoundingBox(representation->GetBounds()).GetMaxLength());
  for (int i = 0; i < 3; ++i)
  {
    motion.translation[i] = std::abs(motion.translation[i]) < 1e-12 * size ? 0.0 : motion.translation[i];
    motion.rotation[i] = std::abs(motion.rotation[i]) < 1e-9 ? 0.0 : motion.rotation[i];
    motion.scale[i] = std::abs(motion.scale[i] - 1) < 1e-12 ? 1.0 : motion.scale[i];
  }
  this->Updating = true;
  vtkSMUncheckedPropertyHelper(this->Motion[0]).Set(motion.translation, 3);
  vtkSMUncheckedPropertyHelper(this->Motion[1]).Set(motion.rotation, 3);
  vtkSMUncheckedPropertyHelper(this->Motion[2]).Set(motion.scale, 3);
  this->Updating = false;
  this->moveRegionPoints();
}
