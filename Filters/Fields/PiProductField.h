// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiProductField.h
 * @brief the product of primitives F = Π f_i − r as a pisurf::Field
 *
 * ProductField answers the Field questions with a shared ProductKernel: point values,
 * the compressed form, vertex attributes and box classification, all with the kernel's
 * overflow-safe arithmetic. The optional Field answers (EvaluateBox, RefineEdge,
 * FirstRoot, OffOuterSide) keep their defaults: the kernel's own fast paths (row
 * restrictions, vertex lanes, monotony proofs) are reached through GetKernel().
 */
#ifndef PiProductField_h
#define PiProductField_h

#include "PiField.h"
#include "PiProductKernel.h"

#include <memory>

namespace pisurf
{

class ProductField : public Field
{
public:
  explicit ProductField(std::shared_ptr<const ProductKernel> kernel);

  int ClassifyBox(const double box[6]) const override;
  double Evaluate(const double p[3]) const override;
  double EvaluateCompressed(const double p[3]) const override;
  void EvaluateVertex(
    const double p[3], double normal[3], double& gradientNorm, int& nearest) const override;

  const ProductKernel& GetKernel() const { return *this->Kernel; }

private:
  std::shared_ptr<const ProductKernel> Kernel;
};
}

#endif
