// SPDX-License-Identifier: BSD-3-Clause
#include "pqPiPrimitivePlacementWidget.h"

#include "PiPrimitiveSpec.h"

#include "pqApplicationCore.h"
#include "pqCoreUtilities.h"
#include "pqInterfaceTracker.h"
#include "pqPropertyWidgetInterface.h"
#include "vtkCommand.h"
#include "vtkSMPropertyGroup.h"
#include "vtkSMProxy.h"
#include "vtkSMUncheckedPropertyHelper.h"
#include "vtkSmartPointer.h"

#include <QPointer>
#include <QVBoxLayout>

#include <cstring>
#include <utility>
#include <vector>

namespace
{
using pisurf::PrimitiveType;

// One placement: ParaView's panel widget and its functions, each bound to a property of
// the Pi Primitive proxy.
struct Placement
{
  const char* PanelWidget;
  std::vector<std::pair<const char*, const char*>> Functions; // function, property
};

// The placement of each primitive type; nullptr panel widget for none.
Placement PlacementOf(int type)
{
  switch (static_cast<PrimitiveType>(type))
  {
    case PrimitiveType::Sphere:
      return { "InteractiveSphere", { { "Center", "Center" }, { "Radius", "Radius" } } };
    case PrimitiveType::Cylinder:
      return { "InteractiveCylinder",
        { { "Center", "Center" }, { "Axis", "Axis" }, { "Radius", "Radius" } } };
    case PrimitiveType::Torus:
      return { "InteractiveCylinder",
        { { "Center", "Center" }, { "Axis", "Axis" }, { "Radius", "MajorRadius" } } };
    case PrimitiveType::Plane:
      return { "InteractivePlane", { { "Origin", "Center" }, { "Normal", "Normal" } } };
    case PrimitiveType::Cone:
      return { "InteractivePlane", { { "Origin", "Center" }, { "Normal", "Axis" } } };
    case PrimitiveType::Ellipsoid:
    case PrimitiveType::Superellipsoid:
    case PrimitiveType::Hyperboloid1:
    case PrimitiveType::Hyperboloid2:
    case PrimitiveType::Paraboloid:
    case PrimitiveType::HyperbolicParaboloid:
      return { "InteractiveBox",
        { { "Position", "Center" }, { "Rotation", "Orientation" }, { "Scale", "Radii" },
          { "UseReferenceBounds", "WidgetUseReferenceBounds" },
          { "ReferenceBounds", "WidgetReferenceBounds" } } };
    case PrimitiveType::Polynomial:
      return { "InteractiveHandle", { { "WorldPosition", "Center" } } };
    default:
      return { nullptr, {} };
  }
}

// The box is always the unit box [-1, 1]^3 scaled by Radii: its reference-bounds
// controls and "Reset Bounds" (which would fit it to the data) do not apply.
void HideReferenceBoundsControls(QWidget* widget)
{
  for (const char* name : { "useReferenceBounds", "xmin", "xmax", "ymin", "ymax", "zmin", "zmax",
         "resetBounds", "referenceBoundsLabel", "referenceBoundsHorizontalLine" })
  {
    for (QWidget* child : widget->findChildren<QWidget*>(name))
    {
      child->hide();
    }
  }
}
}

class pqPiPrimitivePlacementWidget::pqInternals
{
public:
  QVBoxLayout* Layout = nullptr;
  QPointer<pqPropertyWidget> Current;
  vtkSmartPointer<vtkSMPropertyGroup> CurrentGroup;
  int CurrentType = -1;
};

pqPiPrimitivePlacementWidget::pqPiPrimitivePlacementWidget(
  vtkSMProxy* proxy, vtkSMPropertyGroup* group, QWidget* parent)
  : Superclass(proxy, parent)
  , Internals(new pqInternals())
{
  (void)group; // the properties are the proxy's, chosen per type by PlacementOf
  this->setShowLabel(false);
  this->Internals->Layout = new QVBoxLayout(this);
  this->Internals->Layout->setContentsMargins(0, 0, 0, 0);
  if (vtkSMProperty* type = proxy->GetProperty("Type"))
  {
    pqCoreUtilities::connect(
      type, vtkCommand::UncheckedPropertyModifiedEvent, this, SLOT(updateType()));
    pqCoreUtilities::connect(type, vtkCommand::ModifiedEvent, this, SLOT(updateType()));
  }
  this->updateType();
}

pqPiPrimitivePlacementWidget::~pqPiPrimitivePlacementWidget() = default;

const char* pqPiPrimitivePlacementWidget::panelWidgetOf(int type)
{
  return PlacementOf(type).PanelWidget;
}

pqPropertyWidget* pqPiPrimitivePlacementWidget::currentWidget() const
{
  return this->Internals->Current;
}

void pqPiPrimitivePlacementWidget::updateType()
{
  vtkSMProxy* proxy = this->proxy();
  const int type = proxy->GetProperty("Type")
    ? vtkSMUncheckedPropertyHelper(proxy, "Type").GetAsInt()
    : -1;
  pqInternals& internals = *this->Internals;
  const Placement placement = PlacementOf(type);
  const Placement previous = PlacementOf(internals.CurrentType);
  const bool same = internals.Current && previous.PanelWidget && placement.PanelWidget &&
    std::strcmp(previous.PanelWidget, placement.PanelWidget) == 0 &&
    previous.Functions == placement.Functions;
  internals.CurrentType = type;
  if (same)
  {
    return;
  }
  if (internals.Current)
  {
    // (deleted later: this may run inside one of the old widget's own signals)
    internals.Current->deselect();
    internals.Current->hide();
    internals.Layout->removeWidget(internals.Current);
    internals.Current->setParent(nullptr);
    internals.Current->deleteLater();
    internals.Current = nullptr;
  }
  internals.CurrentGroup = nullptr;
  if (!placement.PanelWidget)
  {
    return;
  }
  auto group = vtkSmartPointer<vtkSMPropertyGroup>::New();
  group->SetPanelWidget(placement.PanelWidget);
  group->SetXMLLabel("Placement");
  for (const auto& function : placement.Functions)
  {
    if (vtkSMProperty* property = proxy->GetProperty(function.second))
    {
      group->AddProperty(function.first, property, function.second);
    }
  }
  pqPropertyWidget* widget = nullptr;
  const auto interfaces =
    pqApplicationCore::instance()->interfaceTracker()->interfaces<pqPropertyWidgetInterface*>();
  for (pqPropertyWidgetInterface* iface : interfaces)
  {
    if ((widget = iface->createWidgetForPropertyGroup(proxy, group, this)))
    {
      break;
    }
  }
  if (!widget)
  {
    return; // a client without ParaView's standard widgets: the panel has none
  }
  widget->setObjectName(QString(placement.PanelWidget));
  if (std::strcmp(placement.PanelWidget, "InteractiveBox") == 0)
  {
    HideReferenceBoundsControls(widget);
  }
  internals.Layout->addWidget(widget);
  internals.Current = widget;
  internals.CurrentGroup = group;
  QObject::connect(widget, &pqPropertyWidget::changeAvailable, this,
    &pqPropertyWidget::changeAvailable);
  QObject::connect(widget, &pqPropertyWidget::changeFinished, this,
    &pqPropertyWidget::changeFinished);
  widget->setView(this->view());
  if (this->isSelected())
  {
    widget->select();
  }
}

void pqPiPrimitivePlacementWidget::apply()
{
  if (this->Internals->Current)
  {
    this->Internals->Current->apply();
  }
  this->Superclass::apply();
}

void pqPiPrimitivePlacementWidget::reset()
{
  if (this->Internals->Current)
  {
    this->Internals->Current->reset();
  }
  this->Superclass::reset();
}

void pqPiPrimitivePlacementWidget::select()
{
  this->Superclass::select();
  if (this->Internals->Current)
  {
    this->Internals->Current->select();
  }
}

void pqPiPrimitivePlacementWidget::deselect()
{
  this->Superclass::deselect();
  if (this->Internals->Current)
  {
    this->Internals->Current->deselect();
  }
}

void pqPiPrimitivePlacementWidget::setView(pqView* view)
{
  this->Superclass::setView(view);
  if (this->Internals->Current)
  {
    this->Internals->Current->setView(view);
  }
}
