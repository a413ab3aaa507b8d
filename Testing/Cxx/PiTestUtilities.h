// SPDX-License-Identifier: BSD-3-Clause
// Small helpers shared by the VTK-level tests.
#ifndef PiTestUtilities_h
#define PiTestUtilities_h

#include "vtkCommand.h"
#include "vtkMinimalStandardRandomSequence.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkPiSurface.h"
#include "vtkRegressionTestImage.h"
#include "vtkRenderWindow.h"
#include "vtkRenderWindowInteractor.h"
#include "vtkSmartPointer.h"
#include "vtkTestErrorObserver.h"

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>

#define PI_CHECK(cond)                                                                             \
  do                                                                                               \
  {                                                                                                \
    if (!(cond))                                                                                   \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #cond << std::endl;           \
      ++failures;                                                                                  \
    }                                                                                              \
  } while (0)

#define PI_CHECK_NEAR(a, b, tol)                                                                   \
  do                                                                                               \
  {                                                                                                \
    const double va_ = (a), vb_ = (b);                                                             \
    if (!(std::fabs(va_ - vb_) <= (tol)))                                                          \
    {                                                                                              \
      std::cerr << __FILE__ << ":" << __LINE__ << ": " #a " = " << va_ << " but " #b " = " << vb_  \
                << " (tolerance " << (tol) << ")" << std::endl;                                    \
      ++failures;                                                                                  \
    }                                                                                              \
  } while (0)

namespace pitest
{
/// The path of a model of Testing/Data/Models ("cup_a1.0" or "cup_a1.0.pisurf").
inline std::string ModelPath(const std::string& name)
{
  const std::string suffix = ".pisurf";
  const bool hasSuffix = name.size() >= suffix.size() &&
    name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0;
  return std::string(PISURF_MODELS_DIR) + "/" + name + (hasSuffix ? "" : suffix);
}

/// The model `name` of Testing/Data/Models in a new vtkPiSurface (LoadModel reports a
/// file that does not load through VTK's error mechanism, which the tests watch).
inline vtkSmartPointer<vtkPiSurface> LoadModel(const std::string& name)
{
  auto surface = vtkSmartPointer<vtkPiSurface>::New();
  surface->LoadModel(ModelPath(name).c_str());
  return surface;
}

/// Compares the window with the test's baseline (-V, -T options in argv; -I shows it
/// interactively) and returns the test's exit code.
inline int RegressionResult(int argc, char* argv[], vtkRenderWindow* window)
{
  const int result = vtkRegressionTestImage(window);
  if (result == vtkRegressionTester::DO_INTERACTOR)
  {
    vtkNew<vtkRenderWindowInteractor> interactor;
    interactor->SetRenderWindow(window);
    interactor->Start();
  }
  return result == vtkRegressionTester::FAILED ? EXIT_FAILURE : EXIT_SUCCESS;
}

/// Uniform random numbers in [lo, hi) from VTK's seeded minimal standard sequence.
class Random
{
public:
  explicit Random(int seed) { this->Sequence->SetSeed(seed); }
  double operator()(double lo, double hi)
  {
    this->Sequence->Next();
    return this->Sequence->GetRangeValue(lo, hi);
  }

private:
  vtkNew<vtkMinimalStandardRandomSequence> Sequence;
};

/// Watches an object's errors and warnings (so expected errors do not reach the
/// output window) and lets a test assert on their text.
struct Watch
{
  vtkNew<vtkTest::ErrorObserver> Observer;
  explicit Watch(vtkObject* o)
  {
    o->AddObserver(vtkCommand::ErrorEvent, this->Observer);
    o->AddObserver(vtkCommand::WarningEvent, this->Observer);
  }
  /// True (and clears) if an error containing `text` was reported.
  bool Error(const std::string& text)
  {
    const bool ok = this->Observer->GetError() &&
      this->Observer->GetErrorMessage().find(text) != std::string::npos;
    if (!ok)
    {
      std::cerr << "expected an error containing '" << text << "', got: '"
                << (this->Observer->GetError() ? this->Observer->GetErrorMessage() : "(none)")
                << "'" << std::endl;
    }
    this->Observer->Clear();
    return ok;
  }
  bool Quiet()
  {
    const bool ok = !this->Observer->GetError();
    if (!ok)
    {
      std::cerr << "unexpected error: " << this->Observer->GetErrorMessage() << std::endl;
    }
    this->Observer->Clear();
    return ok;
  }
};
}

#endif
