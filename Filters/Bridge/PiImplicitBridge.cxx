// SPDX-License-Identifier: BSD-3-Clause
#include "PiImplicitBridge.h"

#include "PiModel.h"
#include "PiPolynomialFactor.h"
#include "PiPrimitiveSpec.h"
#include "vtkPiPrimitive.h"

#include "vtkCone.h"
#include "vtkCylinder.h"
#include "vtkImplicitFunction.h"
#include "vtkLinearTransform.h"
#include "vtkMath.h"
#include "vtkMatrix4x4.h"
#include "vtkNew.h"
#include "vtkPlane.h"
#include "vtkQuadric.h"
#include "vtkSphere.h"

#include <algorithm>
#include <cmath>

namespace
{
using pisurf::Polynomial3;
using pisurf::PolynomialFactor;

Polynomial3 V(int a)
{
  return Polynomial3::Variable(a);
}

// VTK's polynomial implicit functions, as the polynomials they evaluate (before their
// Transform). False for anything else.
bool RecognizePolynomial(vtkImplicitFunction* f, PolynomialFactor& pf)
{
  pf = PolynomialFactor();
  if (auto* s = vtkSphere::SafeDownCast(f))
  {
    const double R = s->GetRadius();
    pf.Poly = V(0).Pow(2) + V(1).Pow(2) + V(2).Pow(2) - Polynomial3::Constant(R * R);
    const double* c = s->GetCenter();
    for (int i = 0; i < 3; ++i)
    {
      pf.B[i] = -c[i];
      pf.Bounds[2 * i] = c[i] - std::fabs(R);
      pf.Bounds[2 * i + 1] = c[i] + std::fabs(R);
    }
    pf.Bounded = R != 0.0;
    return true;
  }
  if (auto* p = vtkPlane::SafeDownCast(f))
  {
    const double* n = p->GetNormal();
    const double* o = p->GetOrigin();
    pf.Poly = V(0).Scaled(n[0]) + V(1).Scaled(n[1]) + V(2).Scaled(n[2]);
    for (int i = 0; i < 3; ++i)
    {
      pf.B[i] = -o[i];
    }
    return true;
  }
  if (auto* c = vtkCylinder::SafeDownCast(f))
  {
    // |q|² − (â·q)² − R² with q = p − center.
    double a[3];
    c->GetAxis(a);
    vtkMath::Normalize(a);
    const double R = c->GetRadius();
    Polynomial3 aq = V(0).Scaled(a[0]) + V(1).Scaled(a[1]) + V(2).Scaled(a[2]);
    pf.Poly = V(0).Pow(2) + V(1).Pow(2) + V(2).Pow(2) - aq.Pow(2) - Polynomial3::Constant(R * R);
    const double* ctr = c->GetCenter();
    for (int i = 0; i < 3; ++i)
    {
      pf.B[i] = -ctr[i];
    }
    return true;
  }
  if (auto* c = vtkCone::SafeDownCast(f))
  {
    const double t = std::tan(vtkMath::RadiansFromDegrees(c->GetAngle()));
    pf.Poly = V(1).Pow(2) + V(2).Pow(2) - V(0).Pow(2).Scaled(t * t);
    return true;
  }
  if (auto* q = vtkQuadric::SafeDownCast(f))
  {
    const double* a = q->GetCoefficients();
    Polynomial3& P = pf.Poly;
    P.AddTerm(a[0], 2, 0, 0);
    P.AddTerm(a[1], 0, 2, 0);
    P.AddTerm(a[2], 0, 0, 2);
    P.AddTerm(a[3], 1, 1, 0);
    P.AddTerm(a[4], 0, 1, 1);
    P.AddTerm(a[5], 1, 0, 1);
    P.AddTerm(a[6], 1, 0, 0);
    P.AddTerm(a[7], 0, 1, 0);
    P.AddTerm(a[8], 0, 0, 1);
    P.AddTerm(a[9], 0, 0, 0);
    return true;
  }
  return false;
}

// Folds a function's linear Transform (f is evaluated at M·p + t) into the polynomial's
// affine map. False for a non-linear transform.
bool ApplyTransform(vtkAbstractTransform* transform, PolynomialFactor& pf)
{
  if (!transform)
  {
    return true;
  }
  auto* linear = vtkLinearTransform::SafeDownCast(transform);
  if (!linear)
  {
    return false;
  }
  linear->Update();
  vtkMatrix4x4* M = linear->GetMatrix();
  double A[3][3], B[3];
  for (int i = 0; i < 3; ++i)
  {
    B[i] = pf.B[i];
    for (int j = 0; j < 3; ++j)
    {
      A[i][j] = 0.0;
      for (int k = 0; k < 3; ++k)
      {
        A[i][j] += pf.A[i][k] * M->GetElement(k, j);
      }
      B[i] += pf.A[i][j] * M->GetElement(j, 3);
    }
  }
  if (pf.Bounded)
  {
    // The box corners c satisfy M·p + t = c: map them back and take their box.
    double Minv[16];
    vtkMatrix4x4::Invert(M->GetData(), Minv);
    double box[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
      VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
    for (int c = 0; c < 8; ++c)
    {
      const double corner[4] = { pf.Bounds[(c & 1)], pf.Bounds[2 + ((c >> 1) & 1)],
        pf.Bounds[4 + ((c >> 2) & 1)], 1.0 };
      double p[4];
      vtkMatrix4x4::MultiplyPoint(Minv, corner, p);
      for (int i = 0; i < 3; ++i)
      {
        box[2 * i] = std::min(box[2 * i], p[i] / p[3]);
        box[2 * i + 1] = std::max(box[2 * i + 1], p[i] / p[3]);
      }
    }
    std::copy(box, box + 6, pf.Bounds);
  }
  std::copy(&A[0][0], &A[0][0] + 9, &pf.A[0][0]);
  std::copy(B, B + 3, pf.B);
  return true;
}
}

namespace pisurf
{
FactorKind ExactFactor(vtkImplicitFunction* f, PolynomialFactor& out, std::string& error)
{
  bool polynomial = false;
  if (auto* p = vtkPiPrimitive::SafeDownCast(f))
  {
    auto pf = p->GetPolynomialFactor();
    if (!pf)
    {
      error = p->GetErrorMessage();
      return FactorKind::Invalid;
    }
    out = *pf;
    polynomial = true;
  }
  else
  {
    polynomial = RecognizePolynomial(f, out);
  }
  return polynomial && ApplyTransform(f->GetTransform(), out) ? FactorKind::Exact
                                                              : FactorKind::Generic;
}

vtkSmartPointer<vtkImplicitFunction> MakeFunction(
  const PrimitiveSpec& spec, const ParameterMap& parameters)
{
  vtkNew<vtkPiPrimitive> p;
  for (const auto& kv : parameters)
  {
    p->SetParameter(kv.first.c_str(), kv.second);
  }
  p->SetSpec(spec);
  return p.Get();
}

PrimitiveSpec DescribeFactor(
  vtkImplicitFunction* f, const PolynomialFactor& exact, ParameterMap& parameters)
{
  auto* p = vtkPiPrimitive::SafeDownCast(f);
  bool asSpec = p && !f->GetTransform();
  if (asSpec)
  {
    // The expression's parameters must agree with the model's.
    for (const auto& kv : p->GetParameters())
    {
      auto it = parameters.find(kv.first);
      if (it == parameters.end())
      {
        parameters[kv.first] = kv.second;
      }
      else if (it->second != kv.second)
      {
        asSpec = false;
      }
    }
  }
  if (asSpec)
  {
    return p->GetSpec();
  }
  PrimitiveSpec s;
  s.Type = PrimitiveType::Polynomial;
  s.Name = p ? p->GetName() : f->GetClassName();
  s.Expression = exact.WorldPolynomial().ToString();
  return s;
}

void SetFactorParameter(
  vtkImplicitFunction* f, const std::string& name, double value, bool onlyIfUnset)
{
  if (auto* p = vtkPiPrimitive::SafeDownCast(f))
  {
    if (!onlyIfUnset || std::isnan(p->GetParameter(name.c_str())))
    {
      p->SetParameter(name.c_str(), value);
    }
  }
}
}
