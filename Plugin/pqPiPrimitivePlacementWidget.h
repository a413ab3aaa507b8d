// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class pqPiPrimitivePlacementWidget
 * @brief the "Placement" group of Pi Primitive: ParaView's 3D widget of the current Type
 *
 * A property-group widget (XML `panel_widget="pi_primitive_placement"`) over the
 * geometric properties of the "Pi Primitive" source (Center, Radius, Radii,
 * MajorRadius, Normal, Axis, Orientation and the box widget's reference box). ParaView
 * gives each property to one group only, so one group per primitive type cannot share
 * Center; this widget owns them all and shows, for the Type chosen in the panel (its
 * unchecked value, before Apply), one of ParaView's interactive widgets with the
 * parameters it edits:
 * - Sphere: the sphere widget (Center, Radius);
 * - Cylinder: the cylinder widget (Center, Axis, Radius); Torus: the cylinder through the
 *   tube's centre line (Center, Axis, MajorRadius);
 * - Plane: the plane widget (Center, Normal); Cone: the plane through the apex across
 *   the axis (Center, Axis);
 * - Ellipsoid, Superellipsoid, the hyperboloids and paraboloids: the box widget over
 *   [-1, 1]^3 (Center, Orientation, Radii);
 * - Polynomial: the point handle (Center).
 * The widgets are ParaView's own (created through the registered property-widget
 * interfaces from a property group made here), so Apply, Reset, undo and the view's
 * widget visibility behave as for any ParaView filter.
 *
 * It also checks, as values are typed, the primitive that the panel's values make
 * (vtkPiPrimitive's own validation, the one the source runs): a refused value (a
 * negative radius, an odd exponent, a malformed expression) has its field marked red
 * with the reason as tooltip, before and after Apply, until it is valid again; the
 * source meanwhile keeps its last valid surface.
 */
#ifndef pqPiPrimitivePlacementWidget_h
#define pqPiPrimitivePlacementWidget_h

#include "pqPropertyWidget.h"

#include <QScopedPointer>

class vtkSMPropertyGroup;

class pqPiPrimitivePlacementWidget : public pqPropertyWidget
{
  Q_OBJECT
  typedef pqPropertyWidget Superclass;

public:
  pqPiPrimitivePlacementWidget(
    vtkSMProxy* proxy, vtkSMPropertyGroup* group, QWidget* parent = nullptr);
  ~pqPiPrimitivePlacementWidget() override;

  void apply() override;
  void reset() override;
  void select() override;
  void deselect() override;
  void setView(pqView* view) override;

  /// The widget shown now (nullptr when the type has none).
  pqPropertyWidget* currentWidget() const;

private Q_SLOTS:
  /// The Type (its value in the panel) changed: show that type's widget.
  void updateType();
  /// A value changed: check the panel's values once the event loop is back.
  void scheduleCheck();
  void checkValues();

private:
  Q_DISABLE_COPY(pqPiPrimitivePlacementWidget)
  class pqInternals;
  QScopedPointer<pqInternals> Internals;
};

#endif
