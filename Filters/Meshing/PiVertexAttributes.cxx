// SPDX-License-Identifier: BSD-3-Clause
// PASS 7 of the mesher: vertex positions and attributes (see PiVertexAttributes.h).
#include "PiVertexAttributes.h"

#include "PiParallel.h"
#include "PiRayRoots.h"
#include "vtkAlgorithm.h"
#include "vtkDoubleArray.h"
#include "vtkFloatArray.h"
#include "vtkIntArray.h"
#include "vtkPoints.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

namespace pisurf
{
namespace
{
// PASS 7: vertex positions, each moved to the root of F on its edge (optional), then
// the exact normal, |∇F| and the nearest factor there.
//
// The edge's end points have opposite signs (the sign of F is exact, overflow-safe), so
// the edge brackets a root; the Illinois variant of regula falsi on F (or, where F is
// beyond 1e200 at an end, on the overflow-free sign(F)·ln(1 + |F|)), with bisection
// where the secant leaves the bracket, finds it even where F varies over thousands of
// orders of magnitude along the edge.
struct VertexWorker
{
  const Field* F;
  const ProductKernel* Kernel; // the field's product fast paths, or null
  const BlockGrid* G;
  const pisurf::Buffer<vtkIdType>* VertexEdge;
  const pisurf::Buffer<double>* VertexT;
  const pisurf::Buffer<double>* VertexEnds;
  vtkPoints* Points;
  vtkFloatArray* Normals;
  vtkIntArray* Factor;
  vtkDoubleArray* GradientMagnitude; // may be null
  bool Project;
  double Tolerance;      // stop when the bracket is shorter than this
  bool PositiveEnvelope; // the outer envelope is on and its outside sign is +
  // Progress from 0.75 to 1 and cancel, through the main thread (this pass is the
  // longest for a large molecule).
  vtkAlgorithm* Algorithm;
  std::atomic<bool>* Abort;
  std::atomic<vtkIdType>* Done;
  vtkIdType Total;
  // The sampling's row restrictions (PASS 2), per row (j, k) its index or −1; null for
  // a field.
  const pisurf::LargeVector<vtkIdType>* RowIndex;
  const pisurf::LargeVector<double>* RowCoefficients;
  size_t RowCoefficientCount;

  // Newton's method on F along the edge x = x0 + s·dx, s ∈ [0, 1], from s = t, kept in
  // the bracket the signs give (bisection when a step leaves it), on the factors'
  // restrictions to the edge's line: stops when |F| <= small or a step is shorter than
  // `width` (Newton's error is then about the square of that step). −1 where the plain
  // product cannot be used (then the caller's regula falsi decides).
  static double Newton(const pisurf::ProductKernel* kernel, const double* line, int axis, double x0,
    double dx, double t, double va, double small, double width)
  {
    return NewtonOn(
      [&](double s, double& v, double& slope)
      {
        const bool ok = kernel->EvaluateOnAxisWithSlope(line, axis, x0 + s * dx, v, slope);
        slope *= dx;
        return ok;
      },
      t, va, small, width);
  }

  // The same along an x edge from grid point i of a row whose factors RestrictLine gave
  // (the sampling's own restriction, parameter t = i − mid at the edge's start, one unit
  // per cell): no restriction of its own to compute.
  static double RowNewton(const pisurf::ProductKernel* kernel, const double* row, double t0,
    double t, double va, double small, double width)
  {
    return NewtonOn([&](double s, double& v, double& slope)
      { return kernel->EvaluateRestrictedWithSlope(row, t0 + s, v, slope); },
      t, va, small, width);
  }

  // Newton's method as a state: Step takes F and dF/ds at S (ok false where they cannot
  // be had) and either moves S or finishes with Result (−1: the plain product cannot be
  // used). NewtonOn runs one; the vertex loop runs up to MaxLanes side by side
  // (NewtonLanes), whose chains of dependent operations then overlap.
  struct NewtonLane
  {
    NewtonLane(double t, double va, double small, double width)
      : Va(va)
      , Small(small)
      , Width(width)
      , S(std::max(0.0, std::min(1.0, t)))
    {
    }
    void Step(bool ok, double v, double slope)
    {
      if (!ok)
      {
        this->Finish(-1.0);
        return;
      }
      if (std::fabs(v) <= this->Small)
      {
        this->Finish(this->S);
        return;
      }
      ((v < 0) == (this->Va < 0) ? this->Lo : this->Hi) = this->S;
      if (this->Hi - this->Lo <= this->Width)
      {
        this->Finish(0.5 * (this->Lo + this->Hi));
        return;
      }
      double next = this->S - v / slope;
      const bool newton = next > this->Lo && next < this->Hi;
      if (!newton)
      {
        next = 0.5 * (this->Lo + this->Hi);
      }
      const double step = std::fabs(next - this->S);
      this->S = next;
      if (step <= this->Width)
      {
        this->Finish(this->S);
        return;
      }
      // Converging quadratically (this step at most a quarter of the last): the error
      // after it is about C·step² with C ≈ step / last², so when step³ / last² is below
      // a sixteenth of the width the next evaluation would only confirm it.
      const double last = this->Last;
      if (newton && last > 0.0 && step <= 0.25 * last &&
        step * step * step <= this->Width * last * last / 16)
      {
        this->Finish(this->S);
        return;
      }
      this->Last = newton ? step : 0.0;
      if (++this->Iterations >= 60)
      {
        this->Finish(this->S);
      }
    }
    void Finish(double result)
    {
      this->Result = result;
      this->Done = true;
    }
    double Va, Small, Width;
    double Lo = 0.0, Hi = 1.0, S;
    double Last = 0.0; // the last Newton step (0: none, or a bisection)
    int Iterations = 0;
    bool Done = false;
    double Result = -1.0;
  };

  // Newton's loop for both: `evaluate(s, F, dF/ds)`, false where it cannot.
  template <typename Evaluate>
  static double NewtonOn(Evaluate&& evaluate, double t, double va, double small, double width)
  {
    NewtonLane lane(t, va, small, width);
    while (!lane.Done)
    {
      double v, slope;
      const bool ok = evaluate(lane.S, v, slope);
      lane.Step(ok, v, slope);
    }
    return lane.Result;
  }

  // The same for products whose F leaves the double range (thousands of factors, or F
  // beyond 1e200 at an end): Newton's method on F with the product kept as a logarithm
  // (the step (1 − r/P) / Σ f_i'/f_i needs only ln|P| and Σ f_i'/f_i), safeguarded by
  // bisection in the bracket the exact sign of F gives.
  // −1 when r = 0 (the roots are a factor's zeros: the caller's regula falsi).
  static double LogNewton(const pisurf::ProductKernel* kernel, const double* line, int axis,
    double x0, double dx, double t, double va, double width)
  {
    const double r = kernel->GetBlending();
    if (r == 0.0)
    {
      return -1.0;
    }
    const double logR = std::log(std::fabs(r));
    const int signR = r > 0 ? 1 : -1;
    double lo = 0.0, hi = 1.0, s = std::max(0.0, std::min(1.0, t));
    double last = 1.0, older = 1.0; // the last two steps
    for (int it = 0; it < 100; ++it)
    {
      double F, logP, slope;
      int signP;
      kernel->EvaluateOnAxisLog(line, axis, x0 + s * dx, F, signP, logP, slope);
      if (F == 0.0)
      {
        return s;
      }
      ((F < 0) == (va < 0) ? lo : hi) = s;
      if (hi - lo <= width)
      {
        return 0.5 * (lo + hi);
      }
      // F' = P·Σ f_i'/f_i, so the Newton step on F is (1 − r/P) / Σ f_i'/f_i, with r/P
      // from the logarithms (never overflows; inf only where P is far below r);
      // bisection where P = 0, where the step leaves the bracket, or where it is not
      // half the step before the last (Newton crawling down an exponential-like F).
      double next = 0.5 * (lo + hi);
      if (signP != 0 && std::isfinite(slope) && slope != 0.0)
      {
        const double ratio = (signP == signR ? 1.0 : -1.0) * std::exp(logR - logP);
        const double newton = s - (1.0 - ratio) / (slope * dx);
        if (newton > lo && newton < hi && std::fabs(newton - s) <= 0.5 * older)
        {
          next = newton;
        }
      }
      const double step = std::fabs(next - s);
      older = last;
      last = step;
      s = next;
      if (step <= width)
      {
        return s;
      }
    }
    return 0.5 * (lo + hi);
  }

  // `row`: for an x edge, its grid row's restriction from the sampling (RestrictLine's
  // coefficients, the edge starting at parameter rowT0), or null.
  double Refine(const double a[3], const double b[3], double t, double va, double vb,
    const double* row = nullptr, double rowT0 = 0.0) const
  {
    // A field that can certify the first root from the positive end in one pass (see
    // pisurf::Field::FirstRoot): the root nearest the outside, as the general method
    // below would pick.
    {
      const bool bracket = (va > 0 && vb < 0) || (va < 0 && vb > 0);
      const bool thinWall = va > 0 && vb > 0 && (t == 0.0 || t == 1.0);
      if (bracket || thinWall)
      {
        const bool fromA = bracket ? va > 0 : t == 0.0;
        double s;
        if (this->F->FirstRoot(fromA ? a : b, fromA ? b : a, this->Tolerance, s))
        {
          return fromA ? s : 1.0 - s;
        }
      }
    }
    // F itself is nearly linear along a short edge, and cheapest (its values at the ends
    // are the grid's); where it is beyond 1e200 at an end, its compressed form
    // sign(F)·ln(1 + |F|) is used instead.
    bool compressed = false;
    auto phi = [&](const double x[3])
    { return compressed ? this->F->EvaluateCompressed(x) : this->F->Evaluate(x); };
    if (!(std::fabs(va) < 1e200 && std::fabs(vb) < 1e200))
    {
      compressed = true;
      va = phi(a);
      vb = phi(b);
    }
    // A product of axis-aligned polynomial factors restricted to the edge's line once
    // (one pass over each factor's terms); each step is then Horner's rule on the
    // univariate polynomials instead of a trivariate evaluation.
    int axis = 0;
    while (axis < 2 && a[axis] == b[axis])
    {
      ++axis;
    }
    const pisurf::ProductKernel* kernel = this->Kernel;
    const double length = std::fabs(b[0] - a[0]) + std::fabs(b[1] - a[1]) + std::fabs(b[2] - a[2]);
    if (row && kernel && !compressed && ((va < 0 && vb > 0) || (va > 0 && vb < 0)))
    {
      // An x edge: Newton's method on the row's restriction, already made for the
      // sampling (a product kernel has no outer-side test: its root is the answer).
      const double root = RowNewton(kernel, row, rowT0, t, va,
        1e-12 * std::max(std::fabs(va), std::fabs(vb)), this->Tolerance / length);
      if (root >= 0.0)
      {
        return root;
      }
    }
    return this->RefineOnLine(a, b, t, va, vb, compressed, axis, kernel, length);
  }

  // Refine once F's form (plain or compressed) and the edge's axis are known: the root
  // on the edge's line by the fastest method that applies, then the outer sheet where
  // the envelope is positive.
  double RefineOnLine(const double a[3], const double b[3], double t, double va, double vb,
    bool compressed, int axis, const pisurf::ProductKernel* kernel, double length) const
  {
    auto phi = [&](const double x[3])
    { return compressed ? this->F->EvaluateCompressed(x) : this->F->Evaluate(x); };
    auto pointAt = [&](double s, double x[3])
    {
      for (int k = 0; k < 3; ++k)
      {
        x[k] = a[k] + s * (b[k] - a[k]);
      }
    };
    // On the stack for the usual few factors (a thread_local costs a TLS lookup per
    // vertex in a shared library).
    constexpr size_t StackCoefficients = 256;
    double stackLine[StackCoefficients];
    double* line = stackLine;
    if (kernel && kernel->GetLineCoefficientCount() > StackCoefficients)
    {
      thread_local std::vector<double> heapLine;
      heapLine.resize(kernel->GetLineCoefficientCount());
      line = heapLine.data();
    }
    const bool restricted = kernel && kernel->RestrictToAxis(a, axis, line);
    const bool onAxis = restricted && !compressed;
    auto along = [&](double s)
    {
      if (onAxis)
      {
        return kernel->EvaluateOnAxis(line, axis, a[axis] + s * (b[axis] - a[axis]));
      }
      double x[3];
      pointAt(s, x);
      return phi(x);
    };
    auto offOuterSide = [&](double s)
    {
      double x[3];
      pointAt(s, x);
      return this->F->OffOuterSide(x);
    };
    // The root between s0 and s1 (either order), where F is f0 and f1 of opposite signs.
    auto rootBetween = [&](double s0, double f0, double s1, double f1)
    {
      const double lo = std::min(s0, s1), hi = std::max(s0, s1);
      const double flo = s0 < s1 ? f0 : f1, fhi = s0 < s1 ? f1 : f0;
      return pisurf::BracketedRoot(along, lo, hi, flo, fhi, this->Tolerance / length,
        1e-12 * std::max(std::fabs(flo), std::fabs(fhi)));
    };
    // The first sign change stepping from the end `from` (0 or 1) towards the other:
    // the surface nearest that end; `from` itself if F keeps its sign at every step.
    auto firstCrossing = [&](double from)
    {
      constexpr int Steps = 16;
      double s0 = from, f0 = from == 0.0 ? va : vb;
      for (int m = 1; m <= Steps; ++m)
      {
        const double s1 = from == 0.0 ? double(m) / Steps : 1.0 - double(m) / Steps;
        const double f1 = m == Steps ? (from == 0.0 ? vb : va) : along(s1);
        if (f1 == 0.0)
        {
          return s1;
        }
        if ((f0 > 0) != (f1 > 0))
        {
          return rootBetween(s0, f0, s1, f1);
        }
        s0 = s1;
        f0 = f1;
      }
      return from;
    };
    // From the positive end `from` (on the outer side) to `to` (off it): where the edge
    // leaves the outer side, found by bisection; if F is negative just before it (the
    // thin wall), the root in between is on the outer sheet. -1 if not.
    auto outerCrossing = [&](double from, double to)
    {
      double out = from, off = to;
      for (int m = 0; m < 64 && std::fabs(off - out) * length > this->Tolerance; ++m)
      {
        const double mid = 0.5 * (out + off);
        (offOuterSide(mid) ? off : out) = mid;
      }
      const double fOut = along(out), fFrom = from == 0.0 ? va : vb;
      if (!(fFrom > 0))
      {
        return -1.0;
      }
      if (fOut < 0)
      {
        return rootBetween(from, fFrom, out, fOut);
      }
      // F huge (the surface hugs the wall): the root is within the tolerance after `out`.
      const double fOff = along(off);
      return fOff < 0 ? rootBetween(out, fOut, off, fOff) : out;
    };
    if ((va > 0 && vb > 0) || (va < 0 && vb < 0))
    {
      // Ends of one sign: the edge enters a thin wall the grid does not resolve (the
      // envelope gave the far end the other sign, see BlockContour's Write pass, and t is the end
      // whose sign is its own): the surface nearest to that end.
      if (t != 0.0 && t != 1.0)
      {
        return t;
      }
      const double crossing = firstCrossing(t);
      if (this->PositiveEnvelope && va > 0 && (crossing == t || offOuterSide(crossing)) &&
        offOuterSide(1.0 - t))
      {
        const double outer = outerCrossing(t, 1.0 - t);
        return outer >= 0 ? outer : crossing;
      }
      return crossing;
    }
    if (!(va < 0 && vb > 0) && !(va > 0 && vb < 0))
    {
      return t; // no strict bracket (an end exactly on F = 0): keep the interpolation
    }
    // |F| below 1e-12 of its values at the ends: the root is within ~1e-12 of an edge.
    const double small = 1e-12 * std::max(std::fabs(va), std::fabs(vb));
    double root = -1.0;
    if (onAxis)
    {
      root = this->Newton(
        kernel, line, axis, a[axis], b[axis] - a[axis], t, va, small, this->Tolerance / length);
    }
    if (root < 0.0 && restricted)
    {
      // (Where F is beyond 1e200 at an end, t leans on that end: start from the
      // interpolation of sign(F)·ln(1 + |F|) instead.)
      const double start = compressed && va != vb ? va / (va - vb) : t;
      root = LogNewton(
        kernel, line, axis, a[axis], b[axis] - a[axis], start, va, this->Tolerance / length);
    }
    if (root < 0.0)
    {
      root = pisurf::BracketedRoot(along, 0.0, 1.0, va, vb, this->Tolerance / length, small);
    }
    if (this->PositiveEnvelope && offOuterSide(root))
    {
      // A root of a bounded component's sheet (the edge runs outside, wall, lens, wall):
      // the outer sheet is the crossing nearest the positive end.
      const double from = va > 0 ? 0.0 : 1.0;
      const double crossing = firstCrossing(from);
      if (crossing != from && !offOuterSide(crossing))
      {
        return crossing;
      }
      const double outer = outerCrossing(from, root);
      return outer >= 0 ? outer : root;
    }
    return root;
  }

  // One vertex's edge: its ends a and b (from the edge key), the grid's values there and
  // the linear interpolation t.
  struct Edge
  {
    double A[3], B[3];
    int Axis, Index[3];
    double T, Va, Vb;
  };

  void Decode(vtkIdType id, bool narrow, Edge& e) const
  {
    const int* d = this->G->Dims;
    const vtkIdType key = (*this->VertexEdge)[id];
    if (narrow)
    {
      const std::uint32_t k32 = static_cast<std::uint32_t>(key);
      std::uint32_t p = k32 / 3;
      e.Axis = static_cast<int>(k32 - 3 * p);
      const std::uint32_t row = p / static_cast<std::uint32_t>(d[0]);
      e.Index[0] = static_cast<int>(p - row * static_cast<std::uint32_t>(d[0]));
      const std::uint32_t plane = row / static_cast<std::uint32_t>(d[1]);
      e.Index[1] = static_cast<int>(row - plane * static_cast<std::uint32_t>(d[1]));
      e.Index[2] = static_cast<int>(plane);
    }
    else
    {
      e.Axis = static_cast<int>(key % 3);
      const vtkIdType p = key / 3;
      e.Index[0] = static_cast<int>(p % d[0]);
      e.Index[1] = static_cast<int>((p / d[0]) % d[1]);
      e.Index[2] = static_cast<int>(p / (vtkIdType(d[0]) * d[1]));
    }
    for (int k = 0; k < 3; ++k)
    {
      e.A[k] = this->G->Origin[k] + e.Index[k] * this->G->Spacing[k];
      e.B[k] = e.A[k] + (k == e.Axis ? this->G->Spacing[k] : 0.0);
    }
    e.T = (*this->VertexT)[id];
    e.Va = (*this->VertexEnds)[2 * id];
    e.Vb = (*this->VertexEnds)[2 * id + 1];
  }

  // An x edge's row restriction from the sampling, or null (rowT0: the edge's start on it).
  const double* RowOf(const Edge& e, double& rowT0) const
  {
    rowT0 = 0.0;
    if (e.Axis != 0 || !this->RowIndex || !this->RowCoefficients || this->RowCoefficients->empty())
    {
      return nullptr;
    }
    const int* d = this->G->Dims;
    const vtkIdType r = (*this->RowIndex)[vtkIdType(e.Index[2]) * d[1] + e.Index[1]];
    if (r < 0)
    {
      return nullptr;
    }
    rowT0 = e.Index[0] - 0.5 * (d[0] - 1);
    return this->RowCoefficients->data() + r * this->RowCoefficientCount;
  }

  // Refine's usual case for a product kernel, set up to run beside other vertices': a
  // strict bracket of plain values, Newton's method on the factors evaluated at the
  // edge's points, four edges per vector instruction, where every factor is an
  // axis-aligned quadric or quartic in the squares (ProductKernel::HasStarFactorsOnly);
  // otherwise on the row's restriction (an x edge) or on the factors restricted to the
  // edge's line. Where Newton cannot decide (−1), Refine takes the vertex from the start
  // (the same steps, then its fallbacks).
  static constexpr int MaxLanes = pisurf::ProductKernel::MaxVertices;
  struct Lane
  {
    Edge E;
    const double* Row = nullptr;
    double RowT0 = 0.0;
    double Line[256]; // RestrictToAxis's coefficients, for the other edges
    double X0 = 0.0, Dx = 0.0;
    NewtonLane Newton{ 0.0, 0.0, 0.0, 0.0 };
    vtkIdType Id = 0;
  };

  // Sets `lane` up for the vertex whose edge is e; false where Refine's usual case does
  // not apply (the caller then takes the general path).
  bool Prepare(const Edge& e, Lane& lane) const
  {
    const pisurf::ProductKernel* kernel = this->Kernel;
    const bool bracket = (e.Va < 0 && e.Vb > 0) || (e.Va > 0 && e.Vb < 0);
    if (!this->Project || !kernel || !bracket ||
      !(std::fabs(e.Va) < 1e200 && std::fabs(e.Vb) < 1e200))
    {
      return false;
    }
    const int axis = e.Axis;
    // (Star factors only: NewtonLanes evaluates them at the edge's points themselves.)
    const bool star = kernel->HasStarFactorsOnly();
    lane.Row = star ? nullptr : this->RowOf(e, lane.RowT0);
    if (!star && !lane.Row)
    {
      if (kernel->GetLineCoefficientCount() > sizeof(lane.Line) / sizeof(double) ||
        !kernel->RestrictToAxis(e.A, axis, lane.Line))
      {
        return false;
      }
    }
    lane.E = e;
    lane.X0 = e.A[axis];
    lane.Dx = e.B[axis] - e.A[axis];
    const double length =
      std::fabs(e.B[0] - e.A[0]) + std::fabs(e.B[1] - e.A[1]) + std::fabs(e.B[2] - e.A[2]);
    lane.Newton = NewtonLane(
      e.T, e.Va, 1e-12 * std::max(std::fabs(e.Va), std::fabs(e.Vb)), this->Tolerance / length);
    return true;
  }

  // F and dF/ds at the lane's s: RowNewton's and Newton's evaluations.
  bool EvaluateLane(const Lane& lane, double& v, double& slope) const
  {
    const pisurf::ProductKernel* kernel = this->Kernel;
    const double s = lane.Newton.S;
    if (lane.Row)
    {
      return kernel->EvaluateRestrictedWithSlope(lane.Row, lane.RowT0 + s, v, slope);
    }
    const bool ok =
      kernel->EvaluateOnAxisWithSlope(lane.Line, lane.E.Axis, lane.X0 + s * lane.Dx, v, slope);
    slope *= lane.Dx;
    return ok;
  }

  // Newton's method on several lanes at once (each lane's own steps, interleaved): the
  // evaluations of all unfinished lanes, then their steps.
  void NewtonLanes(Lane* lanes, int count) const
  {
    // Star factors only: every lane at once, as vector lanes (ProductKernel::
    // EvaluateOnSegments), the finished ones too (their results unused).
    const pisurf::ProductKernel* kernel = this->Kernel;
    const bool star = kernel->HasStarFactorsOnly();
    double a[MaxLanes][3], d[MaxLanes][3];
    for (int k = 0; star && k < count; ++k)
    {
      for (int c = 0; c < 3; ++c)
      {
        a[k][c] = lanes[k].E.A[c];
        d[k][c] = lanes[k].E.B[c] - lanes[k].E.A[c];
      }
    }
    for (;;)
    {
      double s[MaxLanes], v[MaxLanes], slope[MaxLanes];
      bool ok[MaxLanes];
      bool any = false;
      for (int k = 0; k < count; ++k)
      {
        s[k] = lanes[k].Newton.S;
        any = any || !lanes[k].Newton.Done;
      }
      if (!any)
      {
        return;
      }
      if (star)
      {
        kernel->EvaluateOnSegments(count, a, d, s, v, slope, ok);
      }
      else
      {
        for (int k = 0; k < count; ++k)
        {
          if (!lanes[k].Newton.Done)
          {
            ok[k] = this->EvaluateLane(lanes[k], v[k], slope[k]);
          }
        }
      }
      for (int k = 0; k < count; ++k)
      {
        if (!lanes[k].Newton.Done)
        {
          lanes[k].Newton.Step(ok[k], v[k], slope[k]);
        }
      }
    }
  }

  // Output arrays, for Write.
  struct Outputs
  {
    double* Xyz;
    float* Normals;
    int* Factors;
    double* Magnitudes; // may be null
  };

  // The vertex at x: the exact normal, |∇F| and the nearest factor there, written out.
  void Finish(vtkIdType id, const double x[3], const Outputs& out) const
  {
    double n[3], gradientNorm;
    int nearest;
    this->F->EvaluateVertex(x, n, gradientNorm, nearest);
    this->Write(id, x, n, gradientNorm, nearest, out);
  }

  static void Write(vtkIdType id, const double x[3], const double n[3], double gradientNorm,
    int nearest, const Outputs& out)
  {
    for (int k = 0; k < 3; ++k)
    {
      out.Xyz[3 * id + k] = x[k];
      out.Normals[3 * id + k] = static_cast<float>(n[k]);
    }
    out.Factors[id] = nearest;
    if (out.Magnitudes)
    {
      out.Magnitudes[id] = gradientNorm;
    }
  }

  // Every other vertex: a field's one-pass edge (RefineEdge), or Refine's general path.
  void General(vtkIdType id, const Edge& e, const Outputs& out) const
  {
    const double va = e.Va, vb = e.Vb;
    double t = e.T;
    // The field restricted to the edge, in one call: Refine's root of a strict bracket,
    // or the crossing nearest the end t where the ends have one sign (a thin wall),
    // and EvaluateVertex's answers there. A root off the outer side takes the general
    // path below, which looks for the outer sheet.
    const bool bracket = (va < 0 && vb > 0) || (va > 0 && vb < 0);
    const bool thinWall = ((va > 0 && vb > 0) || (va < 0 && vb < 0)) && (t == 0.0 || t == 1.0);
    pisurf::Field::EdgeVertex fast;
    double x[3];
    if (this->Project && (bracket || thinWall) && std::fabs(va) < 1e200 && std::fabs(vb) < 1e200 &&
      this->F->RefineEdge(
        e.A, e.B, va, vb, bracket ? -1 : static_cast<int>(t), this->Tolerance, fast) &&
      !(this->PositiveEnvelope && fast.OffOuterSide))
    {
      for (int k = 0; k < 3; ++k)
      {
        x[k] = e.A[k] + fast.S * (e.B[k] - e.A[k]);
      }
      this->Write(id, x, fast.Normal, fast.GradientNorm, fast.Nearest, out);
      return;
    }
    if (this->Project)
    {
      double rowT0;
      const double* row = this->RowOf(e, rowT0);
      t = this->Refine(e.A, e.B, t, va, vb, row, rowT0);
    }
    for (int k = 0; k < 3; ++k)
    {
      x[k] = e.A[k] + t * (e.B[k] - e.A[k]);
    }
    this->Finish(id, x, out);
  }

  // The lanes' vertices once their Newton has finished: each root (Refine's general path
  // where Newton could not decide), then the attributes there, all lanes at once.
  void FinishLanes(const Lane* lanes, int count, const Outputs& out) const
  {
    double x[MaxLanes][3], n[MaxLanes][3], gradientNorm[MaxLanes];
    int nearest[MaxLanes];
    for (int j = 0; j < count; ++j)
    {
      const Edge& e = lanes[j].E;
      double t = lanes[j].Newton.Result;
      if (t < 0.0)
      {
        double rowT0;
        const double* row = this->RowOf(e, rowT0);
        t = this->Refine(e.A, e.B, e.T, e.Va, e.Vb, row, rowT0);
      }
      for (int k = 0; k < 3; ++k)
      {
        x[j][k] = e.A[k] + t * (e.B[k] - e.A[k]);
      }
    }
    // (Lanes exist only for a product kernel.)
    this->Kernel->EvaluateVertices(count, x, n, gradientNorm, nearest);
    for (int j = 0; j < count; ++j)
    {
      this->Write(lanes[j].Id, x[j], n[j], gradientNorm[j], nearest[j], out);
    }
  }

  void operator()(vtkIdType begin, vtkIdType end)
  {
    if (pisurf::SingleThread())
    {
      if (this->Algorithm->CheckAbort())
      {
        *this->Abort = true;
      }
      else
      {
        this->Algorithm->UpdateProgress(
          0.75 + 0.25 * (static_cast<double>(*this->Done) / std::max<vtkIdType>(this->Total, 1)));
      }
    }
    if (*this->Abort)
    {
      return;
    }
    *this->Done += end - begin;
    const int* d = this->G->Dims;
    // Edge keys of grids below 2^32 keys decode with 32-bit divisions (several times
    // faster than 64-bit ones on common CPUs).
    const bool narrow = 3.0 * d[0] * d[1] * d[2] < 4294967296.0;
    const Outputs out{ vtkDoubleArray::FastDownCast(this->Points->GetData())->GetPointer(0),
      this->Normals->GetPointer(0), this->Factor->GetPointer(0),
      this->GradientMagnitude ? this->GradientMagnitude->GetPointer(0) : nullptr };
    // Vertices MaxLanes at a time where they take Refine's usual case (their Newton
    // chains side by side); any other vertex takes the general path at once.
    Lane lanes[MaxLanes];
    int ready = 0;
    for (vtkIdType id = begin; id < end; ++id)
    {
      Edge e;
      this->Decode(id, narrow, e);
      if (!this->Prepare(e, lanes[ready]))
      {
        this->General(id, e, out);
        continue;
      }
      lanes[ready].Id = id;
      if (++ready == MaxLanes || id + 1 == end)
      {
        this->NewtonLanes(lanes, ready);
        this->FinishLanes(lanes, ready, out);
        ready = 0;
      }
    }
    if (ready > 0)
    {
      this->NewtonLanes(lanes, ready);
      this->FinishLanes(lanes, ready, out);
    }
  }
};
}

void VertexAttributes::Run() const
{
  const ProductKernel* kernel = this->TheField->GetProductKernel();
  std::atomic<vtkIdType> done{ 0 };
  VertexWorker worker{ this->TheField, kernel, this->G, this->VertexEdge, this->VertexT,
    this->VertexEnds, this->Points, this->Normals, this->Factor, this->GradientMagnitude,
    this->Project, this->Tolerance, this->PositiveEnvelope, this->Algorithm, this->Abort, &done,
    this->Vertices, kernel ? &this->Rows->RowIndex : nullptr,
    kernel ? &this->Rows->Coefficients : nullptr, kernel ? kernel->GetLineCoefficientCount() : 0 };
  // Chunks of 4096 vertices: the main thread reports and checks for a cancel between them.
  pisurf::ParallelFor(0, this->Vertices, 4096, worker);
}
}
