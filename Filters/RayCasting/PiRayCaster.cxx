// SPDX-License-Identifier: BSD-3-Clause
#include "PiRayCaster.h"

#include "PiField.h"
#include "PiFloat.h"
#include "PiProductKernel.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace pisurf
{

RayCaster::RayCaster(const Field& field)
  : TheField(&field)
  , Kernel(field.GetProductKernel())
{
  if (!this->Kernel)
  {
    return;
  }
  for (size_t f = 0; f < this->Kernel->GetNumberOfFactors(); ++f)
  {
    const Factor& factor = this->Kernel->GetFactor(f);
    if (factor.IsPolynomial)
    {
      this->Counts.push_back(std::max(factor.Polynomial.Poly.GetDegree(), 0) + 1);
      this->LineCoefficients += this->Counts.back();
    }
  }
}

void RayCaster::Cast(const double start[3], const double d[3], double length,
  const RayRootOptions& options, std::vector<RayRoot>& roots) const
{
  roots.clear();
  if (this->Kernel && this->Kernel->IsPolynomial())
  {
    thread_local std::vector<double> coefficients;
    coefficients.resize(this->Kernel->GetLineCoefficientCount());
    this->Kernel->RestrictLine(start, d, coefficients.data());
    FindRayRoots(coefficients.data(), this->Counts.data(), static_cast<int>(this->Counts.size()),
      this->Kernel->GetBlending(), 0.0, length, options, roots);
    return;
  }
  this->TheField->CastRay(start, d, 0.0, length, options, roots);
}

void RayCaster::CastRestricted(const double* coefficients, double t0, double t1,
  const RayRootOptions& options, std::vector<RayRoot>& roots) const
{
  roots.clear();
  FindRayRoots(coefficients, this->Counts.data(), static_cast<int>(this->Counts.size()),
    this->Kernel->GetBlending(), t0, t1, options, roots);
}

void RayCaster::CastRestricted(const double* coefficients, const double* cuts, const int* monotone,
  int pieces, const RayRootOptions& options, std::vector<RayRoot>& roots) const
{
  roots.clear();
  FindRayRoots(coefficients, this->Counts.data(), static_cast<int>(this->Counts.size()),
    this->Kernel->GetBlending(), cuts, monotone, pieces, options, roots);
}

RayGrid::RayGrid(const ProductKernel& kernel, const double O[3], const double U[3],
  const double V[3], const double D[3], int w, int h, double length)
  : CentreI(0.5 * (w - 1))
  , CentreJ(0.5 * (h - 1))
  , HalfLength(0.5 * length)
{
  // World point of (i', j', s) with i' = i − CentreI, j' = j − CentreJ.
  double centre[3];
  for (int k = 0; k < 3; ++k)
  {
    centre[k] = O[k] + this->CentreI * U[k] + this->CentreJ * V[k] + this->HalfLength * D[k];
  }
  size_t offset = 0, rowOffset = 0;
  for (size_t f = 0; f < kernel.GetNumberOfFactors(); ++f)
  {
    const Factor& factor = kernel.GetFactor(f);
    if (!factor.IsPolynomial)
    {
      continue;
    }
    const PolynomialFactor& pf = factor.Polynomial;
    // Local coordinates q = A·p + B of p = centre + i'·U + j'·V + s·D.
    double A[3][3], b[3];
    for (int r = 0; r < 3; ++r)
    {
      A[r][0] = pf.A[r][0] * U[0] + pf.A[r][1] * U[1] + pf.A[r][2] * U[2];
      A[r][1] = pf.A[r][0] * V[0] + pf.A[r][1] * V[1] + pf.A[r][2] * V[2];
      A[r][2] = pf.A[r][0] * D[0] + pf.A[r][1] * D[1] + pf.A[r][2] * D[2];
      b[r] = pf.A[r][0] * centre[0] + pf.A[r][1] * centre[1] + pf.A[r][2] * centre[2] + pf.B[r];
    }
    const Polynomial3 g = pf.Poly.Compose(A, b);
    // The line coefficient count follows the factor's degree (as RestrictLine does),
    // even if the composition cancels its top terms.
    const int n = std::max(pf.Poly.GetDegree(), 0);
    const size_t side = static_cast<size_t>(n) + 1;
    this->Factors.push_back({ n, offset, rowOffset });
    this->G.resize(offset + side * side * side, 0.0);
    for (const Monomial& t : g.GetTerms())
    {
      // x -> i', y -> j', z -> s: the power of s is the line coefficient's index.
      if (t.I <= n && t.J <= n && t.K <= n)
      {
        this->G[offset + (t.K * side + t.I) * side + t.J] += t.Coefficient;
      }
    }
    offset += side * side * side;
    rowOffset += side * side;
  }
  this->RowSize = rowOffset;
}

void RayGrid::SetRow(int j, std::vector<double>& row) const
{
  row.resize(this->RowSize);
  const double y = j - this->CentreJ;
  for (const Composed& c : this->Factors)
  {
    const int side = c.Degree + 1;
    for (int m = 0; m <= c.Degree; ++m)
    {
      for (int a = 0; a + m <= c.Degree; ++a)
      {
        // Σ_b g[m][a][b] y^b, b <= deg − m − a.
        const double* g = this->G.data() + c.Offset + (m * side + a) * side;
        double v = 0.0;
        for (int b = c.Degree - m - a; b >= 0; --b)
        {
          v = v * y + g[b];
        }
        row[c.RowOffset + m * side + a] = v;
      }
    }
  }
}

namespace
{
// One factor's coefficients at pixel column x (Horner's rule in x per power of s), for
// degree D (D > 0: the loops unrolled, the same operations) or `degree`.
template <int D>
inline void RestrictComposed(const double* h, int degree, double x, double* coefficients)
{
  const int d = D > 0 ? D : degree;
  const int side = d + 1;
  for (int m = 0; m <= d; ++m)
  {
    const double* hm = h + m * side;
    double v = 0.0;
    for (int a = d - m; a >= 0; --a)
    {
      v = v * x + hm[a];
    }
    coefficients[m] = v;
  }
}
}

void RayGrid::Restrict(const std::vector<double>& row, int i, double* coefficients) const
{
  const double x = i - this->CentreI;
  for (const Composed& c : this->Factors)
  {
    const double* h = row.data() + c.RowOffset;
    switch (c.Degree)
    {
      case 2:
        RestrictComposed<2>(h, 2, x, coefficients);
        break;
      case 4:
        RestrictComposed<4>(h, 4, x, coefficients);
        break;
      default:
        RestrictComposed<0>(h, c.Degree, x, coefficients);
        break;
    }
    coefficients += c.Degree + 1;
  }
}

void RayCaster::PrepareProbes(const double box[6], double probe)
{
  if (this->Kernel)
  {
    this->Probes = this->Kernel->PrepareProbes(box, probe);
  }
}

bool RayCaster::Attributes(const double p[3], double probe, double tolerance, double normal[3],
  double& gradientNorm, int& nearest) const
{
  if (this->Kernel && probe == this->Probes.Probe && probe > 0 &&
    this->Kernel->EvaluateVertexIfRegular(
      p, this->Probes, tolerance, normal, gradientNorm, nearest))
  {
    return false;
  }
  return this->ProbedAttributes(p, probe, tolerance, normal, gradientNorm, nearest);
}

void RayCaster::Attributes(int count, const double (*p)[3], double probe, double tolerance,
  double (*normal)[3], double* gradientNorm, int* nearest, bool* singular) const
{
  // (Other products one point at a time from here, not through
  // EvaluateVerticesIfRegular's own fallback: that calls the single-point code from its
  // AVX2 clone.)
  if (!this->Kernel || !(probe == this->Probes.Probe && probe > 0) ||
    count > ProductKernel::MaxVertices || !this->Kernel->HasStarFactorsOnly())
  {
    for (int j = 0; j < count; ++j)
    {
      singular[j] =
        this->Attributes(p[j], probe, tolerance, normal[j], gradientNorm[j], nearest[j]);
    }
    return;
  }
  bool regular[ProductKernel::MaxVertices];
  this->Kernel->EvaluateVerticesIfRegular(
    count, p, this->Probes, tolerance, normal, gradientNorm, nearest, regular);
  for (int j = 0; j < count; ++j)
  {
    // (a point not proven regular takes the probes)
    singular[j] = !regular[j] &&
      this->ProbedAttributes(p[j], probe, tolerance, normal[j], gradientNorm[j], nearest[j]);
  }
}

bool RayCaster::ProbedAttributes(const double p[3], double probe, double tolerance,
  double normal[3], double& gradientNorm, int& nearest) const
{
  return this->TheField->ProbeVertex(p, probe, tolerance, normal, gradientNorm, nearest);
}

}
