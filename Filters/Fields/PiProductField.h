// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiProductField.h
 * @brief the product of primitives F = Π f_i − r as a pisurf::Field
 *
 * ProductField answers the Field questions with a shared ProductKernel: point values,
 * the compressed form, sign and logarithm, vertex attributes with the singularity
 * probe, box and octant classification, all with the kernel's overflow-safe
 * arithmetic. The grid and segment answers (EvaluateBox, RefineEdge, FirstRoot,
 * OffOuterSide) and CastRay keep their defaults: the kernel's own fast paths (row and
 * ray restrictions, vertex lanes, monotony proofs) are the capability
 * GetProductKernel() that the algorithms take at set-up.
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
  int ClassifyBoxAndOctants(
    const double box[6], int octants[8], bool allOctants = false) const override;
  int EvaluateSignAndLog(const double p[3], double& logAbs) const override;
  /// One pass over the factors (ProductKernel::EvaluateVertexStar) gives the attributes
  /// and the six probe values, compared directly where every quantity is a normal
  /// double and in logarithms otherwise.
  bool ProbeVertex(const double p[3], double probe, double tolerance, double normal[3],
    double& gradientNorm, int& nearest) const override;
  const ProductKernel* GetProductKernel() const override { return this->Kernel.get(); }

  const ProductKernel& GetKernel() const { return *this->Kernel; }

private:
  std::shared_ptr<const ProductKernel> Kernel;
};
}

#endif
