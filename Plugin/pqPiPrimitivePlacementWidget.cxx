// SPDX-License-Identifier: BSD-3-Clause
#include "pqPiPrimitivePlacementWidget.h"

#include "PiPrimitiveCatalogue.h"

#include "pqApplicationCore.h"
#include "pqCoreUtilities.h"
#include "pqInterfaceTracker.h"
#include "pqPropertyWidgetInterface.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkPiPrimitive.h"
#include "vtkSMPropertyGroup.h"
#include "vtkSMPropertyIterator.h"
#include "vtkSMProxy.h"
#include "vtkSMUncheckedPropertyHelper.h"
#include "vtkSmartPointer.h"

#include <QPointer>
#include <QTimer>
#include <QVBoxLayout>

#include <algorithm>
#include <cstring>
#include <string>
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

// The placement of each primitive type: its catalogue widget, bound to the properties
// the catalogue names; nullptr panel widget for none.
Placement PlacementOf(int type)
{
  if (!pisurf::IsPrimitiveType(type))
  {
    return { nullptr, {} };
  }
  const pisurf::PrimitiveInfo& entry = pisurf::CatalogueEntry(static_cast<PrimitiveType>(type));
  switch (entry.Widget)
  {
    case pisurf::WidgetKind::Sphere:
      return { "InteractiveSphere", { { "Center", "Center" }, { "Radius", entry.WidgetSize } } };
    case pisurf::WidgetKind::Cylinder:
      return { "InteractiveCylinder",
        { { "Center", "Center" }, { "Axis", entry.WidgetDirection },
          { "Radius", entry.WidgetSize } } };
    case pisurf::WidgetKind::Plane:
      return { "InteractivePlane",
        { { "Origin", "Center" }, { "Normal", entry.WidgetDirection } } };
    case pisurf::WidgetKind::Box:
      return { "InteractiveBox",
        { { "Position", "Center" }, { "Rotation", "Orientation" }, { "Scale", entry.WidgetSize },
          { "UseReferenceBounds", "WidgetUseReferenceBounds" },
          { "ReferenceBounds", "WidgetReferenceBounds" } } };
    case pisurf::WidgetKind::Handle:
      return { "InteractiveHandle", { { "WorldPosition", "Center" } } };
  }
  return { nullptr, {} };
}

// Two placements that bind the same functions to the same properties (by name: the
// catalogue's strings need not share addresses).
bool SameFunctions(const Placement& a, const Placement& b)
{
  return std::equal(a.Functions.begin(), a.Functions.end(), b.Functions.begin(), b.Functions.end(),
    [](const auto& x, const auto& y)
    { return std::strcmp(x.first, y.first) == 0 && std::strcmp(x.second, y.second) == 0; });
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

// The property whose value a validation message of the core names (the message starts
// with the parameter's model key: the longest that matches), or nullptr.
const char* PropertyOfMessage(const std::string& message)
{
  std::vector<std::pair<const char*, const char*>> keys = { { "rotation axis", "RotationAxis" },
    { "rotation angle", "RotationAngle" }, { "center", "Center" }, { "scale", "Scale" },
    { "axis", "Axis" } };
  for (const pisurf::PrimitiveInfo& entry : pisurf::PrimitiveCatalogue())
  {
    for (const pisurf::ParameterInfo& p : entry.Parameters)
    {
      keys.emplace_back(p.Key, p.Property);
    }
  }
  const char* property = nullptr;
  size_t longest = 0;
  for (const auto& key : keys)
  {
    const size_t n = std::strlen(key.first);
    if (n > longest && message.compare(0, n, key.first) == 0)
    {
      property = key.second;
      longest = n;
    }
  }
  return property;
}

// The primitive that the panel's values (unchecked: as typed, before Apply) define.
std::string PanelError(vtkSMProxy* proxy)
{
  vtkNew<vtkPiPrimitive> primitive;
  auto get3 = [&](const char* name, double v[3])
  { vtkSMUncheckedPropertyHelper(proxy, name).Get(v, 3); };
  double v[3];
  primitive->SetType(vtkSMUncheckedPropertyHelper(proxy, "Type").GetAsInt());
  // Every type's parameters (their properties hold the values of whichever type shows).
  pisurf::PrimitiveSpec shape = primitive->GetSpec();
  for (const pisurf::PrimitiveInfo& entry : pisurf::PrimitiveCatalogue())
  {
    for (const pisurf::ParameterInfo& p : entry.Parameters)
    {
      vtkSMUncheckedPropertyHelper value(proxy, p.Property);
      switch (p.Kind)
      {
        case pisurf::ParameterKind::Number:
          value.Get(p.Numbers(shape), p.Count);
          break;
        case pisurf::ParameterKind::Integer:
          *p.Integer(shape) = value.GetAsInt();
          break;
        case pisurf::ParameterKind::Text:
        {
          const char* text = value.GetAsString();
          *p.Text(shape) = text ? text : "";
          break;
        }
      }
    }
  }
  primitive->SetSpec(shape);
  get3("Center", v);
  primitive->SetCenter(v);
  get3("Axis", v);
  primitive->SetAxis(v);
  get3("RotationAxis", v);
  primitive->SetRotationAxis(v);
  primitive->SetRotationAngle(vtkSMUncheckedPropertyHelper(proxy, "RotationAngle").GetAsDouble());
  get3("Orientation", v);
  primitive->SetOrientation(v);
  primitive->SetScale(vtkSMUncheckedPropertyHelper(proxy, "Scale").GetAsDouble());
  // vtkPiPrimitive reports an invalid primitive to the output window: this check is
  // silent (the GUI thread runs no other VTK code meanwhile), the source reports on Apply.
  const int display = vtkObject::GetGlobalWarningDisplay();
  vtkObject::GlobalWarningDisplayOff();
  const bool valid = primitive->IsValid();
  vtkObject::SetGlobalWarningDisplay(display);
  return valid ? std::string() : std::string(primitive->GetErrorMessage());
}
}

class pqPiPrimitivePlacementWidget::pqInternals
{
public:
  QVBoxLayout* Layout = nullptr;
  QPointer<pqPropertyWidget> Current;
  vtkSmartPointer<vtkSMPropertyGroup> CurrentGroup;
  int CurrentType = -1;
  QPointer<QWidget> Marked; // the widget marked as refused
  QString MarkedStyle, MarkedTip;
  bool CheckPending = false;
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
  // Any value typed in the panel: check the primitive it makes.
  vtkSmartPointer<vtkSMPropertyIterator> properties;
  properties.TakeReference(proxy->NewPropertyIterator());
  for (properties->Begin(); !properties->IsAtEnd(); properties->Next())
  {
    pqCoreUtilities::connect(properties->GetProperty(), vtkCommand::UncheckedPropertyModifiedEvent,
      this, SLOT(scheduleCheck()));
  }
  pqCoreUtilities::connect(proxy, vtkCommand::PropertyModifiedEvent, this, SLOT(scheduleCheck()));
  this->updateType();
  this->scheduleCheck();
}

pqPiPrimitivePlacementWidget::~pqPiPrimitivePlacementWidget() = default;

pqPropertyWidget* pqPiPrimitivePlacementWidget::currentWidget() const
{
  return this->Internals->Current;
}

void pqPiPrimitivePlacementWidget::updateType()
{
  vtkSMProxy* proxy = this->proxy();
  const int type =
    proxy->GetProperty("Type") ? vtkSMUncheckedPropertyHelper(proxy, "Type").GetAsInt() : -1;
  pqInternals& internals = *this->Internals;
  const Placement placement = PlacementOf(type);
  const Placement previous = PlacementOf(internals.CurrentType);
  const bool same = internals.Current && previous.PanelWidget && placement.PanelWidget &&
    std::strcmp(previous.PanelWidget, placement.PanelWidget) == 0 &&
    SameFunctions(previous, placement);
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
  QObject::connect(
    widget, &pqPropertyWidget::changeAvailable, this, &pqPropertyWidget::changeAvailable);
  QObject::connect(
    widget, &pqPropertyWidget::changeFinished, this, &pqPropertyWidget::changeFinished);
  widget->setView(this->view());
  if (this->isSelected())
  {
    widget->select();
  }
}

void pqPiPrimitivePlacementWidget::scheduleCheck()
{
  if (!this->Internals->CheckPending)
  {
    this->Internals->CheckPending = true;
    QTimer::singleShot(0, this, SLOT(checkValues()));
  }
}

void pqPiPrimitivePlacementWidget::checkValues()
{
  pqInternals& internals = *this->Internals;
  internals.CheckPending = false;
  if (internals.Marked)
  {
    internals.Marked->setStyleSheet(internals.MarkedStyle);
    internals.Marked->setToolTip(internals.MarkedTip);
  }
  internals.Marked = nullptr;
  const std::string error = PanelError(this->proxy());
  if (error.empty())
  {
    return;
  }
  // The refused parameter's field: one of the panel's own, or this group (whose
  // properties ParaView's widget edits).
  const char* name = PropertyOfMessage(error);
  QWidget* target = nullptr;
  vtkSMPropertyGroup* group = internals.CurrentGroup;
  for (unsigned int i = 0; name && group && i < group->GetNumberOfProperties(); ++i)
  {
    if (group->GetPropertyName(i) && std::strcmp(group->GetPropertyName(i), name) == 0)
    {
      target = internals.Current;
    }
  }
  if (!target && name && this->parentWidget())
  {
    target = this->parentWidget()->findChild<pqPropertyWidget*>(name);
  }
  if (!target)
  {
    return;
  }
  internals.Marked = target;
  internals.MarkedStyle = target->styleSheet();
  internals.MarkedTip = target->toolTip();
  target->setStyleSheet("QLineEdit, QTextEdit, QPlainTextEdit { background-color: #f4c7c3; }");
  target->setToolTip(
    QString("Refused: %1. The last valid surface is kept.").arg(QString::fromStdString(error)));
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
