// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiPrimitive.h"

#include "PiPrimitiveCatalogue.h"
#include "PiPrimitiveSpec.h"

#include "vtkDoubleArray.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <mutex>

vtkStandardNewMacro(vtkPiPrimitive);

struct vtkPiPrimitive::vtkInternals
{
  std::string Expression;
  std::string Name;
  pisurf::ParameterMap Parameters;

  std::atomic<bool> Dirty{ true };
  std::mutex BuildMutex;
  std::shared_ptr<const pisurf::PolynomialFactor> Factor; // last valid
  bool Valid = false;
  std::string Error;
};

vtkPiPrimitive::vtkPiPrimitive()
  : Internals(new vtkInternals)
{
  // Every type's numeric parameters at their catalogue defaults. The Expression starts
  // empty, as the XML's: a Polynomial needs one typed (the editor starts a new one at
  // the catalogue's default).
  pisurf::PrimitiveSpec defaults;
  for (const pisurf::PrimitiveInfo& entry : pisurf::PrimitiveCatalogue())
  {
    for (const pisurf::ParameterInfo& parameter : entry.Parameters)
    {
      if (parameter.Kind != pisurf::ParameterKind::Text)
      {
        pisurf::SetDefault(defaults, parameter);
      }
    }
  }
  this->SetSpec(defaults);
}

vtkPiPrimitive::~vtkPiPrimitive() = default;

void vtkPiPrimitive::Modified()
{
  if (this->Internals)
  {
    this->Internals->Dirty = true;
  }
  this->Superclass::Modified();
}

namespace
{
// Turns `s` by the Euler angles `euler` (degrees, R = Rz·Rx·Ry as vtkProp3D) after its
// own orientation: the composed rotation as one axis and angle. A spec whose own
// orientation is invalid is left alone (its build reports it).
void ComposeOrientation(const double euler[3], pisurf::PrimitiveSpec& s)
{
  if (!std::isfinite(euler[0]) || !std::isfinite(euler[1]) || !std::isfinite(euler[2]))
  {
    // Reported by the build: a rotation that cannot be evaluated.
    s.Orient = pisurf::Orientation::Rotation;
    s.RotationAngle = std::numeric_limits<double>::quiet_NaN();
    return;
  }
  double local[3][3];
  std::string error;
  if (!pisurf::OrientationMatrix(s, local, error))
  {
    return;
  }
  const double x[3] = { 1, 0, 0 }, y[3] = { 0, 1, 0 }, z[3] = { 0, 0, 1 };
  double Rx[3][3], Ry[3][3], Rz[3][3], E[3][3], C[3][3];
  pisurf::RotationMatrix(x, euler[0], Rx);
  pisurf::RotationMatrix(y, euler[1], Ry);
  pisurf::RotationMatrix(z, euler[2], Rz);
  vtkMath::Multiply3x3(Rz, Rx, E);
  vtkMath::Multiply3x3(E, Ry, E);
  // World from local: E·localᵀ (local's rows are the local axes).
  double T[3][3];
  vtkMath::Transpose3x3(local, T);
  vtkMath::Multiply3x3(E, T, C);
  double q[4]; // w, x, y, z
  vtkMath::Matrix3x3ToQuaternion(C, q);
  const double sine = std::sqrt(q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!(sine > 0.0))
  {
    s.Orient = pisurf::Orientation::Default;
    return;
  }
  s.Orient = pisurf::Orientation::Rotation;
  s.RotationAngle = vtkMath::DegreesFromRadians(2.0 * std::atan2(sine, q[0]));
  for (int k = 0; k < 3; ++k)
  {
    s.RotationAxis[k] = q[k + 1] / sine;
  }
}
}

pisurf::PrimitiveSpec vtkPiPrimitive::GetSpec()
{
  pisurf::PrimitiveSpec s;
  s.Type = static_cast<pisurf::PrimitiveType>(this->Type);
  s.Name = this->Internals->Name;
  std::copy(this->Center, this->Center + 3, s.Center);
  const bool axisSet = !(this->Axis[0] == 0 && this->Axis[1] == 0 && this->Axis[2] == 1);
  if (this->RotationAngle != 0.0)
  {
    s.Orient = pisurf::Orientation::Rotation;
    // Both set is an error the build reports; keep the axis so it can say so.
    if (axisSet)
    {
      s.Orient = pisurf::Orientation::Axis;
    }
  }
  else if (axisSet)
  {
    s.Orient = pisurf::Orientation::Axis;
  }
  std::copy(this->Axis, this->Axis + 3, s.Axis);
  std::copy(this->RotationAxis, this->RotationAxis + 3, s.RotationAxis);
  s.RotationAngle = this->RotationAngle;
  s.Radius = this->Radius;
  std::copy(this->Radii, this->Radii + 3, s.Radii);
  s.MajorRadius = this->MajorRadius;
  s.MinorRadius = this->MinorRadius;
  s.Exponent = this->Exponent;
  std::copy(this->Normal, this->Normal + 3, s.Normal);
  s.Angle = this->Angle;
  s.Expression = this->Internals->Expression;
  s.Scale = this->Scale;
  s.Negate = this->Negate;
  if (this->Orientation[0] != 0.0 || this->Orientation[1] != 0.0 || this->Orientation[2] != 0.0)
  {
    ComposeOrientation(this->Orientation, s);
  }
  return s;
}

void vtkPiPrimitive::SetSpec(const pisurf::PrimitiveSpec& s)
{
  this->Type = static_cast<int>(s.Type);
  this->Internals->Name = s.Name;
  std::copy(s.Center, s.Center + 3, this->Center);
  const double z[3] = { 0, 0, 1 };
  std::copy(z, z + 3, this->Axis);
  std::copy(z, z + 3, this->RotationAxis);
  this->RotationAngle = 0.0;
  std::fill(this->Orientation, this->Orientation + 3, 0.0);
  if (s.Orient == pisurf::Orientation::Axis)
  {
    std::copy(s.Axis, s.Axis + 3, this->Axis);
  }
  else if (s.Orient == pisurf::Orientation::Rotation)
  {
    std::copy(s.RotationAxis, s.RotationAxis + 3, this->RotationAxis);
    this->RotationAngle = s.RotationAngle;
  }
  this->Radius = s.Radius;
  std::copy(s.Radii, s.Radii + 3, this->Radii);
  this->MajorRadius = s.MajorRadius;
  this->MinorRadius = s.MinorRadius;
  this->Exponent = s.Exponent;
  std::copy(s.Normal, s.Normal + 3, this->Normal);
  this->Angle = s.Angle;
  this->Internals->Expression = s.Expression;
  this->Scale = s.Scale;
  this->Negate = s.Negate;
  this->Modified();
}

std::shared_ptr<const pisurf::PolynomialFactor> vtkPiPrimitive::GetPolynomialFactor()
{
  vtkInternals& in = *this->Internals;
  if (in.Dirty.load(std::memory_order_acquire))
  {
    std::string error;
    {
      std::lock_guard<std::mutex> lock(in.BuildMutex);
      if (in.Dirty.load(std::memory_order_relaxed))
      {
        pisurf::PrimitiveSpec spec = this->GetSpec();
        const bool axisSet = !(this->Axis[0] == 0 && this->Axis[1] == 0 && this->Axis[2] == 1);
        auto f = std::make_shared<pisurf::PolynomialFactor>();
        if (this->RotationAngle != 0.0 && axisSet)
        {
          in.Error = "set either Axis or RotationAxis/RotationAngle, not both";
          in.Valid = false;
        }
        else if (!std::isfinite(this->Orientation[0]) || !std::isfinite(this->Orientation[1]) ||
          !std::isfinite(this->Orientation[2]))
        {
          in.Error = "Orientation must be three finite angles in degrees";
          in.Valid = false;
        }
        else if (pisurf::BuildFactor(spec, in.Parameters, *f, in.Error))
        {
          in.Factor = f;
          in.Valid = true;
          in.Error.clear();
        }
        else
        {
          in.Valid = false;
        }
        error = in.Error;
        in.Dirty.store(false, std::memory_order_release);
      }
    }
    if (!error.empty())
    {
      vtkErrorMacro(<< "Invalid " << this->GetTypeAsString() << " primitive"
                    << (in.Name.empty() ? "" : " '" + in.Name + "'") << ": " << error);
    }
  }
  return in.Valid ? in.Factor : nullptr;
}

double vtkPiPrimitive::EvaluateFunction(double x[3])
{
  this->GetPolynomialFactor();
  const auto& f = this->Internals->Factor;
  return f ? f->Evaluate(x) : std::numeric_limits<double>::quiet_NaN();
}

void vtkPiPrimitive::EvaluateGradient(double x[3], double g[3])
{
  this->GetPolynomialFactor();
  const auto& f = this->Internals->Factor;
  if (f)
  {
    f->EvaluateWithGradient(x, g);
  }
  else
  {
    g[0] = g[1] = g[2] = std::numeric_limits<double>::quiet_NaN();
  }
}

bool vtkPiPrimitive::SetTypeFromString(const char* type)
{
  pisurf::PrimitiveType t;
  if (!type || !pisurf::TypeFromString(type, t))
  {
    vtkErrorMacro(<< "Unknown primitive type '" << (type ? type : "(null)") << "'");
    return false;
  }
  this->SetType(static_cast<int>(t));
  return true;
}

const char* vtkPiPrimitive::GetTypeAsString()
{
  return pisurf::TypeLabel(static_cast<pisurf::PrimitiveType>(this->Type));
}

void vtkPiPrimitive::SetExpression(const char* expression)
{
  const std::string e = expression ? expression : "";
  if (e != this->Internals->Expression)
  {
    this->Internals->Expression = e;
    this->Modified();
  }
}

const char* vtkPiPrimitive::GetExpression()
{
  return this->Internals->Expression.c_str();
}

void vtkPiPrimitive::SetName(const char* name)
{
  const std::string n = name ? name : "";
  if (n != this->Internals->Name)
  {
    this->Internals->Name = n;
    this->Modified();
  }
}

const char* vtkPiPrimitive::GetName()
{
  return this->Internals->Name.c_str();
}

void vtkPiPrimitive::SetParameter(const char* name, double value)
{
  if (!name || !pisurf::IsValidParameterName(name))
  {
    vtkErrorMacro(<< "Invalid parameter name '" << (name ? name : "(null)")
                  << "' (letters, digits, '_'; not x, y or z)");
    return;
  }
  if (!std::isfinite(value))
  {
    vtkErrorMacro(<< "Parameter '" << name << "' must be a finite number");
    return;
  }
  auto it = this->Internals->Parameters.find(name);
  if (it == this->Internals->Parameters.end() || it->second != value)
  {
    this->Internals->Parameters[name] = value;
    this->Modified();
  }
}

double vtkPiPrimitive::GetParameter(const char* name)
{
  auto it = this->Internals->Parameters.find(name ? name : "");
  return it == this->Internals->Parameters.end() ? std::numeric_limits<double>::quiet_NaN()
                                                 : it->second;
}

const std::map<std::string, double>& vtkPiPrimitive::GetParameters()
{
  return this->Internals->Parameters;
}

void vtkPiPrimitive::RemoveAllParameters()
{
  if (!this->Internals->Parameters.empty())
  {
    this->Internals->Parameters.clear();
    this->Modified();
  }
}

bool vtkPiPrimitive::IsValid()
{
  this->GetPolynomialFactor();
  return this->Internals->Valid;
}

const char* vtkPiPrimitive::GetErrorMessage()
{
  this->GetPolynomialFactor();
  return this->Internals->Error.c_str();
}

int vtkPiPrimitive::GetDegree()
{
  auto f = this->GetPolynomialFactor();
  return f ? f->Poly.GetDegree() : -1;
}

bool vtkPiPrimitive::IsBounded()
{
  return pisurf::CatalogueEntry(static_cast<pisurf::PrimitiveType>(this->Type)).Bounded;
}

void vtkPiPrimitive::SetType(int type)
{
  const int last = static_cast<int>(pisurf::PrimitiveCatalogue().size()) - 1;
  type = std::min(std::max(type, 0), last);
  if (type != this->Type)
  {
    this->Type = type;
    this->Modified();
  }
}

int vtkPiPrimitive::GetNumberOfTypes()
{
  return static_cast<int>(pisurf::PrimitiveCatalogue().size());
}

std::string vtkPiPrimitive::GetCatalogueJSON()
{
  return pisurf::CatalogueJSON();
}

bool vtkPiPrimitive::GetPrimitiveBounds(double bounds[6])
{
  auto f = this->GetPolynomialFactor();
  if (!f || !f->Bounded)
  {
    return false;
  }
  std::copy(f->Bounds, f->Bounds + 6, bounds);
  return true;
}

std::string vtkPiPrimitive::GetWorldPolynomial()
{
  auto f = this->GetPolynomialFactor();
  return f ? f->WorldPolynomial().ToString() : std::string();
}

void vtkPiPrimitive::RestrictToLine(
  const double origin[3], const double direction[3], vtkDoubleArray* c)
{
  auto f = this->GetPolynomialFactor();
  if (!c)
  {
    return;
  }
  c->SetNumberOfComponents(1);
  c->SetNumberOfTuples(0);
  if (!f)
  {
    return;
  }
  for (double v : f->RestrictToLine(origin, direction))
  {
    c->InsertNextValue(v);
  }
}

void vtkPiPrimitive::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Type: " << this->GetTypeAsString() << "\n";
  os << indent << "Name: " << this->Internals->Name << "\n";
  os << indent << "Center: (" << this->Center[0] << ", " << this->Center[1] << ", "
     << this->Center[2] << ")\n";
  os << indent << "Axis: (" << this->Axis[0] << ", " << this->Axis[1] << ", " << this->Axis[2]
     << ")\n";
  os << indent << "RotationAxis: (" << this->RotationAxis[0] << ", " << this->RotationAxis[1]
     << ", " << this->RotationAxis[2] << ")\n";
  os << indent << "RotationAngle: " << this->RotationAngle << "\n";
  os << indent << "Orientation: (" << this->Orientation[0] << ", " << this->Orientation[1] << ", "
     << this->Orientation[2] << ")\n";
  os << indent << "Radius: " << this->Radius << "\n";
  os << indent << "Radii: (" << this->Radii[0] << ", " << this->Radii[1] << ", " << this->Radii[2]
     << ")\n";
  os << indent << "MajorRadius: " << this->MajorRadius << "\n";
  os << indent << "MinorRadius: " << this->MinorRadius << "\n";
  os << indent << "Exponent: " << this->Exponent << "\n";
  os << indent << "Normal: (" << this->Normal[0] << ", " << this->Normal[1] << ", "
     << this->Normal[2] << ")\n";
  os << indent << "Angle: " << this->Angle << "\n";
  os << indent << "Expression: " << this->Internals->Expression << "\n";
  os << indent << "Parameters:";
  for (const auto& kv : this->Internals->Parameters)
  {
    os << " " << kv.first << "=" << kv.second;
  }
  os << "\n";
  os << indent << "Scale: " << this->Scale << "\n";
  os << indent << "Negate: " << (this->Negate ? "On" : "Off") << "\n";
}
