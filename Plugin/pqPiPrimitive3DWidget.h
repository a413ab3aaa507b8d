// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class pqPiPrimitive3DWidget
 * @brief the 3D widget of one primitive in a render view: ParaView's sphere, box or handle
 *
 * The primitive editor (pqPiPrimitiveListWidget) places its selected primitive with one
 * of ParaView's interactive widgets, the same widget representation proxies ("3D
 * widgets" of the `representations` group) that the "Pi Primitive" source uses through
 * its PropertyGroups, chosen by the primitive catalogue's widget kind
 * (Filters/Core/PiPrimitiveCatalogue.h):
 * - a sphere kind: SphereWidgetRepresentation, Center and Radius (the WidgetSize);
 * - a box kind of a bounded type (an ellipsoid or a superellipsoid), unrotated or
 *   turned by a rotation: BoxWidgetRepresentation over the reference box [-1, 1]^3,
 *   Position = Center, Scale = Radii (the WidgetSize) and Rotation = the primitive's
 *   rotation as the widget's Euler angles (vtkProp3D's R = Rz Rx Ry); turning the box
 *   sets the primitive's RotationAxis and RotationAngle (orientation Rotation);
 * - any other primitive, or one oriented by an Axis: HandleWidgetRepresentation at its
 *   Center.
 *
 * The widget proxy is created on demand in the session of the edited proxy, added to
 * the view's HiddenRepresentations (not a pipeline representation: no state, no undo),
 * and removed when the view goes away, when the kind changes, or with this object.
 * Dragging fires interaction() and endInteraction(); readPrimitive() then reads the
 * widget's placement back (UpdatePropertyInformation and the *Info properties) into a
 * primitive. show() pushes a primitive into the widget, except while it is being
 * dragged (the widget is then the source of truth).
 *
 * @sa pqPiPrimitiveListWidget, vtkSMNewWidgetRepresentationProxy
 */
#ifndef pqPiPrimitive3DWidget_h
#define pqPiPrimitive3DWidget_h

#include <QObject>
#include <QScopedPointer>

class pqView;
class vtkSMNewWidgetRepresentationProxy;
class vtkSMSessionProxyManager;

namespace pisurf
{
struct PrimitiveSpec;
}

class pqPiPrimitive3DWidget : public QObject
{
  Q_OBJECT
  typedef QObject Superclass;

public:
  /// Which ParaView widget places a primitive.
  enum class Kind
  {
    None,
    Sphere,
    Box,
    Handle
  };

  /// Widget proxies are created with `pxm` (the session of the edited proxy).
  explicit pqPiPrimitive3DWidget(vtkSMSessionProxyManager* pxm, QObject* parent = nullptr);
  ~pqPiPrimitive3DWidget() override;

  /// The widget that places `spec`.
  static Kind kindOf(const pisurf::PrimitiveSpec& spec);
  /// Its representation proxy name ("SphereWidgetRepresentation"...), nullptr for None.
  static const char* proxyName(Kind kind);

  /// Shows `spec` (nullptr: none) in `view` (a render view of the same session, else
  /// none) when `active`; otherwise hides the widget. Creates, replaces or removes the
  /// widget proxy as needed; cheap when nothing changes.
  void show(const pisurf::PrimitiveSpec* spec, pqView* view, bool active);

  /// Copies the widget's current placement into `spec` (the centre, and the radius or
  /// the semi-axes and the rotation); false without a widget.
  bool readPrimitive(pisurf::PrimitiveSpec& spec) const;

  /// The current widget proxy (nullptr when none), its kind, and whether it is shown.
  vtkSMNewWidgetRepresentationProxy* widgetProxy() const;
  Kind kind() const;
  bool isShown() const;

  /// True between the start and the end of a drag.
  bool isInteracting() const;

Q_SIGNALS:
  /// The user moves the widget (many times during a drag).
  void interaction();
  /// The user released the widget.
  void endInteraction();

private Q_SLOTS:
  void onStartInteraction();
  void onEndInteraction();
  void onViewRemoved(pqView* view);

private:
  pqPiPrimitive3DWidget(const pqPiPrimitive3DWidget&) = delete;
  void operator=(const pqPiPrimitive3DWidget&) = delete;

  class pqInternals;
  QScopedPointer<pqInternals> Internals;
};

#endif
