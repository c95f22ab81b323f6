// A property widget decorator that shows its widget only while the proxy's Input is a composite
// dataset (an OpenFOAM case, a multiblock): the Constraint Region's Blocks checklist, which on a
// single dataset (a deck read by the Mesh File reader) would be an empty box.
//
//   <PropertyWidgetDecorator type="mlsdeform_composite_input" />
#pragma once

#include <pqPropertyWidgetDecorator.h>

class pqCompositeInputDecorator : public pqPropertyWidgetDecorator
{
  Q_OBJECT

public:
  pqCompositeInputDecorator(vtkPVXMLElement* config, pqPropertyWidget* parent);

  bool canShowWidget(bool showAdvanced) const override;
};
