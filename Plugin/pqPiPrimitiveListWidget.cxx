// SPDX-License-Identifier: BSD-3-Clause
#include "pqPiPrimitiveListWidget.h"

#include "PiModel.h"
#include "PiPrimitiveCatalogue.h"
#include "pqPiPrimitive3DWidget.h"

#include "pqView.h"
#include "vtkSMProperty.h"
#include "vtkSMProxy.h"
#include "vtkSetGet.h"

#include <QCheckBox>
#include <QComboBox>
#include <QFormLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QLabel>
#include <QLineEdit>
#include <QLocale>
#include <QPlainTextEdit>
#include <QPointer>
#include <QPushButton>
#include <QSignalBlocker>
#include <QStringList>
#include <QTableWidget>
#include <QToolButton>
#include <QVBoxLayout>

#include <string>
#include <vector>

namespace
{
using pisurf::Orientation;
using pisurf::PrimitiveSpec;
using pisurf::PrimitiveType;

// The style of a refused field.
const char* const RefusedStyle = "QLineEdit { background-color: #f6c4c4; }";

using Kind = pisurf::ParameterKind;

// One editable parameter of a primitive: the "Pi Primitive" property name, its label
// with units, and how many components.
struct Field
{
  const char* Name;
  QString Label;
  const char* Tip;
  Kind Type;
  int Count;
};

const Field NameField = { "Name", "Name", "Optional name of the primitive.", Kind::Text, 1 };
const Field CenterField = { "Center", "Center (x, y, z)", "Position of the primitive.",
  Kind::Number, 3 };
const Field AxisField = { "Axis", "Axis (x, y, z)",
  "Direction of the primitive's local w axis (need not be unit, not zero).", Kind::Number, 3 };
const Field RotationAxisField = { "RotationAxis", "Rotation axis (x, y, z)",
  "Axis of the rotation (not zero).", Kind::Number, 3 };
const Field RotationAngleField = { "RotationAngle", "Rotation angle (degrees)",
  "Right-handed rotation about the rotation axis, in degrees.", Kind::Number, 1 };
const Field ScaleField = { "Scale", "Scale (factor)",
  "The primitive's polynomial is multiplied by this non-zero number.", Kind::Number, 1 };

// The label of a catalogue parameter: "Radius R (length)".
QString LabelOf(const pisurf::ParameterInfo& p)
{
  const QString label = QString::fromUtf8(p.Label);
  return *p.Unit ? QString("%1 (%2)").arg(label, QString::fromUtf8(p.Unit)) : label;
}

// The type's own parameters, from the catalogue.
std::vector<Field> ShapeFields(PrimitiveType t)
{
  std::vector<Field> fields;
  for (const pisurf::ParameterInfo& p : pisurf::CatalogueEntry(t).Parameters)
  {
    fields.push_back({ p.Property, LabelOf(p), p.Tooltip, p.Kind, p.Count });
  }
  return fields;
}

// The catalogue parameter stored under this property name (by any type), or nullptr.
const pisurf::ParameterInfo* ShapeParameter(const QString& name)
{
  const std::string property = name.toStdString();
  for (const pisurf::PrimitiveInfo& entry : pisurf::PrimitiveCatalogue())
  {
    if (const pisurf::ParameterInfo* p = pisurf::FindParameter(entry, property))
    {
      return p;
    }
  }
  return nullptr;
}

// The storage of a numeric field in a spec: the frame's, or a catalogue parameter's.
double* Slot(PrimitiveSpec& s, const QString& name)
{
  if (name == "Center")
    return s.Center;
  if (name == "Axis")
    return s.Axis;
  if (name == "RotationAxis")
    return s.RotationAxis;
  if (name == "RotationAngle")
    return &s.RotationAngle;
  if (name == "Scale")
    return &s.Scale;
  const pisurf::ParameterInfo* p = ShapeParameter(name);
  return p && p->Kind == Kind::Number ? p->Numbers(s) : nullptr;
}

QString Number(double v)
{
  return QString::number(v, 'g', QLocale::FloatingPointShortest);
}

QString FieldText(const PrimitiveSpec& spec, const QString& name, int component)
{
  PrimitiveSpec& s = const_cast<PrimitiveSpec&>(spec); // the accessors only read here
  if (name == "Name")
    return QString::fromStdString(s.Name);
  const pisurf::ParameterInfo* p = ShapeParameter(name);
  if (p && p->Kind == Kind::Text)
    return QString::fromStdString(*p->Text(s));
  if (p && p->Kind == Kind::Integer)
    return QString::number(*p->Integer(s));
  double* slot = Slot(s, name);
  return slot ? Number(slot[component]) : QString();
}

// Sets one field from text; false with a message when the text is not a number.
bool SetField(
  PrimitiveSpec& s, const QString& name, int component, const QString& text, QString& error)
{
  if (name == "Name")
  {
    s.Name = text.trimmed().toStdString();
    return true;
  }
  const pisurf::ParameterInfo* p = ShapeParameter(name);
  if (p && p->Kind == Kind::Text)
  {
    *p->Text(s) = text.toStdString();
    return true;
  }
  bool ok = false;
  const QString t = text.trimmed();
  if (p && p->Kind == Kind::Integer)
  {
    const int n = t.toInt(&ok);
    if (!ok)
    {
      error = QString("%1: '%2' is not an integer").arg(name, text);
      return false;
    }
    *p->Integer(s) = n;
    return true;
  }
  const double v = QLocale::c().toDouble(t, &ok);
  double* slot = Slot(s, name);
  if (!ok || !slot)
  {
    error = QString("%1: '%2' is not a number").arg(name, text);
    return false;
  }
  slot[component] = v;
  return true;
}

QString Triple(const double v[3])
{
  return QString("(%1, %2, %3)").arg(Number(v[0]), Number(v[1]), Number(v[2]));
}

// The table's one-line description of a primitive: its parameters by their symbols
// ("a, b, c = 1, 1, 1, n = 4", "θ = 30°"; an expression as written).
QString Summary(const PrimitiveSpec& spec)
{
  PrimitiveSpec& s = const_cast<PrimitiveSpec&>(spec); // the accessors only read here
  QStringList parts;
  for (const pisurf::ParameterInfo& p : pisurf::CatalogueEntry(s.Type).Parameters)
  {
    if (p.Kind == Kind::Text)
    {
      parts << QString::fromStdString(*p.Text(s));
      continue;
    }
    const QStringList symbols = QString::fromUtf8(p.Symbol).split(' ');
    QString value;
    if (p.Kind == Kind::Integer)
    {
      value = QString::number(*p.Integer(s));
    }
    else
    {
      QStringList values;
      for (int i = 0; i < p.Count; ++i)
        values << Number(p.Numbers(s)[i]);
      value = values.join(", ");
      // One symbol for several components: a vector, in parentheses.
      if (p.Count > 1 && symbols.size() == 1)
        value = QString("(%1)").arg(value);
    }
    const QString unit = std::string(p.Unit) == "degrees" ? QString("°") : QString();
    parts << QString("%1 = %2%3").arg(symbols.mid(0, p.Count).join(", "), value, unit);
  }
  const QString shape = parts.join(", ");
  QString text = QString("%1 at %2").arg(shape, Triple(s.Center));
  if (s.Scale != 1.0)
    text += QString(", \u00d7%1").arg(Number(s.Scale));
  if (s.Negate)
    text += ", negated";
  if (!s.Name.empty())
    text = QString::fromStdString(s.Name) + ": " + text;
  return text;
}

QComboBox* NewTypeCombo(QWidget* parent)
{
  auto* combo = new QComboBox(parent);
  // Narrow docks: the combo may be shorter than its longest entry.
  combo->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  combo->setMinimumContentsLength(8);
  for (const pisurf::PrimitiveInfo& entry : pisurf::PrimitiveCatalogue())
  {
    combo->addItem(entry.Label, static_cast<int>(entry.Type));
  }
  return combo;
}

// A primitive changed to type `t`: a text parameter it needs (a polynomial's
// expression) starts at its default when empty.
void ChangeType(PrimitiveSpec& s, PrimitiveType t)
{
  s.Type = t;
  for (const pisurf::ParameterInfo& p : pisurf::CatalogueEntry(t).Parameters)
  {
    if (p.Kind == Kind::Text && p.Text(s)->empty())
      pisurf::SetDefault(s, p);
  }
}
}

//-----------------------------------------------------------------------------
class pqPiPrimitiveListWidget::pqInternals
{
public:
  explicit pqInternals(pqPiPrimitiveListWidget* self)
    : Self(self)
  {
  }

  pqPiPrimitiveListWidget* Self;
  pisurf::Model Model; // the last valid model
  QString Text;        // the property's text (canonical after our own edits)
  int Row = -1;        // the selected primitive

  QTableWidget* Table = nullptr;
  QComboBox* NewType = nullptr;
  QPushButton* Remove = nullptr;
  QPushButton* Duplicate = nullptr;
  QPushButton* Up = nullptr;
  QPushButton* Down = nullptr;
  QCheckBox* ShowWidget = nullptr;
  pqPiPrimitive3DWidget* Widget3D = nullptr; // the selected row's widget in the view
  QLabel* ParametersTitle = nullptr;
  QVBoxLayout* ParametersLayout = nullptr;
  QPointer<QWidget> Parameters; // the selected row's fields, rebuilt with the row
  QLineEdit* Blending = nullptr;
  QLabel* Status = nullptr;
  QToolButton* ShowText = nullptr;
  QPlainTextEdit* ModelText = nullptr;
  QPushButton* ApplyText = nullptr;

  int count() const { return static_cast<int>(this->Model.Primitives.size()); }

  void clampRow()
  {
    if (this->Row >= this->count())
      this->Row = this->count() - 1;
    if (this->Row < 0 && this->count() > 0)
      this->Row = 0;
  }

  /// Validates `candidate` through the core (write, then strict read). Accepted: it
  /// becomes the model, the property gets its canonical text, true. Refused: `culprit`
  /// turns red, the message goes under the table and to the output window, false.
  bool commit(const pisurf::Model& candidate, int row, QWidget* culprit)
  {
    const std::string text = pisurf::WriteModel(candidate);
    pisurf::Model parsed;
    std::string error;
    if (!pisurf::ParseModel(text, parsed, error))
    {
      this->refuse(QString::fromStdString(error), culprit);
      return false;
    }
    this->Model = parsed;
    this->Text = QString::fromStdString(text);
    this->Row = row;
    this->clampRow();
    this->Status->hide();
    this->refresh();
    Q_EMIT this->Self->modelTextChanged();
    return true;
  }

  void refuse(const QString& message, QWidget* culprit)
  {
    if (culprit)
    {
      culprit->setStyleSheet(RefusedStyle);
      culprit->setToolTip(message);
    }
    this->Status->setText(
      QObject::tr("Refused: %1. The model keeps its last valid value.").arg(message));
    this->Status->show();
    vtkGenericWarningMacro(
      "Pi Surface editor: refused " << message.toStdString() << "; the model is unchanged.");
  }

  /// The table, the selected row's parameters, r and the JSON, from the model.
  void refresh()
  {
    {
      const QSignalBlocker blocker(this->Table);
      this->Table->setRowCount(this->count());
      for (int i = 0; i < this->count(); ++i)
      {
        const PrimitiveSpec& s = this->Model.Primitives[i];
        auto* combo = qobject_cast<QComboBox*>(this->Table->cellWidget(i, 0));
        if (!combo)
        {
          combo = NewTypeCombo(this->Table);
          combo->setProperty("piRow", i);
          QObject::connect(combo, QOverload<int>::of(&QComboBox::currentIndexChanged), this->Self,
            &pqPiPrimitiveListWidget::onRowTypeChanged);
          this->Table->setCellWidget(i, 0, combo);
        }
        combo->setObjectName(QString("PiPrimitiveTypeRow%1").arg(i));
        {
          const QSignalBlocker comboBlocker(combo);
          combo->setCurrentIndex(static_cast<int>(s.Type));
        }
        auto* item = this->Table->item(i, 1);
        if (!item)
        {
          item = new QTableWidgetItem();
          this->Table->setItem(i, 1, item);
        }
        item->setText(Summary(s));
        item->setToolTip(Summary(s));
      }
      if (this->Row >= 0)
        this->Table->selectRow(this->Row);
      else
        this->Table->clearSelection();
    }
    this->Remove->setEnabled(this->Row >= 0);
    this->Duplicate->setEnabled(this->Row >= 0);
    this->Up->setEnabled(this->Row > 0);
    this->Down->setEnabled(this->Row >= 0 && this->Row + 1 < this->count());
    this->Blending->setText(Number(this->Model.Blending));
    this->Blending->setStyleSheet(QString());
    this->Blending->setToolTip(QString());
    this->ModelText->setPlainText(this->Text);
    this->rebuildParameters();
    this->syncWidget();
  }

  /// The 3D widget follows the selected row, the view, the panel and the checkbox.
  void syncWidget()
  {
    const PrimitiveSpec* spec = this->Row >= 0 ? &this->Model.Primitives[this->Row] : nullptr;
    this->Widget3D->show(
      spec, this->Self->view(), this->Self->isSelected() && this->ShowWidget->isChecked());
  }

  /// Takes the widget's placement into the selected row (validated like any edit). A
  /// refused placement (a zero radius) snaps the widget back to the row.
  void takeWidgetPlacement()
  {
    if (this->Row < 0)
    {
      return;
    }
    pisurf::Model candidate = this->Model;
    if (!this->Widget3D->readPrimitive(candidate.Primitives[this->Row]))
    {
      return;
    }
    if (pisurf::WriteModel(candidate) == this->Text.toStdString())
    {
      return;
    }
    if (!this->commit(candidate, this->Row, nullptr) && !this->Widget3D->isInteracting())
    {
      this->syncWidget();
    }
  }

  /// A new parameter panel for the selected row (the fields differ between types).
  void rebuildParameters()
  {
    if (this->Parameters)
    {
      // Out of the tree at once (tests look children up by name), deleted later because
      // the edit that caused this may be one of its fields.
      this->Parameters->hide();
      this->Parameters->setParent(nullptr);
      this->Parameters->deleteLater();
    }
    if (this->Row < 0)
    {
      this->ParametersTitle->setText(QObject::tr("No primitive: add one."));
      return;
    }
    const PrimitiveSpec& spec = this->Model.Primitives[this->Row];
    this->ParametersTitle->setText(
      QObject::tr("Primitive %1: %2").arg(this->Row + 1).arg(pisurf::TypeLabel(spec.Type)));
    pqPiPrimitiveListWidget* self = this->Self;
    auto* panel = new QWidget(self);
    panel->setObjectName("PiParameters");
    auto* form = new QFormLayout(panel);
    form->setContentsMargins(0, 0, 0, 0);
    form->setRowWrapPolicy(QFormLayout::WrapLongRows);

    QComboBox* type = NewTypeCombo(panel);
    type->setObjectName("PiPrimitiveType");
    type->setCurrentIndex(static_cast<int>(spec.Type));
    type->setToolTip(QObject::tr("The type of the selected primitive."));
    QObject::connect(type, QOverload<int>::of(&QComboBox::currentIndexChanged), self,
      &pqPiPrimitiveListWidget::onSelectedTypeChanged);
    form->addRow(QObject::tr("Type"), type);

    auto newEdit = [&](QWidget* parent, const Field& f, int i)
    {
      auto* edit = new QLineEdit(parent);
      edit->setObjectName(f.Count == 1 ? QString("PiParameter_%1").arg(f.Name)
                                       : QString("PiParameter_%1_%2").arg(f.Name).arg(i));
      edit->setProperty("piField", f.Name);
      edit->setProperty("piComponent", i);
      edit->setMinimumWidth(30);
      edit->setText(FieldText(spec, f.Name, i));
      edit->setToolTip(QObject::tr(f.Tip));
      QObject::connect(
        edit, &QLineEdit::editingFinished, self, &pqPiPrimitiveListWidget::onFieldEdited);
      return edit;
    };
    auto addField = [&](const Field& f)
    {
      if (f.Count == 1)
      {
        form->addRow(QObject::tr(f.Label.toUtf8().constData()), newEdit(panel, f, 0));
        return;
      }
      auto* editor = new QWidget(panel);
      auto* row = new QHBoxLayout(editor);
      row->setContentsMargins(0, 0, 0, 0);
      for (int i = 0; i < f.Count; ++i)
        row->addWidget(newEdit(editor, f, i));
      form->addRow(QObject::tr(f.Label.toUtf8().constData()), editor);
    };

    for (const Field& f : ShapeFields(spec.Type))
      addField(f);
    addField(CenterField);

    auto* orientation = new QComboBox(panel);
    orientation->setObjectName("PiParameter_Orientation");
    orientation->addItems(
      { QObject::tr("Default (w along +z)"), QObject::tr("Axis"), QObject::tr("Rotation") });
    orientation->setCurrentIndex(static_cast<int>(spec.Orient));
    orientation->setToolTip(QObject::tr("How the primitive's local axes turn: not at all, w "
                                        "along a given axis, or by a rotation."));
    QObject::connect(orientation, QOverload<int>::of(&QComboBox::currentIndexChanged), self,
      &pqPiPrimitiveListWidget::onOrientationChanged);
    form->addRow(QObject::tr("Orientation"), orientation);
    if (spec.Orient == Orientation::Axis)
    {
      addField(AxisField);
    }
    else if (spec.Orient == Orientation::Rotation)
    {
      addField(RotationAxisField);
      addField(RotationAngleField);
    }
    addField(ScaleField);

    auto* negate = new QCheckBox(QObject::tr("Negate (a bump becomes a dent)"), panel);
    negate->setObjectName("PiParameter_Negate");
    negate->setChecked(spec.Negate);
    negate->setToolTip(QObject::tr("Multiply the primitive by \u22121."));
    QObject::connect(negate, &QCheckBox::toggled, self, &pqPiPrimitiveListWidget::onNegateToggled);
    form->addRow(QString(), negate);
    addField(NameField);

    this->ParametersLayout->addWidget(panel);
    this->Parameters = panel;
  }
};

//-----------------------------------------------------------------------------
pqPiPrimitiveListWidget::pqPiPrimitiveListWidget(
  vtkSMProxy* smproxy, vtkSMProperty* smproperty, QWidget* parentObject)
  : Superclass(smproxy, parentObject)
  , Internals(new pqInternals(this))
{
  this->setProperty(smproperty);
  this->setShowLabel(false);
  this->setChangeAvailableAsChangeFinished(true);
  pqInternals& internals = *this->Internals;

  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);

  internals.Table = new QTableWidget(0, 2, this);
  internals.Table->setObjectName("PiPrimitiveTable");
  internals.Table->setHorizontalHeaderLabels({ tr("Type"), tr("Primitive") });
  internals.Table->horizontalHeader()->setStretchLastSection(true);
  internals.Table->horizontalHeader()->setSectionResizeMode(0, QHeaderView::ResizeToContents);
  internals.Table->setSelectionBehavior(QAbstractItemView::SelectRows);
  internals.Table->setSelectionMode(QAbstractItemView::SingleSelection);
  internals.Table->setEditTriggers(QAbstractItemView::NoEditTriggers);
  internals.Table->setMinimumHeight(130);
  internals.Table->setToolTip(tr("The primitives f_i of F = \u03a0 f_i \u2212 r, in order."));
  layout->addWidget(internals.Table);
  QObject::connect(internals.Table, &QTableWidget::itemSelectionChanged, this,
    &pqPiPrimitiveListWidget::onCurrentRowChanged);

  // Two short rows, so the editor fits the narrow Properties dock.
  auto* adding = new QHBoxLayout();
  internals.NewType = NewTypeCombo(this);
  internals.NewType->setObjectName("PiNewPrimitiveType");
  internals.NewType->setToolTip(tr("The type of the primitive that Add appends."));
  adding->addWidget(internals.NewType, 1);
  auto* buttons = new QHBoxLayout();
  QHBoxLayout* row = adding;
  auto button = [this, &row](const char* name, const QString& text, const QString& tip)
  {
    auto* b = new QPushButton(text, this);
    b->setObjectName(name);
    b->setToolTip(tip);
    b->setMinimumWidth(0);
    row->addWidget(b);
    return b;
  };
  QObject::connect(
    button("PiAddPrimitive", tr("Add"), tr("Append a primitive of the type on the left")),
    &QPushButton::clicked, this, &pqPiPrimitiveListWidget::addPrimitive);
  layout->addLayout(adding);
  row = buttons;
  internals.Remove = button("PiRemovePrimitive", tr("Remove"), tr("Remove the selected primitive"));
  QObject::connect(
    internals.Remove, &QPushButton::clicked, this, &pqPiPrimitiveListWidget::removePrimitive);
  internals.Duplicate =
    button("PiDuplicatePrimitive", tr("Duplicate"), tr("Insert a copy of the selected primitive"));
  QObject::connect(
    internals.Duplicate, &QPushButton::clicked, this, &pqPiPrimitiveListWidget::duplicatePrimitive);
  internals.Up = button("PiMovePrimitiveUp", tr("Up \u2191"), tr("Move the selected primitive up"));
  QObject::connect(
    internals.Up, &QPushButton::clicked, this, &pqPiPrimitiveListWidget::movePrimitiveUp);
  internals.Down =
    button("PiMovePrimitiveDown", tr("Down \u2193"), tr("Move the selected primitive down"));
  QObject::connect(
    internals.Down, &QPushButton::clicked, this, &pqPiPrimitiveListWidget::movePrimitiveDown);
  layout->addLayout(buttons);

  internals.ShowWidget = new QCheckBox(tr("Show 3D widget"), this);
  internals.ShowWidget->setObjectName("PiShowWidget");
  internals.ShowWidget->setChecked(true);
  internals.ShowWidget->setToolTip(
    tr("Place the selected primitive in the render view: a sphere widget for a sphere, a "
       "box for an ellipsoid or superellipsoid (its semi-axes), a handle at the centre of "
       "any other primitive. Dragging it edits the row."));
  layout->addWidget(internals.ShowWidget);
  internals.Widget3D = new pqPiPrimitive3DWidget(smproxy->GetSessionProxyManager(), this);
  QObject::connect(
    internals.ShowWidget, &QCheckBox::toggled, this, [this]() { this->Internals->syncWidget(); });
  QObject::connect(internals.Widget3D, &pqPiPrimitive3DWidget::interaction, this,
    &pqPiPrimitiveListWidget::onWidgetMoved);
  QObject::connect(internals.Widget3D, &pqPiPrimitive3DWidget::endInteraction, this,
    &pqPiPrimitiveListWidget::onWidgetMoved);

  internals.ParametersTitle = new QLabel(this);
  internals.ParametersTitle->setObjectName("PiParametersTitle");
  QFont bold = internals.ParametersTitle->font();
  bold.setBold(true);
  internals.ParametersTitle->setFont(bold);
  layout->addWidget(internals.ParametersTitle);
  internals.ParametersLayout = new QVBoxLayout();
  layout->addLayout(internals.ParametersLayout);

  auto* blending = new QFormLayout();
  internals.Blending = new QLineEdit(this);
  internals.Blending->setObjectName("PiBlending");
  blending->addRow(tr("Model blending r"), internals.Blending);
  blending->labelForField(internals.Blending)
    ->setToolTip(tr("The blending parameter r of F = \u03a0 f_i \u2212 r: 0 is the union of "
                    "the primitives' surfaces, larger r inflates and blends them."));
  layout->addLayout(blending);
  QObject::connect(internals.Blending, &QLineEdit::editingFinished, this,
    &pqPiPrimitiveListWidget::onBlendingEdited);

  internals.Status = new QLabel(this);
  internals.Status->setObjectName("PiStatus");
  internals.Status->setWordWrap(true);
  internals.Status->setStyleSheet("QLabel { color: #c00000; }");
  internals.Status->hide();
  layout->addWidget(internals.Status);

  internals.ShowText = new QToolButton(this);
  internals.ShowText->setObjectName("PiShowModelText");
  internals.ShowText->setText(tr("Model JSON"));
  internals.ShowText->setCheckable(true);
  internals.ShowText->setToolButtonStyle(Qt::ToolButtonTextBesideIcon);
  internals.ShowText->setArrowType(Qt::RightArrow);
  internals.ShowText->setAutoRaise(true);
  internals.ShowText->setToolTip(
    tr("The whole model as .pisurf JSON: name, description, bounds and parameters too."));
  layout->addWidget(internals.ShowText);
  internals.ModelText = new QPlainTextEdit(this);
  internals.ModelText->setObjectName("PiModelText");
  internals.ModelText->setMinimumHeight(160);
  QFont mono("Monospace");
  mono.setStyleHint(QFont::TypeWriter);
  internals.ModelText->setFont(mono);
  internals.ModelText->hide();
  layout->addWidget(internals.ModelText);
  internals.ApplyText = new QPushButton(tr("Use this JSON"), this);
  internals.ApplyText->setObjectName("PiApplyModelText");
  internals.ApplyText->setToolTip(tr("Read the text above as the model (validated first)"));
  internals.ApplyText->hide();
  layout->addWidget(internals.ApplyText);
  QObject::connect(internals.ShowText, &QToolButton::toggled, this,
    [this](bool on)
    {
      this->Internals->ShowText->setArrowType(on ? Qt::DownArrow : Qt::RightArrow);
      this->Internals->ModelText->setVisible(on);
      this->Internals->ApplyText->setVisible(on);
    });
  QObject::connect(
    internals.ApplyText, &QPushButton::clicked, this, &pqPiPrimitiveListWidget::applyModelText);

  internals.refresh();
  // The property's text, both ways (unchecked until Apply, like every panel widget).
  this->addPropertyLink(this, "modelText", SIGNAL(modelTextChanged()), smproperty);
}

//-----------------------------------------------------------------------------
pqPiPrimitiveListWidget::~pqPiPrimitiveListWidget() = default;

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::select()
{
  this->Superclass::select();
  this->Internals->syncWidget();
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::deselect()
{
  this->Superclass::deselect();
  this->Internals->syncWidget();
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::setView(pqView* view)
{
  this->Superclass::setView(view);
  this->Internals->syncWidget();
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::onWidgetMoved()
{
  this->Internals->takeWidgetPlacement();
}

//-----------------------------------------------------------------------------
QString pqPiPrimitiveListWidget::modelText() const
{
  return this->Internals->Text;
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::updateWidget(bool showingAdvancedProperties)
{
  // The raw JSON opens by itself in the advanced view.
  if (showingAdvancedProperties && !this->Internals->ShowText->isChecked())
  {
    this->Internals->ShowText->setChecked(true);
  }
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::setModelText(const QString& text)
{
  pqInternals& internals = *this->Internals;
  if (text == internals.Text)
  {
    return;
  }
  internals.Text = text;
  pisurf::Model model;
  std::string error;
  const bool valid = pisurf::ParseModel(text.toStdString(), model, error);
  if (valid)
  {
    internals.Model = model;
  }
  internals.clampRow();
  internals.refresh();
  internals.Status->setVisible(!valid);
  if (!valid)
  {
    internals.Status->setText(
      tr("The Model property is not a valid model (%1); the table shows the last valid one.")
        .arg(QString::fromStdString(error)));
  }
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::onCurrentRowChanged()
{
  pqInternals& internals = *this->Internals;
  const QModelIndexList rows = internals.Table->selectionModel()->selectedRows();
  const int row = rows.isEmpty() ? -1 : rows.first().row();
  if (row == internals.Row || row < 0)
  {
    return;
  }
  internals.Row = row;
  internals.refresh();
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::onRowTypeChanged(int index)
{
  pqInternals& internals = *this->Internals;
  auto* combo = qobject_cast<QComboBox*>(this->sender());
  if (!combo)
  {
    return;
  }
  const int row = combo->property("piRow").toInt();
  if (row < 0 || row >= internals.count())
  {
    return;
  }
  pisurf::Model candidate = internals.Model;
  PrimitiveSpec& spec = candidate.Primitives[row];
  ChangeType(spec, static_cast<PrimitiveType>(index));
  if (!internals.commit(candidate, row, combo))
  {
    internals.refresh();
  }
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::onSelectedTypeChanged(int index)
{
  pqInternals& internals = *this->Internals;
  if (internals.Row < 0)
  {
    return;
  }
  pisurf::Model candidate = internals.Model;
  PrimitiveSpec& spec = candidate.Primitives[internals.Row];
  ChangeType(spec, static_cast<PrimitiveType>(index));
  internals.commit(candidate, internals.Row, qobject_cast<QWidget*>(this->sender()));
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::onFieldEdited()
{
  pqInternals& internals = *this->Internals;
  auto* edit = qobject_cast<QLineEdit*>(this->sender());
  // editingFinished also fires when focus merely leaves an unchanged field.
  if (!edit || !edit->isModified() || internals.Row < 0)
  {
    return;
  }
  edit->setModified(false);
  pisurf::Model candidate = internals.Model;
  QString error;
  if (!SetField(candidate.Primitives[internals.Row], edit->property("piField").toString(),
        edit->property("piComponent").toInt(), edit->text(), error))
  {
    internals.refuse(error, edit);
    return;
  }
  internals.commit(candidate, internals.Row, edit);
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::onNegateToggled(bool checked)
{
  pqInternals& internals = *this->Internals;
  if (internals.Row < 0)
  {
    return;
  }
  pisurf::Model candidate = internals.Model;
  candidate.Primitives[internals.Row].Negate = checked;
  internals.commit(candidate, internals.Row, qobject_cast<QWidget*>(this->sender()));
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::onOrientationChanged(int index)
{
  pqInternals& internals = *this->Internals;
  if (internals.Row < 0)
  {
    return;
  }
  pisurf::Model candidate = internals.Model;
  candidate.Primitives[internals.Row].Orient = static_cast<Orientation>(index);
  internals.commit(candidate, internals.Row, qobject_cast<QWidget*>(this->sender()));
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::onBlendingEdited()
{
  pqInternals& internals = *this->Internals;
  QLineEdit* edit = internals.Blending;
  if (!edit->isModified())
  {
    return;
  }
  edit->setModified(false);
  bool ok = false;
  const double r = QLocale::c().toDouble(edit->text().trimmed(), &ok);
  if (!ok)
  {
    internals.refuse(tr("blending: '%1' is not a number").arg(edit->text()), edit);
    return;
  }
  pisurf::Model candidate = internals.Model;
  candidate.Blending = r;
  internals.commit(candidate, internals.Row, edit);
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::addPrimitive()
{
  pqInternals& internals = *this->Internals;
  pisurf::Model candidate = internals.Model;
  candidate.Primitives.push_back(
    pisurf::DefaultPrimitive(static_cast<PrimitiveType>(internals.NewType->currentIndex())));
  internals.commit(candidate, internals.count(), internals.NewType);
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::removePrimitive()
{
  pqInternals& internals = *this->Internals;
  if (internals.Row < 0)
  {
    return;
  }
  pisurf::Model candidate = internals.Model;
  candidate.Primitives.erase(candidate.Primitives.begin() + internals.Row);
  internals.commit(candidate, internals.Row, nullptr);
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::duplicatePrimitive()
{
  pqInternals& internals = *this->Internals;
  if (internals.Row < 0)
  {
    return;
  }
  pisurf::Model candidate = internals.Model;
  candidate.Primitives.insert(
    candidate.Primitives.begin() + internals.Row + 1, candidate.Primitives[internals.Row]);
  internals.commit(candidate, internals.Row + 1, nullptr);
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::movePrimitiveUp()
{
  pqInternals& internals = *this->Internals;
  if (internals.Row < 1)
  {
    return;
  }
  pisurf::Model candidate = internals.Model;
  std::swap(candidate.Primitives[internals.Row - 1], candidate.Primitives[internals.Row]);
  internals.commit(candidate, internals.Row - 1, nullptr);
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::movePrimitiveDown()
{
  pqInternals& internals = *this->Internals;
  if (internals.Row < 0 || internals.Row + 1 >= internals.count())
  {
    return;
  }
  pisurf::Model candidate = internals.Model;
  std::swap(candidate.Primitives[internals.Row], candidate.Primitives[internals.Row + 1]);
  internals.commit(candidate, internals.Row + 1, nullptr);
}

//-----------------------------------------------------------------------------
void pqPiPrimitiveListWidget::applyModelText()
{
  pqInternals& internals = *this->Internals;
  pisurf::Model parsed;
  std::string error;
  if (!pisurf::ParseModel(internals.ModelText->toPlainText().toStdString(), parsed, error))
  {
    internals.ModelText->setStyleSheet("QPlainTextEdit { background-color: #f6c4c4; }");
    internals.refuse(QString::fromStdString(error), nullptr);
    return;
  }
  internals.ModelText->setStyleSheet(QString());
  internals.commit(parsed, internals.Row, nullptr);
}
