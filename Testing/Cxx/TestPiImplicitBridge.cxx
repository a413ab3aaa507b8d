// SPDX-License-Identifier: BSD-3-Clause
// The bridge between VTK implicit functions and the exact model: each recognised
// function type gives the polynomial factor that evaluates as the function does; other
// functions are not claimed exact; a model's primitive becomes a function and back.
#include "PiTestUtilities.h"

#include "Bridge/PiImplicitBridge.h"
#include "PiPolynomialFactor.h"
#include "PiPrimitiveSpec.h"

#include "vtkBox.h"
#include "vtkCone.h"
#include "vtkCylinder.h"
#include "vtkNew.h"
#include "vtkPiPrimitive.h"
#include "vtkPlane.h"
#include "vtkQuadric.h"
#include "vtkSphere.h"
#include "vtkSphericalTransform.h"
#include "vtkSuperquadric.h"
#include "vtkTransform.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

int TestPiImplicitBridge(int, char*[])
{
  int failures = 0;
  pitest::Random random(11);

  vtkNew<vtkTransform> move;
  move->Translate(0.3, -0.2, 0.1);
  move->RotateWXYZ(40, 1, 2, 3);
  move->Scale(1.5, 0.8, 1.2);

  vtkNew<vtkSphere> sphere;
  sphere->SetCenter(0.2, -0.4, 0.6);
  sphere->SetRadius(0.9);
  vtkNew<vtkSphere> movedSphere;
  movedSphere->SetCenter(-0.1, 0.3, 0.2);
  movedSphere->SetRadius(1.1);
  movedSphere->SetTransform(move);
  vtkNew<vtkPlane> plane;
  plane->SetOrigin(-0.3, 0.4, 0.1);
  plane->SetNormal(2, -1, 0.5);
  vtkNew<vtkCylinder> cylinder;
  cylinder->SetCenter(0, 0.5, -0.2);
  cylinder->SetAxis(1, 0, 1);
  cylinder->SetRadius(0.6);
  vtkNew<vtkCone> cone;
  cone->SetAngle(25);
  cone->SetTransform(move);
  vtkNew<vtkQuadric> quadric;
  quadric->SetCoefficients(2, -1, 0.5, 0.3, -0.2, 0.1, 0.4, -0.5, 1, -1.5);
  vtkNew<vtkPiPrimitive> torus;
  torus->SetTypeToTorus();
  torus->SetCenter(0.1, 0.2, -0.3);
  torus->SetAxis(1, 1, 0);
  torus->SetMajorRadius(1.0);
  torus->SetMinorRadius(0.3);
  torus->SetScale(2.5);
  torus->NegateOn();
  vtkNew<vtkPiPrimitive> movedEllipsoid;
  movedEllipsoid->SetTypeToEllipsoid();
  movedEllipsoid->SetRadii(1.0, 0.5, 0.8);
  movedEllipsoid->SetRotationAngle(20);
  movedEllipsoid->SetTransform(move);

  const std::vector<std::pair<const char*, vtkImplicitFunction*>> exact = { { "sphere", sphere },
    { "transformed sphere", movedSphere }, { "plane", plane }, { "cylinder", cylinder },
    { "transformed cone", cone }, { "quadric", quadric }, { "primitive", torus },
    { "transformed primitive", movedEllipsoid } };
  for (const auto& named : exact)
  {
    pisurf::PolynomialFactor pf;
    std::string error;
    const pisurf::FactorKind kind = pisurf::ExactFactor(named.second, pf, error);
    if (kind != pisurf::FactorKind::Exact)
    {
      std::cerr << named.first << " is not an exact factor" << std::endl;
      ++failures;
      continue;
    }
    int mismatches = 0;
    for (int i = 0; i < 200; ++i)
    {
      double p[3] = { random(-2, 2), random(-2, 2), random(-2, 2) };
      // FunctionValue applies the function's Transform; EvaluateFunction does not.
      const double expected = named.second->FunctionValue(p);
      const double got = pf.Evaluate(p);
      if (!(std::fabs(got - expected) <= 1e-12 * std::max(1.0, std::fabs(expected))))
      {
        if (mismatches++ == 0)
        {
          std::cerr << named.first << " at (" << p[0] << ", " << p[1] << ", " << p[2]
                    << "): factor " << got << ", function " << expected << std::endl;
        }
      }
    }
    PI_CHECK(mismatches == 0);
  }

  // Functions that are not polynomials are evaluated through their virtual calls.
  vtkNew<vtkBox> box;
  vtkNew<vtkSuperquadric> superquadric;
  for (vtkImplicitFunction* f : std::vector<vtkImplicitFunction*>{ box, superquadric })
  {
    pisurf::PolynomialFactor pf;
    std::string error;
    PI_CHECK(pisurf::ExactFactor(f, pf, error) == pisurf::FactorKind::Generic);
  }
  // A non-linear transform: the function is not claimed exact either.
  vtkNew<vtkSphere> warped;
  vtkNew<vtkSphericalTransform> spherical;
  warped->SetTransform(spherical);
  {
    pisurf::PolynomialFactor pf;
    std::string error;
    PI_CHECK(pisurf::ExactFactor(warped, pf, error) == pisurf::FactorKind::Generic);
  }

  // An invalid primitive says why.
  vtkNew<vtkPiPrimitive> invalid;
  invalid->SetRadius(-1);
  {
    pisurf::PolynomialFactor pf;
    std::string error;
    pitest::Watch watch(invalid);
    PI_CHECK(pisurf::ExactFactor(invalid, pf, error) == pisurf::FactorKind::Invalid);
    PI_CHECK(!error.empty());
  }

  // A model's primitive becomes a function with the model's parameters, and back.
  pisurf::PrimitiveSpec spec;
  spec.Type = pisurf::PrimitiveType::Polynomial;
  spec.Name = "handle";
  spec.Expression = "x^2 + y^2 + z^2 - a^2";
  pisurf::ParameterMap parameters{ { "a", 0.75 } };
  vtkSmartPointer<vtkImplicitFunction> made = pisurf::MakeFunction(spec, parameters);
  PI_CHECK(made != nullptr);
  if (made)
  {
    double p[3] = { 0.5, 0.25, -0.5 };
    PI_CHECK_NEAR(made->EvaluateFunction(p), 0.25 + 0.0625 + 0.25 - 0.5625, 1e-15);
    pisurf::PolynomialFactor pf;
    std::string error;
    PI_CHECK(pisurf::ExactFactor(made, pf, error) == pisurf::FactorKind::Exact);
    pisurf::ParameterMap described;
    const pisurf::PrimitiveSpec back = pisurf::DescribeFactor(made, pf, described);
    PI_CHECK(back.Name == "handle");
    PI_CHECK(back.Expression == spec.Expression);
    PI_CHECK(described.size() == 1 && described["a"] == 0.75);
    pisurf::SetFactorParameter(made, "a", 2.0, true); // set already: unchanged
    PI_CHECK_NEAR(made->EvaluateFunction(p), 0.25 + 0.0625 + 0.25 - 0.5625, 1e-15);
    pisurf::SetFactorParameter(made, "a", 1.0, false);
    PI_CHECK_NEAR(made->EvaluateFunction(p), 0.25 + 0.0625 + 0.25 - 1.0, 1e-15);
  }
  // A VTK function is described by its world polynomial, named after its class.
  {
    pisurf::PolynomialFactor pf;
    std::string error;
    pisurf::ExactFactor(sphere, pf, error);
    pisurf::ParameterMap described;
    const pisurf::PrimitiveSpec s = pisurf::DescribeFactor(sphere, pf, described);
    PI_CHECK(s.Type == pisurf::PrimitiveType::Polynomial);
    PI_CHECK(s.Name == "vtkSphere");
    PI_CHECK(!s.Expression.empty());
    PI_CHECK(described.empty());
  }
  return failures == 0 ? EXIT_SUCCESS : EXIT_FAILURE;
}
