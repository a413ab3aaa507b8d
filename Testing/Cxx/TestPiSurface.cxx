// SPDX-License-Identifier: BSD-3-Clause
// vtkPiSurface: the product, its exact gradient, VTK's own functions as factors,
// MTime, the model round trip and its errors, batch evaluation.
#include "PiTestUtilities.h"

#include "vtkPiPrimitive.h"
#include "vtkPiSurface.h"

#include "vtkCone.h"
#include "vtkCylinder.h"
#include "vtkDoubleArray.h"
#include "vtkPlane.h"
#include "vtkQuadric.h"
#include "vtkSphere.h"
#include "vtkSuperquadric.h"
#include "vtkTransform.h"

#include <vector>

namespace
{
double Sphere(const double p[3], const double c[3], double R)
{
  return (p[0] - c[0]) * (p[0] - c[0]) + (p[1] - c[1]) * (p[1] - c[1]) +
    (p[2] - c[2]) * (p[2] - c[2]) - R * R;
}

void FiniteDifference(vtkImplicitFunction* f, double p[3], double g[3])
{
  const double h = 1e-6;
  for (int a = 0; a < 3; ++a)
  {
    double q1[3] = { p[0], p[1], p[2] }, q2[3] = { p[0], p[1], p[2] };
    q1[a] += h;
    q2[a] -= h;
    g[a] = (f->EvaluateFunction(q1) - f->EvaluateFunction(q2)) / (2 * h);
  }
}
}

int TestPiSurface(int, char*[])
{
  int failures = 0;
  pitest::Random random(7);

  // The paper's two spheres from VTK's own vtkSphere and one vtkPiPrimitive.
  vtkNew<vtkSphere> left;
  left->SetCenter(-0.9, 0, 0);
  left->SetRadius(1.0);
  vtkNew<vtkPiPrimitive> right;
  right->SetTypeToSphere();
  right->SetCenter(0.9, 0, 0);
  right->SetRadius(1.0);
  vtkNew<vtkPiSurface> surface;
  pitest::Watch watch(surface);
  surface->AddFactor(left);
  surface->AddFactor(right);
  surface->SetBlending(0.25);
  PI_CHECK(surface->GetNumberOfFactors() == 2);
  PI_CHECK(surface->GetFactor(0) == left.GetPointer());
  PI_CHECK(surface->IsValid());
  const double cl[3] = { -0.9, 0, 0 }, cr[3] = { 0.9, 0, 0 };
  for (int i = 0; i < 200; ++i)
  {
    double p[3] = { random(-3, 3), random(-2, 2), random(-2, 2) };
    const double expected = Sphere(p, cl, 1) * Sphere(p, cr, 1) - 0.25;
    PI_CHECK_NEAR(surface->EvaluateFunction(p), expected, 1e-12 * (1 + std::fabs(expected)));
    double g[3], fd[3];
    surface->EvaluateGradient(p, g);
    FiniteDifference(surface, p, fd);
    for (int a = 0; a < 3; ++a)
    {
      PI_CHECK_NEAR(g[a], fd[a], 1e-5 * (1 + std::fabs(fd[a])));
    }
  }
  // The neck of the blend lies on x = 0 at radius sqrt(1.5 - d²) (F = 0 there).
  double neck[3] = { 0, std::sqrt(1.5 - 0.81), 0 };
  PI_CHECK_NEAR(surface->EvaluateFunction(neck), 0.0, 1e-12);

  // Exact gradient where a factor is zero: ∇F = ∇f_zero · Π others.
  double onRight[3] = { 1.9, 0, 0 };
  double g[3];
  surface->EvaluateGradient(onRight, g);
  PI_CHECK_NEAR(g[0], 2.0 * Sphere(onRight, cl, 1), 1e-12);
  PI_CHECK_NEAR(g[1], 0.0, 1e-15);

  // Modifying a factor re-evaluates (observer) and bumps the surface's MTime.
  const vtkMTimeType before = surface->GetMTime();
  left->SetRadius(1.2);
  PI_CHECK(surface->GetMTime() > before);
  double origin[3] = { 0, 0, 0 };
  PI_CHECK_NEAR(surface->EvaluateFunction(origin),
    Sphere(origin, cl, 1.2) * Sphere(origin, cr, 1) - 0.25, 1e-12);
  right->SetRadius(0.8);
  PI_CHECK_NEAR(surface->EvaluateFunction(origin),
    Sphere(origin, cl, 1.2) * Sphere(origin, cr, 0.8) - 0.25, 1e-12);
  left->SetRadius(1.0);
  right->SetRadius(1.0);

  // Batch evaluation equals point evaluation.
  vtkNew<vtkDoubleArray> points;
  points->SetNumberOfComponents(3);
  for (int i = 0; i < 5000; ++i)
  {
    points->InsertNextTuple3(random(-3, 3), random(-2, 2), random(-2, 2));
  }
  vtkNew<vtkDoubleArray> values;
  surface->FunctionValue(points, values);
  PI_CHECK(values->GetNumberOfTuples() == 5000);
  for (vtkIdType i = 0; i < 5000; i += 37)
  {
    double p[3];
    points->GetTuple(i, p);
    PI_CHECK_NEAR(values->GetValue(i), surface->EvaluateFunction(p), 1e-12);
  }

  // Every VTK polynomial function is a polynomial factor, transforms included:
  // the model JSON can be written and reads back to the same function.
  vtkNew<vtkPiSurface> mixed;
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(0.1, 0.2, 0.3);
  plane->SetNormal(1, 2, 2);
  vtkNew<vtkCylinder> cylinder;
  cylinder->SetCenter(0.5, 0, 0);
  cylinder->SetAxis(0, 1, 1);
  cylinder->SetRadius(0.7);
  vtkNew<vtkCone> cone;
  cone->SetAngle(25);
  vtkNew<vtkTransform> move;
  move->Translate(0.3, -0.2, 0.1);
  move->RotateZ(30);
  cone->SetTransform(move);
  vtkNew<vtkQuadric> quadric;
  quadric->SetCoefficients(1, 2, 3, 0.1, 0.2, 0.3, -1, 0.5, 0.25, -2);
  mixed->AddFactor(plane);
  mixed->AddFactor(cylinder);
  mixed->AddFactor(cone);
  mixed->AddFactor(quadric);
  mixed->AddFactor(left);
  mixed->SetBlending(0.5);
  pitest::Watch mixedWatch(mixed);
  PI_CHECK(mixed->GetModelJSON().empty()); // unbounded factors need model bounds
  PI_CHECK(mixedWatch.Error("set the model bounds"));
  const double roi[6] = { -2, 2, -2, 2, -2, 2 };
  mixed->SetModelBounds(roi);
  const std::string json = mixed->GetModelJSON();
  PI_CHECK(!json.empty());
  vtkNew<vtkPiSurface> reread;
  PI_CHECK(reread->SetModelJSON(json));
  PI_CHECK(reread->GetNumberOfFactors() == 5);
  for (int i = 0; i < 100; ++i)
  {
    double p[3] = { random(-2, 2), random(-2, 2), random(-2, 2) };
    double direct = 1.0;
    for (vtkImplicitFunction* f :
      std::vector<vtkImplicitFunction*>{ plane, cylinder, cone, quadric, left })
    {
      direct *= f->FunctionValue(p);
    }
    direct -= 0.5;
    const double tol = 1e-10 * (1 + std::fabs(direct));
    PI_CHECK_NEAR(mixed->EvaluateFunction(p), direct, tol);
    PI_CHECK_NEAR(reread->EvaluateFunction(p), direct, tol);
  }

  // A function that is not a polynomial works as a factor, but has no model JSON.
  vtkNew<vtkSuperquadric> superquadric;
  vtkNew<vtkPiSurface> generic;
  pitest::Watch genericWatch(generic);
  generic->AddFactor(superquadric);
  generic->AddFactor(left);
  double p[3] = { 0.3, 0.2, 0.1 };
  PI_CHECK_NEAR(
    generic->EvaluateFunction(p), superquadric->FunctionValue(p) * left->FunctionValue(p), 1e-12);
  PI_CHECK(generic->GetModelJSON().empty());
  PI_CHECK(genericWatch.Error("not a polynomial"));

  // Invalid models are refused and leave the function unchanged.
  const double valueBefore = surface->EvaluateFunction(origin);
  PI_CHECK(!surface->SetModelJSON("{\"pisurf\": 1, \"blending\": 0.2, \"primitives\": "
                                  "[{\"type\": \"sphere\", \"radius\": -1}]}"));
  PI_CHECK(watch.Error("primitives[0]: radius must be a positive"));
  PI_CHECK(!surface->SetModelJSON("{\"pisurf\": 1, \"blending\": 0.2, \"colour\": 3, "
                                  "\"primitives\": []}"));
  PI_CHECK(watch.Error("unknown key 'colour'"));
  PI_CHECK(!surface->SetModelJSON("{\"pisurf\": 1,\n \"blending\": }"));
  PI_CHECK(watch.Error("line 2"));
  PI_CHECK(!surface->LoadModel("/nonexistent/model.pisurf"));
  PI_CHECK(watch.Error("cannot open model file"));
  PI_CHECK(surface->GetNumberOfFactors() == 2);
  PI_CHECK_NEAR(surface->EvaluateFunction(origin), valueBefore, 0.0);

  // Parameters reach the primitives' expressions.
  PI_CHECK(surface->SetModelJSON("{\"pisurf\": 1, \"blending\": 0, \"bounds\": [-2,2,-2,2,-2,2],"
                                 "\"parameters\": {\"d\": 0.5}, \"primitives\": [{\"type\": "
                                 "\"polynomial\", \"expression\": \"(x-d)^2+y^2+z^2-1\"}]}"));
  PI_CHECK(watch.Quiet());
  PI_CHECK_NEAR(surface->EvaluateFunction(origin), 0.25 - 1.0, 1e-15);
  surface->SetParameter("d", 1.0);
  PI_CHECK_NEAR(surface->EvaluateFunction(origin), 0.0, 1e-15);
  double b[6];
  PI_CHECK(surface->GetModelBounds(b));
  PI_CHECK(b[0] == -2 && b[5] == 2);

  // Automatic bounds of bounded primitives contain the whole surface (r inflates it).
  vtkNew<vtkPiSurface> inflated;
  vtkNew<vtkPiPrimitive> unit;
  inflated->AddFactor(unit);
  inflated->SetBlending(3.0); // |p|² − 1 = 3: radius 2, twice the primitive
  PI_CHECK(inflated->GetModelBounds(b));
  PI_CHECK(b[0] < -2 && b[1] > 2 && b[4] < -2 && b[5] > 2);

  // A factor without a model cannot be meshed: no bounds for an unbounded factor.
  vtkNew<vtkPiSurface> unbounded;
  pitest::Watch unboundedWatch(unbounded);
  unbounded->AddFactor(plane);
  PI_CHECK(!unbounded->GetModelBounds(b));
  PI_CHECK(unboundedWatch.Error("unbounded"));

  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
