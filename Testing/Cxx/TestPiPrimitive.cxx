// SPDX-License-Identifier: BSD-3-Clause
// vtkPiPrimitive as a VTK implicit function: agreement with VTK's own functions,
// placement, invalid parameters (error, last valid polynomial kept), line restriction.
#include "PiTestUtilities.h"

#include "vtkPiPrimitive.h"

#include "vtkCylinder.h"
#include "vtkDoubleArray.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkPlane.h"
#include "vtkSphere.h"

int TestPiPrimitive(int, char*[])
{
  int failures = 0;
  vtkNew<vtkMinimalStandardRandomSequence> rng;
  rng->SetSeed(11);
  auto random = [&]()
  {
    rng->Next();
    return rng->GetRangeValue(-3, 3);
  };

  vtkNew<vtkPiPrimitive> sphere;
  pitest::Watch watch(sphere);
  sphere->SetCenter(0.5, -1, 2);
  sphere->SetRadius(1.5);
  vtkNew<vtkSphere> vtkS;
  vtkS->SetCenter(0.5, -1, 2);
  vtkS->SetRadius(1.5);

  vtkNew<vtkPiPrimitive> cylinder;
  cylinder->SetTypeFromString("cylinder");
  cylinder->SetCenter(1, 2, 3);
  cylinder->SetAxis(1, 1, 0);
  cylinder->SetRadius(0.75);
  vtkNew<vtkCylinder> vtkC;
  vtkC->SetCenter(1, 2, 3);
  vtkC->SetAxis(1, 1, 0);
  vtkC->SetRadius(0.75);

  vtkNew<vtkPiPrimitive> plane;
  plane->SetTypeToPlane();
  plane->SetCenter(0.1, 0.2, 0.3);
  plane->SetNormal(0, 3, 4);
  vtkNew<vtkPlane> vtkP;
  vtkP->SetOrigin(0.1, 0.2, 0.3);
  vtkP->SetNormal(0, 0.6, 0.8);

  for (int i = 0; i < 100; ++i)
  {
    double p[3] = { random(), random(), random() };
    PI_CHECK_NEAR(sphere->EvaluateFunction(p), vtkS->EvaluateFunction(p), 1e-12);
    PI_CHECK_NEAR(cylinder->EvaluateFunction(p), vtkC->EvaluateFunction(p), 1e-12);
    PI_CHECK_NEAR(plane->EvaluateFunction(p), vtkP->EvaluateFunction(p), 1e-12);
    double g1[3], g2[3];
    cylinder->EvaluateGradient(p, g1);
    vtkC->EvaluateGradient(p, g2);
    for (int a = 0; a < 3; ++a)
    {
      PI_CHECK_NEAR(g1[a], g2[a], 1e-12);
    }
  }
  PI_CHECK(watch.Quiet());
  PI_CHECK(std::string(cylinder->GetTypeAsString()) == "Cylinder");
  PI_CHECK(sphere->GetDegree() == 2);
  PI_CHECK(sphere->IsBounded() && !cylinder->IsBounded());
  double b[6];
  PI_CHECK(sphere->GetPrimitiveBounds(b));
  PI_CHECK_NEAR(b[0], -1.0, 1e-15);
  PI_CHECK_NEAR(b[5], 3.5, 1e-15);
  PI_CHECK(!cylinder->GetPrimitiveBounds(b));

  // Torus about +y: the ring lies in the x-z plane.
  vtkNew<vtkPiPrimitive> torus;
  torus->SetTypeToTorus();
  torus->SetAxis(0, 1, 0);
  torus->SetMajorRadius(2);
  torus->SetMinorRadius(0.5);
  double onRing[3] = { 0, 0.5, 2 }, inHole[3] = { 0, 0, 0 }, inTube[3] = { 2, 0, 0 };
  PI_CHECK_NEAR(torus->EvaluateFunction(onRing), 0.0, 1e-12);
  PI_CHECK(torus->EvaluateFunction(inHole) > 0);
  PI_CHECK(torus->EvaluateFunction(inTube) < 0);
  // The same torus by rotating +z onto +y: −90° about x.
  vtkNew<vtkPiPrimitive> rotated;
  rotated->SetTypeToTorus();
  rotated->SetRotationAxis(1, 0, 0);
  rotated->SetRotationAngle(-90);
  rotated->SetMajorRadius(2);
  rotated->SetMinorRadius(0.5);
  for (int i = 0; i < 50; ++i)
  {
    double p[3] = { random(), random(), random() };
    PI_CHECK_NEAR(rotated->EvaluateFunction(p), torus->EvaluateFunction(p),
      1e-10 * (1 + std::fabs(torus->EvaluateFunction(p))));
  }

  // Scale and negate multiply the polynomial.
  double p0[3] = { 0.2, 0.3, 0.4 };
  const double v = sphere->EvaluateFunction(p0);
  sphere->SetScale(2.5);
  sphere->NegateOn();
  PI_CHECK_NEAR(sphere->EvaluateFunction(p0), -2.5 * v, 1e-12);
  sphere->SetScale(1);
  sphere->NegateOff();

  // A polynomial with a parameter, and its restriction to a line.
  vtkNew<vtkPiPrimitive> poly;
  pitest::Watch polyWatch(poly);
  poly->SetTypeToPolynomial();
  poly->SetParameter("a", 2);
  poly->SetExpression("x^3 - a*y*z + 1");
  double q[3] = { 1, 2, 3 };
  PI_CHECK_NEAR(poly->EvaluateFunction(q), 1 - 12 + 1, 1e-12);
  vtkNew<vtkDoubleArray> c;
  const double o[3] = { 1, 0, 0 }, d[3] = { 1, 1, 1 };
  poly->RestrictToLine(o, d, c);
  PI_CHECK(c->GetNumberOfTuples() == 4);
  for (double t : { -1.0, 0.5, 2.0 })
  {
    double pt[3] = { o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2] };
    double h = 0;
    for (vtkIdType k = c->GetNumberOfTuples() - 1; k >= 0; --k)
    {
      h = h * t + c->GetValue(k);
    }
    PI_CHECK_NEAR(h, poly->EvaluateFunction(pt), 1e-12);
  }
  PI_CHECK(polyWatch.Quiet());

  // Invalid parameters: an error naming the parameter; the last valid polynomial stays.
  poly->SetExpression("x^2 + 2y");
  PI_CHECK(!poly->IsValid());
  PI_CHECK(polyWatch.Error("write '*' for multiplication"));
  PI_CHECK_NEAR(poly->EvaluateFunction(q), 1 - 12 + 1, 1e-12);
  poly->SetExpression("x^2 + 2*y");
  PI_CHECK(poly->IsValid());
  PI_CHECK_NEAR(poly->EvaluateFunction(q), 1 + 4, 1e-12);

  vtkNew<vtkPiPrimitive> bad;
  pitest::Watch badWatch(bad);
  bad->SetTypeToSuperellipsoid();
  bad->SetExponent(3);
  PI_CHECK(!bad->IsValid());
  PI_CHECK(badWatch.Error("exponent must be an even integer"));
  PI_CHECK(std::isnan(bad->EvaluateFunction(q))); // never had a valid polynomial
  bad->SetExponent(6);
  PI_CHECK(bad->IsValid());
  bad->SetRadii(1, -2, 1);
  PI_CHECK(!bad->IsValid());
  PI_CHECK(badWatch.Error("radii[1] must be a positive"));
  bad->SetRadii(1, 2, 1);
  bad->SetAxis(1, 0, 0);
  bad->SetRotationAngle(45);
  PI_CHECK(!bad->IsValid());
  PI_CHECK(badWatch.Error("either Axis or RotationAxis"));
  PI_CHECK(!bad->SetTypeFromString("dodecahedron"));
  PI_CHECK(badWatch.Error("Unknown primitive type 'dodecahedron'"));

  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
