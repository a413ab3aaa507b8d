// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiFlyingEdges.h"

#include "PiModel.h"
#include "PiProduct.h"
#include "vtkPiSurface.h"

#include "vtkCellArray.h"
#include "vtkDoubleArray.h"
#include "vtkFieldData.h"
#include "vtkFlyingEdges3D.h"
#include "vtkFloatArray.h"
#include "vtkGarbageCollector.h"
#include "vtkImageData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtkStringArray.h"

#include <atomic>
#include <cmath>

vtkStandardNewMacro(vtkPiFlyingEdges);
vtkCxxSetObjectMacro(vtkPiFlyingEdges, PiSurface, vtkPiSurface);

vtkPiFlyingEdges::vtkPiFlyingEdges()
{
  this->SetNumberOfInputPorts(0);
}

vtkPiFlyingEdges::~vtkPiFlyingEdges()
{
  this->SetPiSurface(nullptr);
}

vtkMTimeType vtkPiFlyingEdges::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  if (this->PiSurface)
  {
    t = std::max(t, this->PiSurface->GetMTime());
  }
  return t;
}

void vtkPiFlyingEdges::ReportReferences(vtkGarbageCollector* collector)
{
  this->Superclass::ReportReferences(collector);
  vtkGarbageCollectorReport(collector, this->PiSurface, "PiSurface");
}

namespace
{
// Grid blocks of BlockCells³ cells are classified first; only points of blocks the
// surface may cross are evaluated.
constexpr int BlockCells = 8;

struct BlockGrid
{
  int Count[3]; // blocks per axis
  std::vector<signed char> Sign; // +1/−1: F has that sign on the whole block; 0: active

  vtkIdType Index(int bx, int by, int bz) const
  {
    return (vtkIdType(bz) * this->Count[1] + by) * this->Count[0] + bx;
  }
};

// PASS 1: interval bounds of F over each block.
struct ClassifyBlocks
{
  const pisurf::ProductKernel* Kernel;
  const int* Dims;
  const double* Origin;
  const double* Spacing;
  BlockGrid* Blocks;

  void operator()(vtkIdType begin, vtkIdType end)
  {
    for (vtkIdType b = begin; b < end; ++b)
    {
      const int c[3] = { int(b % this->Blocks->Count[0]),
        int((b / this->Blocks->Count[0]) % this->Blocks->Count[1]),
        int(b / (vtkIdType(this->Blocks->Count[0]) * this->Blocks->Count[1])) };
      double box[6];
      for (int a = 0; a < 3; ++a)
      {
        const int i0 = c[a] * BlockCells, i1 = std::min(i0 + BlockCells, this->Dims[a] - 1);
        box[2 * a] = this->Origin[a] + i0 * this->Spacing[a];
        box[2 * a + 1] = this->Origin[a] + i1 * this->Spacing[a];
      }
      this->Blocks->Sign[b] = static_cast<signed char>(this->Kernel->ClassifyBox(box));
    }
  }
};

// PASS 2: samples F on the grid, one row (fixed j, k) per work item. Points that lie
// only in blocks the surface cannot cross get ±1 (their sign is known); the others are
// evaluated exactly, segment by segment, with the factors restricted to the row.
struct SampleRows
{
  const pisurf::ProductKernel* Kernel;
  const int* Dims;
  const double* Origin;
  const double* Spacing;
  const BlockGrid* Blocks;
  double* Values;
  vtkPiFlyingEdges* Algorithm;
  std::atomic<bool>* Abort;

  // The blocks along one axis that contain grid index i.
  static int Containing(int i, int count, int out[2])
  {
    int n = 0;
    if (i / BlockCells < count)
    {
      out[n++] = i / BlockCells;
    }
    if (i % BlockCells == 0 && i > 0)
    {
      out[n++] = i / BlockCells - 1;
    }
    return n;
  }

  void operator()(vtkIdType begin, vtkIdType end)
  {
    const bool single = vtkSMPTools::GetSingleThread();
    const double step[3] = { this->Spacing[0], 0.0, 0.0 };
    const int nx = this->Dims[0];
    std::vector<signed char> sign(nx);
    for (vtkIdType row = begin; row < end; ++row)
    {
      if (single && (row - begin) % 64 == 0 && this->Algorithm->CheckAbort())
      {
        *this->Abort = true;
      }
      if (*this->Abort)
      {
        return;
      }
      const int j = static_cast<int>(row % this->Dims[1]);
      const int k = static_cast<int>(row / this->Dims[1]);
      int ys[2], zs[2], xs[2];
      const int ny = Containing(j, this->Blocks->Count[1], ys);
      const int nz = Containing(k, this->Blocks->Count[2], zs);
      // sign[i]: the known sign of point i, or 0 if it must be evaluated.
      for (int i = 0; i < nx; ++i)
      {
        const int n = Containing(i, this->Blocks->Count[0], xs);
        signed char s = 1;
        for (int a = 0; a < n && s != 0; ++a)
        {
          for (int b = 0; b < ny && s != 0; ++b)
          {
            for (int c = 0; c < nz && s != 0; ++c)
            {
              const signed char bs = this->Blocks->Sign[this->Blocks->Index(xs[a], ys[b], zs[c])];
              s = bs == 0 ? 0 : bs;
            }
          }
        }
        sign[i] = s;
      }
      double* v = this->Values + row * nx;
      for (int i = 0; i < nx;)
      {
        if (sign[i] != 0)
        {
          v[i] = sign[i];
          ++i;
          continue;
        }
        int e = i;
        while (e < nx && sign[e] == 0)
        {
          ++e;
        }
        const double o[3] = { this->Origin[0] + i * this->Spacing[0],
          this->Origin[1] + j * this->Spacing[1], this->Origin[2] + k * this->Spacing[2] };
        this->Kernel->EvaluateLine(o, step, e - i, v + i);
        // Compress to sign(F)·ln(1 + |F|): same signs and zero set, but finite
        // differences between neighbours, so interpolated vertices stay strictly
        // inside their edges.
        for (int m = i; m < e; ++m)
        {
          v[m] = std::copysign(std::log1p(std::fabs(v[m])), v[m]);
        }
        i = e;
      }
    }
  }
};

// Moves each vertex onto F = 0 (optional), then takes the exact normal and the
// nearest factor there.
//
// Flying edges puts every vertex on a grid edge whose two samples have opposite signs;
// the sign of F is exact (overflow-safe), so the edge brackets a root. The vertex is
// moved to that root by the Illinois variant of regula falsi on F (or, where F is
// beyond 1e200 at an end of the edge, on the overflow-free sign(F)·ln(1 + |F|)), with
// bisection where the secant leaves the bracket: it converges even where F varies over
// thousands of orders of magnitude along the edge.
struct VertexAttributes
{
  const pisurf::ProductKernel* Kernel;
  vtkPoints* IndexPoints; // flying edges' vertices, in grid index coordinates
  vtkPoints* Points;      // the output vertices, in world coordinates (double)
  vtkFloatArray* Normals;
  vtkIntArray* Factor;
  bool Project;
  const double* Origin;
  const double* Spacing;
  double Tolerance; // stop when the bracket is shorter than this

  // The grid edge [a, b] (world coordinates) of a vertex given in index coordinates:
  // flying edges ran on a unit grid, where on-grid coordinates are exact integers even
  // in float. False if the vertex is a grid point.
  bool FindEdge(const double t[3], double a[3], double b[3]) const
  {
    int offAxis = -1;
    for (int k = 0; k < 3; ++k)
    {
      const double lo = std::floor(t[k]);
      a[k] = this->Origin[k] + lo * this->Spacing[k];
      b[k] = a[k];
      if (t[k] != lo)
      {
        if (offAxis >= 0)
        {
          return false;
        }
        offAxis = k;
        b[k] = this->Origin[k] + (lo + 1) * this->Spacing[k];
      }
    }
    return offAxis >= 0;
  }

  // Moves p (world) to the root on the edge of the index-space vertex t.
  void Refine(const double t[3], double p[3]) const
  {
    double a[3], b[3];
    if (!this->FindEdge(t, a, b))
    {
      return;
    }
    // F itself is nearly linear along a short edge, and cheapest; where it is beyond
    // 1e200 at an end, its compressed form sign(F)·ln(1 + |F|) is used instead.
    bool compressed = false;
    auto phi = [&](const double x[3]) {
      return compressed ? this->Kernel->EvaluateCompressed(x) : this->Kernel->Evaluate(x);
    };
    double va = phi(a), vb = phi(b);
    if (!(std::fabs(va) < 1e200 && std::fabs(vb) < 1e200))
    {
      compressed = true;
      va = phi(a);
      vb = phi(b);
    }
    if (!(va < 0 && vb > 0) && !(va > 0 && vb < 0))
    {
      return; // no bracket (a sample exactly zero): keep the interpolated vertex
    }
    const double small = 1e-15 * std::max(std::fabs(va), std::fabs(vb));
    double s0 = 0, s1 = 1;
    int side = 0;
    const double length = std::fabs(b[0] - a[0]) + std::fabs(b[1] - a[1]) + std::fabs(b[2] - a[2]);
    double q[3];
    for (int it = 0; it < 100 && (s1 - s0) * length > this->Tolerance; ++it)
    {
      double s = 0.5 * (s0 + s1);
      if (std::isfinite(va) && std::isfinite(vb))
      {
        const double secant = s1 - vb * (s1 - s0) / (vb - va);
        if (secant > s0 && secant < s1)
        {
          s = secant;
        }
      }
      for (int k = 0; k < 3; ++k)
      {
        q[k] = a[k] + s * (b[k] - a[k]);
      }
      const double v = phi(q);
      if (std::fabs(v) <= small)
      {
        s0 = s1 = s;
        break;
      }
      if ((v < 0) == (va < 0))
      {
        s0 = s;
        va = v;
        if (side == -1)
        {
          vb *= 0.5; // Illinois: the stale end is halved
        }
        side = -1;
      }
      else
      {
        s1 = s;
        vb = v;
        if (side == 1)
        {
          va *= 0.5;
        }
        side = 1;
      }
    }
    const double s = 0.5 * (s0 + s1);
    for (int k = 0; k < 3; ++k)
    {
      p[k] = a[k] + s * (b[k] - a[k]);
    }
  }

  void operator()(vtkIdType begin, vtkIdType end)
  {
    double t[3], p[3], n[3];
    for (vtkIdType i = begin; i < end; ++i)
    {
      this->IndexPoints->GetPoint(i, t);
      for (int k = 0; k < 3; ++k)
      {
        p[k] = this->Origin[k] + t[k] * this->Spacing[k];
      }
      if (this->Project)
      {
        this->Refine(t, p);
      }
      this->Points->SetPoint(i, p);
      double gradientNorm;
      int nearest;
      this->Kernel->EvaluateVertex(p, n, gradientNorm, nearest);
      const float nf[3] = { static_cast<float>(n[0]), static_cast<float>(n[1]),
        static_cast<float>(n[2]) };
      this->Normals->SetTypedTuple(i, nf);
      this->Factor->SetValue(i, nearest);
    }
  }
};
}

bool vtkPiFlyingEdges::ComputeGrid(const double b[6], int dims[3], double spacing[3])
{
  const double side[3] = { b[1] - b[0], b[3] - b[2], b[5] - b[4] };
  const int* sd = this->SampleDimensions;
  if (sd[0] != 0 || sd[1] != 0 || sd[2] != 0)
  {
    if (sd[0] < 2 || sd[1] < 2 || sd[2] < 2)
    {
      vtkErrorMacro(<< "SampleDimensions must be at least 2 points per axis (got " << sd[0]
                    << ", " << sd[1] << ", " << sd[2] << "); set all to 0 to use Resolution");
      return false;
    }
    std::copy(sd, sd + 3, dims);
  }
  else
  {
    if (this->Resolution < 1)
    {
      vtkErrorMacro(<< "Resolution must be at least 1 (got " << this->Resolution << ")");
      return false;
    }
    const double h = std::max({ side[0], side[1], side[2] }) / this->Resolution;
    for (int a = 0; a < 3; ++a)
    {
      const double cells = std::max(1.0, std::ceil(side[a] / h - 1e-9));
      if (cells > 1e9)
      {
        vtkErrorMacro(<< "Grid too fine along axis " << a);
        return false;
      }
      dims[a] = static_cast<int>(cells) + 1;
    }
  }
  const double samples = double(dims[0]) * dims[1] * dims[2];
  if (samples > static_cast<double>(this->MaximumNumberOfSamples))
  {
    vtkErrorMacro(<< "A grid of " << dims[0] << " x " << dims[1] << " x " << dims[2] << " = "
                  << samples << " samples needs " << samples * sizeof(double) / (1 << 20)
                  << " MiB; the limit (MaximumNumberOfSamples) is "
                  << this->MaximumNumberOfSamples << " samples");
    return false;
  }
  for (int a = 0; a < 3; ++a)
  {
    spacing[a] = side[a] / (dims[a] - 1);
  }
  return true;
}

int vtkPiFlyingEdges::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  if (!this->PiSurface)
  {
    vtkErrorMacro(<< "No Pi-surface to mesh: call SetPiSurface()");
    return 0;
  }
  auto kernel = this->PiSurface->GetKernel();
  if (!kernel || kernel->GetNumberOfFactors() == 0)
  {
    vtkErrorMacro(<< "The Pi-surface is invalid or has no factors"
                  << (*this->PiSurface->GetErrorMessage() ? ": " : "")
                  << this->PiSurface->GetErrorMessage());
    return 0;
  }

  double bounds[6];
  const bool automatic = std::all_of(this->Bounds, this->Bounds + 6, [](double v) { return v == 0; });
  if (automatic)
  {
    if (!this->PiSurface->GetModelBounds(bounds))
    {
      vtkErrorMacro(<< "No bounds to mesh in: " << this->PiSurface->GetErrorMessage());
      return 0;
    }
  }
  else
  {
    if (!pisurf::ValidBounds(this->Bounds))
    {
      vtkErrorMacro(<< "Bounds must be finite with x0 < x1, y0 < y1, z0 < z1 (or all zero "
                       "for the model's bounds)");
      return 0;
    }
    std::copy(this->Bounds, this->Bounds + 6, bounds);
  }

  int dims[3];
  double spacing[3];
  if (!this->ComputeGrid(bounds, dims, spacing))
  {
    return 0;
  }
  const double origin[3] = { bounds[0], bounds[2], bounds[4] };

  // PASS 1: sample F row by row.
  // Flying edges runs in index space (origin 0, spacing 1): its float vertices then
  // have exact integer coordinates on the axes they do not interpolate along.
  vtkNew<vtkImageData> image;
  image->SetDimensions(dims);
  vtkNew<vtkDoubleArray> values;
  values->SetName("F");
  values->SetNumberOfTuples(vtkIdType(dims[0]) * dims[1] * dims[2]);
  image->GetPointData()->SetScalars(values);
  BlockGrid blocks;
  for (int a = 0; a < 3; ++a)
  {
    blocks.Count[a] = std::max(1, (dims[a] - 1 + BlockCells - 1) / BlockCells);
  }
  blocks.Sign.assign(vtkIdType(blocks.Count[0]) * blocks.Count[1] * blocks.Count[2], 0);
  ClassifyBlocks classify{ kernel.get(), dims, origin, spacing, &blocks };
  vtkSMPTools::For(0, static_cast<vtkIdType>(blocks.Sign.size()), classify);
  std::atomic<bool> abort{ false };
  SampleRows sample{ kernel.get(), dims, origin, spacing, &blocks, values->GetPointer(0), this,
    &abort };
  vtkSMPTools::For(0, vtkIdType(dims[1]) * dims[2], sample);
  if (abort || this->CheckAbort())
  {
    return 1;
  }
  this->UpdateProgress(0.5);

  // PASS 2: contour F = 0.
  vtkNew<vtkFlyingEdges3D> contour;
  contour->SetInputData(image);
  contour->SetValue(0, 0.0);
  contour->ComputeNormalsOff();
  contour->ComputeGradientsOff();
  contour->ComputeScalarsOff();
  contour->InterpolateAttributesOff();
  contour->Update();
  output->ShallowCopy(contour->GetOutput());
  output->GetPointData()->Initialize();
  // Flying edges winds its triangles facing decreasing values; ours face ∇F, like the
  // Normals, so that renderers light the side they see.
  vtkNew<vtkCellArray> polys;
  polys->DeepCopy(output->GetPolys());
  for (vtkIdType c = 0; c < polys->GetNumberOfCells(); ++c)
  {
    polys->ReverseCellAtId(c);
  }
  output->SetPolys(polys);
  this->UpdateProgress(0.8);
  if (this->CheckAbort())
  {
    return 1;
  }

  // PASS 3: analytic normals and the primitive of each vertex.
  const vtkIdType n = output->GetNumberOfPoints();
  vtkNew<vtkFloatArray> normals;
  normals->SetName("Normals");
  normals->SetNumberOfComponents(3);
  normals->SetNumberOfTuples(n);
  vtkNew<vtkIntArray> factor;
  factor->SetName("Factor");
  factor->SetNumberOfTuples(n);
  if (n > 0)
  {
    vtkNew<vtkPoints> points;
    points->SetDataTypeToDouble();
    points->SetNumberOfPoints(n);
    vtkSmartPointer<vtkPoints> indexPoints = output->GetPoints();
    output->SetPoints(points);
    const double size = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
      (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
      (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
    VertexAttributes attributes{ kernel.get(), indexPoints, points, normals, factor,
      this->ProjectVertices,
      origin, spacing, 1e-13 * size };
    vtkSMPTools::For(0, n, attributes);
  }
  output->GetPointData()->SetNormals(normals);
  output->GetPointData()->AddArray(factor);

  pisurf::Model model;
  if (this->PiSurface->GetCoreModel(model))
  {
    if (!model.HasBounds)
    {
      // Downstream users rebuild the function and the region it was meshed in.
      model.HasBounds = true;
      std::copy(bounds, bounds + 6, model.Bounds);
    }
    vtkNew<vtkStringArray> json;
    json->SetName("PiSurfaceModel");
    json->InsertNextValue(pisurf::WriteModel(model));
    output->GetFieldData()->AddArray(json);
  }
  if (n == 0)
  {
    vtkWarningMacro(<< "The Pi-surface does not cross the bounds [" << bounds[0] << ", "
                    << bounds[1] << "] x [" << bounds[2] << ", " << bounds[3] << "] x ["
                    << bounds[4] << ", " << bounds[5] << "] at this resolution: empty mesh");
  }
  this->UpdateProgress(1.0);
  return 1;
}

void vtkPiFlyingEdges::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PiSurface: " << this->PiSurface << "\n";
  os << indent << "Bounds: (" << this->Bounds[0] << ", " << this->Bounds[1] << ", "
     << this->Bounds[2] << ", " << this->Bounds[3] << ", " << this->Bounds[4] << ", "
     << this->Bounds[5] << ")\n";
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "SampleDimensions: (" << this->SampleDimensions[0] << ", "
     << this->SampleDimensions[1] << ", " << this->SampleDimensions[2] << ")\n";
  os << indent << "MaximumNumberOfSamples: " << this->MaximumNumberOfSamples << "\n";
  os << indent << "ProjectVertices: " << (this->ProjectVertices ? "On" : "Off") << "\n";
}
