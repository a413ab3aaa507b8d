// SPDX-License-Identifier: BSD-3-Clause
#include "PiProductField.h"

#include <stdexcept>
#include <utility>

namespace pisurf
{

ProductField::ProductField(std::shared_ptr<const ProductKernel> kernel)
  : Kernel(std::move(kernel))
{
  if (!this->Kernel)
  {
    throw std::invalid_argument("ProductField needs a kernel");
  }
}

int ProductField::ClassifyBox(const double box[6]) const
{
  return this->Kernel->ClassifyBox(box);
}

double ProductField::Evaluate(const double p[3]) const
{
  return this->Kernel->Evaluate(p);
}

double ProductField::EvaluateCompressed(const double p[3]) const
{
  return this->Kernel->EvaluateCompressed(p);
}

void ProductField::EvaluateVertex(
  const double p[3], double normal[3], double& gradientNorm, int& nearest) const
{
  this->Kernel->EvaluateVertex(p, normal, gradientNorm, nearest);
}
}
