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
 * Name), PiBlending, PiStatus, PiShowModelText, PiModelText and PiApplyModelText.
 *
 * @warning No 3D widget: the selected primitive is placed by typing its parameters (or
 * with the "Pi Primitive" source, which has ParaView's 3D widgets).
 *
 * @sa pisurf::ParseModel, pisurf::WriteModel, vtkPiSurfaceSource
 */
#ifndef pqPiPrimitiveListWidget_h
#define pqPiPrimitiveListWidget_h

#include "pqPropertyWidget.h"

#include <QScopedPointer>
#include <QString>

class QWidget;
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

Q_SIGNALS:
  /// Fired after an accepted edit, with canonical JSON in modelText().
  void modelTextChanged();

public Q_SLOTS: // NOLINT(readability-redundant-access-specifiers)
  /// Shows the model of `text` (from the property). Invalid text is kept as is and
  /// reported; the table then shows the last valid model.
  void setModelText(const QString& text);

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

private:
  pqPiPrimitiveListWidget(const pqPiPrimitiveListWidget&) = delete;
  void operator=(const pqPiPrimitiveListWidget&) = delete;

  class pqInternals;
  QScopedPointer<pqInternals> Internals;
};

#endif
