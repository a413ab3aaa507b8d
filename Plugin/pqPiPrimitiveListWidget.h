// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class pqPiPrimitiveListWidget
 * @brief the primitive editor of the "Pi Surface" source: a table over its Model JSON
 *
 * A pqPropertyWidget for the `Model` string property (XML `panel_widget="pi_primitive_list"`).
 * It shows the model's primitives as a table (a type selector and a summary per row),
 * the parameters of the selected row (the type's own fields, the centre, the
 * orientation, scale and negate), buttons to add, remove, duplicate and reorder rows,
 * the blending r, and the raw JSON text for anything else (name, bounds, parameters).
 *
 * Every edit builds a candidate model, writes it with pisurf::WriteModel and reads it
 * back with pisurf::ParseModel: the core's validation decides (positive radii, even
 * superellipsoid exponents, a parsable expression ...), and the property always holds
 * canonical JSON. A refused edit marks its field red, shows the core's message under
 * the table and in ParaView's output window, and leaves the model as it was. A change
 * of the property from elsewhere (Python, undo, a state file) refreshes the table.
 *
 * Child widgets carry stable object names for GUI tests: PiPrimitiveTable,
 * PiPrimitiveTypeRow<i> (the type selector of row i), PiNewPrimitiveType,
 * PiAddPrimitive, PiRemovePrimitive, PiDuplicatePrimitive, PiMovePrimitiveUp,
 * PiMovePrimitiveDown, PiPrimitiveType (the selected row's type), PiParameter_<Name>
 * for a scalar and PiParameter_<Name>_<i> for a vector component (Name as in the "Pi
 * Primitive" source: Radius, Radii, MajorRadius, MinorRadius, Exponent, Normal, Angle,
 * Expression, Center, Orientation, Axis, RotationAxis, RotationAngle, Scale, Negate,
 * Name), PiShowWidget, PiBlending, PiStatus, PiShowModelText, PiModelText and PiApplyModelText.
 *
 * The selected primitive also gets one of ParaView's 3D widgets in the active render
 * view (pqPiPrimitive3DWidget): a sphere widget for a sphere (centre and radius), a box
 * for an ellipsoid or superellipsoid in the default orientation (centre and semi-axes),
 * a handle at the centre of any other primitive. Dragging it edits the row through the
 * same validation as typing (InteractionEvent and EndInteractionEvent), and a typed edit,
 * a new selection or a change of the property moves the widget. The widget shows while
 * the panel is selected (pqPropertyWidget::select/deselect), a render view is the panel's
 * view and the "Show 3D widget" checkbox (PiShowWidget) is on; it leaves the view when
 * the view goes away. Like the editor's other edits, a drag changes the Model on Apply
 * (at once with auto-apply).
 *
 * @warning The widgets place the centre and the radius or semi-axes only; orientation,
 * a torus's radii, a cone's angle and the rest are typed. A rotated ellipsoid gets the
 * handle (ParaView's box widget would show an axis-aligned box).
 *
 * @sa pisurf::ParseModel, pisurf::WriteModel, vtkPiSurfaceSource
 */
#ifndef pqPiPrimitiveListWidget_h
#define pqPiPrimitiveListWidget_h

#include "pqPropertyWidget.h"

#include <QScopedPointer>
#include <QString>

class QWidget;
class pqView;
class vtkSMProperty;
class vtkSMProxy;

class pqPiPrimitiveListWidget : public pqPropertyWidget
{
  Q_OBJECT
  Q_PROPERTY(QString modelText READ modelText WRITE setModelText NOTIFY modelTextChanged)
  typedef pqPropertyWidget Superclass;

public:
  pqPiPrimitiveListWidget(vtkSMProxy* proxy, vtkSMProperty* property, QWidget* parent = nullptr);
  ~pqPiPrimitiveListWidget() override;

  /// The model as JSON text: what the property holds.
  QString modelText() const;

  void updateWidget(bool showingAdvancedProperties) override;

  ///@{
  /// The panel is shown or hidden: the 3D widget shows or hides with it.
  void select() override;
  void deselect() override;
  ///@}

Q_SIGNALS:
  /// Fired after an accepted edit, with canonical JSON in modelText().
  void modelTextChanged();

public Q_SLOTS: // NOLINT(readability-redundant-access-specifiers)
  /// Shows the model of `text` (from the property). Invalid text is kept as is and
  /// reported; the table then shows the last valid model.
  void setModelText(const QString& text);

  /// The view that gets the 3D widget (the panel's active view).
  void setView(pqView* view) override;

private Q_SLOTS:
  void onCurrentRowChanged();
  void onRowTypeChanged(int index);
  void onSelectedTypeChanged(int index);
  void onFieldEdited();
  void onNegateToggled(bool checked);
  void onOrientationChanged(int index);
  void onBlendingEdited();
  void addPrimitive();
  void removePrimitive();
  void duplicatePrimitive();
  void movePrimitiveUp();
  void movePrimitiveDown();
  void applyModelText();
  void onWidgetMoved();

private:
  pqPiPrimitiveListWidget(const pqPiPrimitiveListWidget&) = delete;
  void operator=(const pqPiPrimitiveListWidget&) = delete;

  class pqInternals;
  QScopedPointer<pqInternals> Internals;
};

#endif
