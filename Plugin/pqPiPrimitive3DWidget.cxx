// SPDX-License-Identifier: BSD-3-Clause
#include "pqPiPrimitive3DWidget.h"

#include "PiPrimitiveCatalogue.h"

#include "pqApplicationCore.h"
#include "pqCoreUtilities.h"
#include "pqRenderView.h"
#include "pqServer.h"
#include "pqServerManagerModel.h"
#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkSMNewWidgetRepresentationProxy.h"
#include "vtkSMParaViewPipelineController.h"
#include "vtkSMPropertyHelper.h"
#include "vtkSMSession.h"
#include "vtkSMSessionProxyManager.h"
#include "vtkSMViewProxy.h"
#include "vtkSmartPointer.h"
#include "vtkTransform.h"
#include "vtkWeakPointer.h"

#include <QPointer>

#include <algorithm>
#include <cmath>
#include <vector>

namespace
{
using pisurf::Orientation;
using pisurf::PrimitiveType;
using Kind = pqPiPrimitive3DWidget::Kind;

void Set3(vtkSMProxy* proxy, const char* name, const double v[3])
{
  vtkSMPropertyHelper(proxy, name).Set(v, 3);
}

// A value read back from a widget: the box's position and scale come out of a matrix
// decomposition with round-off (-0.8999999999999999 for -0.9). A difference within a few
// ulps keeps the row's value, so an untouched parameter stays as typed.
void Settle(double& value, double fromWidget)
{
  const double tolerance = 1e-12 * std::max(1.0, std::abs(value));
  if (std::abs(fromWidget - value) > tolerance)
  {
    value = fromWidget;
  }
}

// The box widget turns by Euler angles in degrees, as vtkProp3D and vtkPVTransform do:
// R = Rz(c) Rx(a) Ry(b) for Rotation (a, b, c). A primitive turns by an axis and an
// angle (PrimitiveSpec::RotationAxis, RotationAngle): world = centre + R local.
void EulerOf(const pisurf::PrimitiveSpec& spec, double euler[3])
{
  vtkNew<vtkTransform> t;
  if (spec.Orient == Orientation::Rotation)
  {
    t->RotateWXYZ(spec.RotationAngle, spec.RotationAxis);
  }
  t->GetOrientation(euler);
}

// Euler angles to the primitive's axis and angle; false for no rotation.
bool AxisAngleOf(const double euler[3], double axis[3], double& angle)
{
  vtkNew<vtkTransform> t;
  t->RotateZ(euler[2]);
  t->RotateX(euler[0]);
  t->RotateY(euler[1]);
  double wxyz[4];
  t->GetOrientationWXYZ(wxyz);
  angle = wxyz[0];
  std::copy(wxyz + 1, wxyz + 4, axis);
  return std::abs(angle) > 1e-9 && (axis[0] != 0 || axis[1] != 0 || axis[2] != 0);
}

// The values the sphere's radius or the box's scale edit: the catalogue's WidgetSize.
double* SizeOf(pisurf::PrimitiveSpec& spec)
{
  const pisurf::PrimitiveInfo& entry = pisurf::CatalogueEntry(spec.Type);
  const pisurf::ParameterInfo* size =
    entry.WidgetSize ? pisurf::FindParameter(entry, entry.WidgetSize) : nullptr;
  return size && size->Kind == pisurf::ParameterKind::Number ? size->Numbers(spec) : nullptr;
}

void Get3(vtkSMProxy* proxy, const char* name, double v[3])
{
  double read[3];
  vtkSMPropertyHelper(proxy, name).Get(read, 3);
  for (int i = 0; i < 3; ++i)
  {
    Settle(v[i], read[i]);
  }
}
}

//-----------------------------------------------------------------------------
class pqPiPrimitive3DWidget::pqInternals
{
public:
  vtkWeakPointer<vtkSMSessionProxyManager> ProxyManager;
  vtkSmartPointer<vtkSMNewWidgetRepresentationProxy> Proxy;
  Kind ProxyKind = Kind::None;
  QPointer<pqView> View;                // the view that holds Proxy
  vtkWeakPointer<vtkSMProxy> ViewProxy; // its proxy, to remove Proxy from it
  std::vector<unsigned long> Observers;
  bool Shown = false;
  bool Interacting = false;

  void render()
  {
    if (this->View)
    {
      this->View->render();
    }
  }

  /// Takes the widget out of its view and drops it.
  void release()
  {
    if (!this->Proxy)
    {
      return;
    }
    for (unsigned long id : this->Observers)
    {
      this->Proxy->RemoveObserver(id);
    }
    this->Observers.clear();
    vtkSMPropertyHelper(this->Proxy, "Visibility").Set(0);
    vtkSMPropertyHelper(this->Proxy, "Enabled").Set(0);
    this->Proxy->UpdateVTKObjects();
    if (this->ViewProxy)
    {
      vtkSMPropertyHelper(this->ViewProxy, "HiddenRepresentations").Remove(this->Proxy);
      this->ViewProxy->UpdateVTKObjects();
    }
    this->render();
    this->Proxy = nullptr;
    this->ProxyKind = Kind::None;
    this->View = nullptr;
    this->ViewProxy = nullptr;
    this->Shown = false;
    this->Interacting = false;
  }

  /// A new widget proxy of `kind`, placed for its kind, in `view`.
  bool create(Kind kind, pqView* view, pqPiPrimitive3DWidget* self)
  {
    if (!this->ProxyManager)
    {
      return false;
    }
    vtkSmartPointer<vtkSMProxy> proxy;
    proxy.TakeReference(
      this->ProxyManager->NewProxy("representations", pqPiPrimitive3DWidget::proxyName(kind)));
    auto* widget = vtkSMNewWidgetRepresentationProxy::SafeDownCast(proxy);
    if (!widget)
    {
      return false;
    }
    vtkNew<vtkSMParaViewPipelineController> controller;
    controller->InitializeProxy(widget);
    // Placement first, in its own update: placing a sphere or a box resets it.
    const double unit[6] = { -1, 1, -1, 1, -1, 1 };
    if (kind == Kind::Box)
    {
      // The box is the reference box [-1, 1]^3 scaled by Scale, turned by Rotation and
      // moved to Position: Scale holds the semi-axes, Rotation the orientation.
      vtkSMPropertyHelper(widget, "UseReferenceBounds").Set(1);
      vtkSMPropertyHelper(widget, "ReferenceBounds").Set(unit, 6);
      vtkSMPropertyHelper(widget, "PlaceWidget").Set(unit, 6);
      vtkSMPropertyHelper(widget, "RotationEnabled").Set(1);
      const double none[3] = { 0, 0, 0 };
      Set3(widget, "Rotation", none);
    }
    else if (kind == Kind::Sphere)
    {
      vtkSMPropertyHelper(widget, "PlaceWidget").Set(unit, 6);
    }
    widget->UpdateVTKObjects();
    // As ParaView's own interactive widgets: outside undo/redo and state files.
    widget->PrototypeOn();

    this->Observers.push_back(pqCoreUtilities::connect(
      widget, vtkCommand::StartInteractionEvent, self, SLOT(onStartInteraction())));
    this->Observers.push_back(
      pqCoreUtilities::connect(widget, vtkCommand::InteractionEvent, self, SIGNAL(interaction())));
    this->Observers.push_back(pqCoreUtilities::connect(
      widget, vtkCommand::EndInteractionEvent, self, SLOT(onEndInteraction())));

    this->Proxy = widget;
    this->ProxyKind = kind;
    this->View = view;
    this->ViewProxy = view->getProxy();
    vtkSMPropertyHelper(this->ViewProxy, "HiddenRepresentations").Add(widget);
    this->ViewProxy->UpdateVTKObjects();
    return true;
  }

  /// The primitive's placement into the widget's properties.
  void push(const pisurf::PrimitiveSpec& primitive)
  {
    vtkSMProxy* widget = this->Proxy;
    pisurf::PrimitiveSpec spec = primitive;
    const double* size = SizeOf(spec);
    switch (this->ProxyKind)
    {
      case Kind::Sphere:
        // The radius after the centre, each pushed: with its handle shown, a sphere
        // widget whose centre moves keeps the handle and takes the radius from it.
        Set3(widget, "Center", spec.Center);
        vtkSMPropertyHelper(widget, "Radius").Set(size[0]);
        widget->UpdateProperty("Center", 1);
        widget->UpdateProperty("Radius", 1);
        break;
      case Kind::Box:
      {
        double euler[3];
        EulerOf(spec, euler);
        Set3(widget, "Position", spec.Center);
        Set3(widget, "Rotation", euler);
        Set3(widget, "Scale", size);
        break;
      }
      case Kind::Handle:
        Set3(widget, "WorldPosition", spec.Center);
        break;
      case Kind::None:
        break;
    }
  }
};

//-----------------------------------------------------------------------------
pqPiPrimitive3DWidget::pqPiPrimitive3DWidget(vtkSMSessionProxyManager* pxm, QObject* parentObject)
  : Superclass(parentObject)
  , Internals(new pqInternals())
{
  this->Internals->ProxyManager = pxm;
  if (pqApplicationCore* core = pqApplicationCore::instance())
  {
    QObject::connect(core->getServerManagerModel(), &pqServerManagerModel::preViewRemoved, this,
      &pqPiPrimitive3DWidget::onViewRemoved);
  }
}

//-----------------------------------------------------------------------------
pqPiPrimitive3DWidget::~pqPiPrimitive3DWidget()
{
  this->Internals->release();
}

//-----------------------------------------------------------------------------
Kind pqPiPrimitive3DWidget::kindOf(const pisurf::PrimitiveSpec& spec)
{
  // The catalogue's widget where this editor has it: a sphere (the same in every
  // orientation), a box for a bounded type (the box is its extent; an Axis orientation
  // picks its own frame about the axis: a handle), a handle at the centre otherwise.
  const pisurf::PrimitiveInfo& entry = pisurf::CatalogueEntry(spec.Type);
  if (entry.Widget == pisurf::WidgetKind::Sphere)
  {
    return Kind::Sphere;
  }
  if (entry.Widget == pisurf::WidgetKind::Box && entry.Bounded)
  {
    return spec.Orient != Orientation::Axis ? Kind::Box : Kind::Handle;
  }
  return Kind::Handle;
}

//-----------------------------------------------------------------------------
const char* pqPiPrimitive3DWidget::proxyName(Kind kind)
{
  switch (kind)
  {
    case Kind::Sphere:
      return "SphereWidgetRepresentation";
    case Kind::Box:
      return "BoxWidgetRepresentation";
    case Kind::Handle:
      return "HandleWidgetRepresentation";
    default:
      return nullptr;
  }
}

//-----------------------------------------------------------------------------
void pqPiPrimitive3DWidget::show(const pisurf::PrimitiveSpec* spec, pqView* view, bool active)
{
  pqInternals& internals = *this->Internals;
  // Only render views of our session can hold the widget.
  auto* renderView = qobject_cast<pqRenderView*>(view);
  if (renderView && internals.ProxyManager &&
    renderView->getServer()->session() != internals.ProxyManager->GetSession())
  {
    renderView = nullptr;
  }
  const Kind kind = spec ? kindOf(*spec) : Kind::None;
  const bool wanted = active && renderView && kind != Kind::None;

  if (internals.Proxy && (internals.ProxyKind != kind || internals.View != renderView))
  {
    internals.release();
  }
  if (!wanted)
  {
    if (internals.Proxy && internals.Shown)
    {
      vtkSMPropertyHelper(internals.Proxy, "Visibility").Set(0);
      vtkSMPropertyHelper(internals.Proxy, "Enabled").Set(0);
      internals.Proxy->UpdateVTKObjects();
      internals.Shown = false;
      internals.Interacting = false;
      internals.render();
    }
    return;
  }
  if (!internals.Proxy && !internals.create(kind, renderView, this))
  {
    return;
  }
  if (!internals.Interacting)
  {
    internals.push(*spec);
  }
  vtkSMPropertyHelper(internals.Proxy, "Visibility").Set(1);
  vtkSMPropertyHelper(internals.Proxy, "Enabled").Set(1);
  internals.Proxy->UpdateVTKObjects();
  internals.Shown = true;
  internals.render();
}

//-----------------------------------------------------------------------------
bool pqPiPrimitive3DWidget::readPrimitive(pisurf::PrimitiveSpec& spec) const
{
  vtkSMProxy* widget = this->Internals->Proxy;
  if (!widget)
  {
    return false;
  }
  // The widget proxy announces a move before it fetches the new placement: fetch it.
  widget->UpdatePropertyInformation();
  switch (this->Internals->ProxyKind)
  {
    case Kind::Sphere:
      Get3(widget, "CenterInfo", spec.Center);
      Settle(SizeOf(spec)[0], vtkSMPropertyHelper(widget, "RadiusInfo").GetAsDouble());
      return true;
    case Kind::Box:
    {
      Get3(widget, "PositionInfo", spec.Center);
      Get3(widget, "ScaleInfo", SizeOf(spec));
      // The orientation changes only if the box turned (the angles out of the widget's
      // matrix carry round-off; an untouched rotation keeps its typed axis and angle).
      double current[3], turned[3];
      EulerOf(spec, current);
      vtkSMPropertyHelper(widget, "RotationInfo").Get(turned, 3);
      bool same = true;
      for (int i = 0; i < 3; ++i)
      {
        same =
          same && std::abs(turned[i] - current[i]) <= 1e-9 * std::max(1.0, std::abs(current[i]));
      }
      if (!same)
      {
        double axis[3], angle = 0;
        if (AxisAngleOf(turned, axis, angle))
        {
          spec.Orient = Orientation::Rotation;
          std::copy(axis, axis + 3, spec.RotationAxis);
          spec.RotationAngle = angle;
        }
        else if (spec.Orient == Orientation::Rotation)
        {
          spec.RotationAngle = 0;
        }
      }
      return true;
    }
    case Kind::Handle:
      Get3(widget, "WorldPositionInfo", spec.Center);
      return true;
    default:
      return false;
  }
}

//-----------------------------------------------------------------------------
vtkSMNewWidgetRepresentationProxy* pqPiPrimitive3DWidget::widgetProxy() const
{
  return this->Internals->Proxy;
}

//-----------------------------------------------------------------------------
pqPiPrimitive3DWidget::Kind pqPiPrimitive3DWidget::kind() const
{
  return this->Internals->ProxyKind;
}

//-----------------------------------------------------------------------------
bool pqPiPrimitive3DWidget::isShown() const
{
  return this->Internals->Shown;
}

//-----------------------------------------------------------------------------
bool pqPiPrimitive3DWidget::isInteracting() const
{
  return this->Internals->Interacting;
}

//-----------------------------------------------------------------------------
void pqPiPrimitive3DWidget::onStartInteraction()
{
  this->Internals->Interacting = true;
}

//-----------------------------------------------------------------------------
void pqPiPrimitive3DWidget::onEndInteraction()
{
  this->Internals->Interacting = false;
  Q_EMIT this->endInteraction();
}

//-----------------------------------------------------------------------------
void pqPiPrimitive3DWidget::onViewRemoved(pqView* view)
{
  if (view && view == this->Internals->View)
  {
    this->Internals->release();
  }
}
