// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiSurface.h"

#include "Bridge/PiImplicitBridge.h"
#include "PiModel.h"
#include "PiParallel.h"
#include "PiProductKernel.h"

#include "vtkCallbackCommand.h"
#include "vtkDataArray.h"
#include "vtkMath.h"
#include "vtkObjectFactory.h"
#include "vtkSMPTools.h"
#include "vtkSmartPointer.h"
#include "vtksys/SystemTools.hxx"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <fstream>
#include <limits>
#include <mutex>
#include <sstream>
#include <vector>

vtkStandardNewMacro(vtkPiSurface);

struct vtkPiSurface::vtkInternals
{
  std::vector<vtkSmartPointer<vtkImplicitFunction>> Factors;
  std::vector<unsigned long> ObserverTags;
  vtkNew<vtkCallbackCommand> FactorObserver;

  bool HasBounds = false;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  pisurf::ParameterMap Parameters;
  std::string Name;
  std::string Description;

  std::atomic<bool> Dirty{ true };
  std::mutex BuildMutex;
  std::shared_ptr<const pisurf::ProductKernel> Kernel; // null if invalid
  vtkMTimeType KernelTime = 0;
  std::string Error;
};

vtkPiSurface::vtkPiSurface()
  : Internals(new vtkInternals)
{
  this->Internals->FactorObserver->SetClientData(this);
  this->Internals->FactorObserver->SetCallback(
    [](vtkObject*, unsigned long, void* clientData, void*)
    {
      auto* self = static_cast<vtkPiSurface*>(clientData);
      self->Internals->Dirty = true;
      self->Modified();
    });
}

vtkPiSurface::~vtkPiSurface()
{
  this->RemoveAllFactors();
}

void vtkPiSurface::AddFactor(vtkImplicitFunction* f)
{
  if (!f)
  {
    vtkErrorMacro(<< "AddFactor: null function");
    return;
  }
  if (f == this)
  {
    vtkErrorMacro(<< "AddFactor: a Pi-surface cannot be a factor of itself");
    return;
  }
  this->Internals->Factors.emplace_back(f);
  this->Internals->ObserverTags.push_back(
    f->AddObserver(vtkCommand::ModifiedEvent, this->Internals->FactorObserver));
  for (const auto& kv : this->Internals->Parameters)
  {
    pisurf::SetFactorParameter(f, kv.first, kv.second, true);
  }
  this->Internals->Dirty = true;
  this->Modified();
}

void vtkPiSurface::RemoveAllFactors()
{
  auto& in = *this->Internals;
  if (in.Factors.empty())
  {
    return;
  }
  for (size_t i = 0; i < in.Factors.size(); ++i)
  {
    in.Factors[i]->RemoveObserver(in.ObserverTags[i]);
  }
  in.Factors.clear();
  in.ObserverTags.clear();
  in.Dirty = true;
  this->Modified();
}

int vtkPiSurface::GetNumberOfFactors()
{
  return static_cast<int>(this->Internals->Factors.size());
}

vtkImplicitFunction* vtkPiSurface::GetFactor(int i)
{
  if (i < 0 || i >= this->GetNumberOfFactors())
  {
    vtkErrorMacro(<< "GetFactor: index " << i << " out of range [0, " << this->GetNumberOfFactors()
                  << ")");
    return nullptr;
  }
  return this->Internals->Factors[i];
}

void vtkPiSurface::SetBlending(double r)
{
  if (!std::isfinite(r))
  {
    vtkErrorMacro(<< "Blending must be a finite number");
    return;
  }
  if (r != this->Blending)
  {
    this->Blending = r;
    this->Internals->Dirty = true;
    this->Modified();
  }
}

void vtkPiSurface::SetModelBounds(const double bounds[6])
{
  if (!pisurf::ValidBounds(bounds))
  {
    vtkErrorMacro(<< "Model bounds must be finite with x0 < x1, y0 < y1, z0 < z1");
    return;
  }
  this->Internals->HasBounds = true;
  std::copy(bounds, bounds + 6, this->Internals->Bounds);
  this->Modified();
}

void vtkPiSurface::ClearModelBounds()
{
  if (this->Internals->HasBounds)
  {
    this->Internals->HasBounds = false;
    this->Modified();
  }
}

bool vtkPiSurface::HasModelBounds()
{
  return this->Internals->HasBounds;
}

void vtkPiSurface::SetParameter(const char* name, double value)
{
  if (!name || !pisurf::IsValidParameterName(name) || !std::isfinite(value))
  {
    vtkErrorMacro(<< "Invalid parameter '" << (name ? name : "(null)") << "' = " << value);
    return;
  }
  this->Internals->Parameters[name] = value;
  for (auto& f : this->Internals->Factors)
  {
    pisurf::SetFactorParameter(f, name, value, false);
  }
  this->Modified();
}

double vtkPiSurface::GetParameter(const char* name)
{
  auto it = this->Internals->Parameters.find(name ? name : "");
  return it == this->Internals->Parameters.end() ? std::numeric_limits<double>::quiet_NaN()
                                                 : it->second;
}

int vtkPiSurface::GetNumberOfParameters()
{
  return static_cast<int>(this->Internals->Parameters.size());
}

const char* vtkPiSurface::GetParameterName(int i)
{
  if (i < 0 || i >= this->GetNumberOfParameters())
  {
    return nullptr;
  }
  auto it = this->Internals->Parameters.begin();
  std::advance(it, i);
  return it->first.c_str();
}

const pisurf::ProductKernel* vtkPiSurface::FastKernel()
{
  auto& in = *this->Internals;
  if (in.Dirty.load(std::memory_order_acquire))
  {
    std::string error;
    {
      std::lock_guard<std::mutex> lock(in.BuildMutex);
      if (in.Dirty.load(std::memory_order_relaxed))
      {
        std::vector<pisurf::Factor> factors;
        factors.reserve(in.Factors.size());
        in.Error.clear();
        for (size_t i = 0; i < in.Factors.size() && in.Error.empty(); ++i)
        {
          vtkImplicitFunction* f = in.Factors[i];
          pisurf::Factor factor;
          std::string reason;
          const pisurf::FactorKind kind = pisurf::ExactFactor(f, factor.Polynomial, reason);
          if (kind == pisurf::FactorKind::Invalid)
          {
            in.Error = "factor " + std::to_string(i) + " is invalid: " + reason;
            break;
          }
          if (kind == pisurf::FactorKind::Exact)
          {
            factor.IsPolynomial = true;
          }
          else
          {
            vtkSmartPointer<vtkImplicitFunction> held = f;
            factor.IsPolynomial = false;
            factor.Generic = [held](const double p[3], double* g)
            {
              if (g)
              {
                held->FunctionGradient(p, g);
              }
              return held->FunctionValue(p);
            };
          }
          factors.push_back(std::move(factor));
        }
        if (in.Error.empty())
        {
          in.Kernel = std::make_shared<pisurf::ProductKernel>(std::move(factors), this->Blending);
        }
        else
        {
          in.Kernel.reset();
        }
        in.KernelTime = this->GetMTime();
        error = in.Error;
        in.Dirty.store(false, std::memory_order_release);
      }
    }
    if (!error.empty())
    {
      vtkErrorMacro(<< error);
    }
  }
  return in.Kernel.get();
}

std::shared_ptr<const pisurf::ProductKernel> vtkPiSurface::GetKernel()
{
  // Transforms of factors do not fire the factor's ModifiedEvent: compare times too.
  if (this->GetMTime() > this->Internals->KernelTime)
  {
    this->Internals->Dirty = true;
  }
  this->FastKernel();
  return this->Internals->Kernel;
}

double vtkPiSurface::EvaluateFunction(double x[3])
{
  const pisurf::ProductKernel* k = this->FastKernel();
  return k ? k->Evaluate(x) : std::numeric_limits<double>::quiet_NaN();
}

void vtkPiSurface::EvaluateGradient(double x[3], double g[3])
{
  const pisurf::ProductKernel* k = this->FastKernel();
  if (k)
  {
    k->EvaluateWithGradient(x, g);
  }
  else
  {
    g[0] = g[1] = g[2] = std::numeric_limits<double>::quiet_NaN();
  }
}

void vtkPiSurface::EvaluateFunction(vtkDataArray* input, vtkDataArray* output)
{
  auto kernel = this->GetKernel();
  const vtkIdType n = input->GetNumberOfTuples();
  output->SetNumberOfComponents(1);
  output->SetNumberOfTuples(n);
  if (!kernel)
  {
    output->Fill(std::numeric_limits<double>::quiet_NaN());
    return;
  }
  // PASS 1: evaluate blocks of points, factor by factor.
  pisurf::ParallelFor(0, n, 1024,
    [&](vtkIdType begin, vtkIdType end)
    {
      std::vector<double> xyz(3 * (end - begin)), values(end - begin);
      for (vtkIdType i = begin; i < end; ++i)
      {
        input->GetTuple(i, &xyz[3 * (i - begin)]);
      }
      kernel->EvaluatePoints(xyz.data(), end - begin, values.data());
      for (vtkIdType i = begin; i < end; ++i)
      {
        output->SetTuple1(i, values[i - begin]);
      }
    });
}

int vtkPiSurface::EvaluateSignAndLog(double x[3], double& logAbs)
{
  const pisurf::ProductKernel* k = this->FastKernel();
  if (!k)
  {
    logAbs = std::numeric_limits<double>::quiet_NaN();
    return 0;
  }
  return k->EvaluateSignAndLog(x, logAbs);
}

int vtkPiSurface::GetNearestFactor(double x[3])
{
  const pisurf::ProductKernel* k = this->FastKernel();
  return k ? k->NearestFactor(x) : -1;
}

bool vtkPiSurface::IsValid()
{
  return this->GetKernel() != nullptr && !this->Internals->Factors.empty();
}

const char* vtkPiSurface::GetErrorMessage()
{
  return this->Internals->Error.c_str();
}

bool vtkPiSurface::GetModelBounds(double bounds[6])
{
  auto& in = *this->Internals;
  if (in.HasBounds)
  {
    std::copy(in.Bounds, in.Bounds + 6, bounds);
    return true;
  }
  auto kernel = this->GetKernel();
  if (!kernel || kernel->GetNumberOfFactors() == 0)
  {
    in.Error = "the Pi-surface has no valid factors, so it has no bounds";
    vtkErrorMacro(<< in.Error);
    return false;
  }
  double box[6] = { VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX, VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX,
    VTK_DOUBLE_MAX, -VTK_DOUBLE_MAX };
  for (size_t i = 0; i < kernel->GetNumberOfFactors(); ++i)
  {
    const pisurf::Factor& f = kernel->GetFactor(i);
    if (!f.IsPolynomial || !f.Polynomial.Bounded)
    {
      in.Error = "factor " + std::to_string(i) +
        " is unbounded: give the model bounds (the .pisurf \"bounds\" key)";
      vtkErrorMacro(<< in.Error);
      return false;
    }
    for (int a = 0; a < 3; ++a)
    {
      box[2 * a] = std::min(box[2 * a], f.Polynomial.Bounds[2 * a]);
      box[2 * a + 1] = std::max(box[2 * a + 1], f.Polynomial.Bounds[2 * a + 1]);
    }
  }
  const double side =
    std::max({ box[1] - box[0], box[3] - box[2], box[5] - box[4], VTK_DBL_EPSILON });
  // Grow until the boundary of the box is free of the surface: F has one sign and no
  // zero on a 17×17 sample of each face.
  constexpr int N = 17;
  double margin = 0.1 * side;
  for (int attempt = 0; attempt < 12; ++attempt, margin *= 2.0)
  {
    double b[6];
    for (int a = 0; a < 3; ++a)
    {
      b[2 * a] = box[2 * a] - margin;
      b[2 * a + 1] = box[2 * a + 1] + margin;
    }
    int sign = 0;
    bool clean = true;
    for (int face = 0; face < 6 && clean; ++face)
    {
      const int axis = face / 2, u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int i = 0; i < N && clean; ++i)
      {
        for (int j = 0; j < N && clean; ++j)
        {
          double p[3];
          p[axis] = b[face];
          p[u] = b[2 * u] + (b[2 * u + 1] - b[2 * u]) * i / (N - 1);
          p[v] = b[2 * v] + (b[2 * v + 1] - b[2 * v]) * j / (N - 1);
          const double F = kernel->Evaluate(p);
          const int s = F > 0 ? 1 : (F < 0 ? -1 : 0);
          if (s == 0 || (sign != 0 && s != sign))
          {
            clean = false;
          }
          sign = s;
        }
      }
    }
    if (clean)
    {
      std::copy(b, b + 6, bounds);
      return true;
    }
  }
  in.Error = "could not find bounds that enclose the surface (it reaches beyond " +
    std::to_string(margin) + " of the primitives): give the model bounds";
  vtkErrorMacro(<< in.Error);
  return false;
}

bool vtkPiSurface::ResolveBounds(const double requested[6], double bounds[6])
{
  if (pisurf::UnsetBounds(requested))
  {
    return this->GetModelBounds(bounds);
  }
  return pisurf::TakeBounds(requested, "model's", bounds, this->Internals->Error);
}

bool vtkPiSurface::GetCoreModel(pisurf::Model& model)
{
  auto& in = *this->Internals;
  pisurf::Model m;
  m.Name = in.Name;
  m.Description = in.Description;
  m.Blending = this->Blending;
  m.HasBounds = in.HasBounds;
  std::copy(in.Bounds, in.Bounds + 6, m.Bounds);
  m.Parameters = in.Parameters;
  auto kernel = this->GetKernel();
  if (!kernel)
  {
    return false;
  }
  for (size_t i = 0; i < in.Factors.size(); ++i)
  {
    vtkImplicitFunction* f = in.Factors[i];
    const pisurf::Factor& kf = kernel->GetFactor(i);
    if (!kf.IsPolynomial)
    {
      in.Error = "factor " + std::to_string(i) + " (" + f->GetClassName() +
        ") is not a polynomial and cannot be written to a model";
      return false;
    }
    m.Primitives.push_back(pisurf::DescribeFactor(f, kf.Polynomial, m.Parameters));
  }
  model = std::move(m);
  return true;
}

void vtkPiSurface::SetCoreModel(const pisurf::Model& model)
{
  auto& in = *this->Internals;
  for (size_t i = 0; i < in.Factors.size(); ++i)
  {
    in.Factors[i]->RemoveObserver(in.ObserverTags[i]);
  }
  in.Factors.clear();
  in.ObserverTags.clear();
  in.Parameters = model.Parameters;
  in.Name = model.Name;
  in.Description = model.Description;
  in.HasBounds = model.HasBounds;
  std::copy(model.Bounds, model.Bounds + 6, in.Bounds);
  this->Blending = model.Blending;
  for (const pisurf::PrimitiveSpec& s : model.Primitives)
  {
    vtkSmartPointer<vtkImplicitFunction> p = pisurf::MakeFunction(s, model.Parameters);
    in.Factors.emplace_back(p);
    in.ObserverTags.push_back(p->AddObserver(vtkCommand::ModifiedEvent, in.FactorObserver));
  }
  in.Error.clear();
  in.Dirty = true;
  this->Modified();
}

bool vtkPiSurface::SetModelJSON(const std::string& json)
{
  pisurf::Model model;
  std::string error;
  if (!pisurf::ParseModel(json, model, error))
  {
    this->Internals->Error = error;
    vtkErrorMacro(<< "Invalid Pi-surface model: " << error);
    return false;
  }
  this->SetCoreModel(model);
  return true;
}

std::string vtkPiSurface::GetModelJSON()
{
  pisurf::Model model;
  if (!this->GetCoreModel(model))
  {
    vtkErrorMacro(<< "Cannot write the model: " << this->Internals->Error);
    return std::string();
  }
  // A model file with an unbounded primitive must say where to look.
  auto kernel = this->GetKernel();
  for (size_t i = 0; kernel && !model.HasBounds && i < kernel->GetNumberOfFactors(); ++i)
  {
    if (!kernel->GetFactor(i).Polynomial.Bounded)
    {
      this->Internals->Error = "factor " + std::to_string(i) +
        " is unbounded: set the model bounds (SetModelBounds) before writing the model";
      vtkErrorMacro(<< "Cannot write the model: " << this->Internals->Error);
      return std::string();
    }
  }
  return pisurf::WriteModel(model);
}

bool vtkPiSurface::LoadModel(const char* path)
{
  if (!path || !*path)
  {
    this->Internals->Error = "no model file name given";
    vtkErrorMacro(<< this->Internals->Error);
    return false;
  }
  if (vtksys::SystemTools::FileIsDirectory(path))
  {
    this->Internals->Error = std::string("model file '") + path + "' is a directory";
    vtkErrorMacro(<< this->Internals->Error);
    return false;
  }
  std::ifstream file(path, std::ios::binary);
  if (!file)
  {
    this->Internals->Error = std::string("cannot open model file '") + path + "'";
    vtkErrorMacro(<< this->Internals->Error);
    return false;
  }
  file.seekg(0, std::ios::end);
  const std::streamoff size = file.tellg();
  constexpr std::streamoff MaxSize = 512LL << 20;
  if (size < 0)
  {
    this->Internals->Error = std::string("cannot read model file '") + path + "'";
    vtkErrorMacro(<< this->Internals->Error);
    return false;
  }
  if (size > MaxSize)
  {
    this->Internals->Error = std::string("model file '") + path + "' is larger than 512 MiB";
    vtkErrorMacro(<< this->Internals->Error);
    return false;
  }
  file.seekg(0);
  std::string text(static_cast<size_t>(size), '\0');
  file.read(&text[0], size);
  pisurf::Model model;
  std::string error;
  if (!pisurf::ParseModel(text, model, error))
  {
    this->Internals->Error = std::string(path) + ": " + error;
    vtkErrorMacro(<< "Invalid Pi-surface model " << this->Internals->Error);
    return false;
  }
  this->SetCoreModel(model);
  return true;
}

vtkMTimeType vtkPiSurface::GetMTime()
{
  vtkMTimeType t = this->Superclass::GetMTime();
  for (const auto& f : this->Internals->Factors)
  {
    t = std::max(t, f->GetMTime());
  }
  return t;
}

void vtkPiSurface::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  auto& in = *this->Internals;
  os << indent << "Blending: " << this->Blending << "\n";
  os << indent << "Name: " << in.Name << "\n";
  os << indent << "Description: " << in.Description << "\n";
  os << indent << "ModelBounds: ";
  if (in.HasBounds)
  {
    os << "(" << in.Bounds[0] << ", " << in.Bounds[1] << ", " << in.Bounds[2] << ", "
       << in.Bounds[3] << ", " << in.Bounds[4] << ", " << in.Bounds[5] << ")\n";
  }
  else
  {
    os << "(automatic)\n";
  }
  os << indent << "Parameters:";
  for (const auto& kv : in.Parameters)
  {
    os << " " << kv.first << "=" << kv.second;
  }
  os << "\n";
  os << indent << "Number Of Factors: " << in.Factors.size() << "\n";
  for (size_t i = 0; i < in.Factors.size(); ++i)
  {
    os << indent << "Factor " << i << ":\n";
    in.Factors[i]->PrintSelf(os, indent.GetNextIndent());
  }
  os << indent << "Error: " << in.Error << "\n";
}
