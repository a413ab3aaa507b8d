// SPDX-License-Identifier: BSD-3-Clause
// Small helpers shared by the VTK-level tests.
#ifndef PiTestUtilities_h
#define PiTestUtilities_h

#include "vtkCommand.h"
#include "vtkNew.h"
#include "vtkObject.h"
#include "vtkTestErrorObserver.h"

#include <cmath>
#include <iostream>
#include <string>

#define PI_CHECK(cond)                                                                     \
  do                                                                                       \
  {                                                                                        \
    if (!(cond))                                                                           \
    {                                                                                      \
      std::cerr << __FILE__ << ":" << __LINE__ << ": check failed: " #cond << std::endl;   \
      ++failures;                                                                          \
    }                                                                                      \
  } while (0)

#define PI_CHECK_NEAR(a, b, tol)                                                           \
  do                                                                                       \
  {                                                                                        \
    const double va_ = (a), vb_ = (b);                                                     \
    if (!(std::fabs(va_ - vb_) <= (tol)))                                                  \
    {                                                                                      \
      std::cerr << __FILE__ << ":" << __LINE__ << ": " #a " = " << va_ << " but " #b " = " \
                << vb_ << " (tolerance " << (tol) << ")" << std::endl;                     \
      ++failures;                                                                          \
    }                                                                                      \
  } while (0)

namespace pitest
{
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
    const bool ok =
      this->Observer->GetError() && this->Observer->GetErrorMessage().find(text) != std::string::npos;
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
