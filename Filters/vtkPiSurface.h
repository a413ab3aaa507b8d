// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiSurface
 * @brief implicit function of a Pi-surface: F(p) = Π f_i(p) − r
 *
 * vtkPiSurface multiplies any number of implicit functions (the factors f_i) and
 * subtracts the blending parameter r (Blending), as in Raposo and Gomes,
 * "Π-surfaces: products of implicit surfaces towards constructive composition of 3D
 * objects" (WSCG 2019). Small r shrinks the surface onto the union of the primitives,
 * larger r inflates and blends them.
 *
 * vtkPiSurface is a container, like vtkImplicitSum: a factor is any
 * vtkImplicitFunction, and vtkPiSurface knows no concrete function type. The
 * translation to the exact model is the bridge's (Filters/Bridge/PiImplicitBridge.h):
 * vtkPiPrimitive, and VTK's vtkSphere, vtkPlane, vtkCylinder, vtkCone and vtkQuadric
 * (with no transform or a linear one), are the polynomials they are, so algorithms
 * evaluate them exactly and in batches; other functions are called through
 * FunctionValue/FunctionGradient. A model's primitives become vtkPiPrimitive factors,
 * and GetModelJSON writes each factor's model entry, both through the bridge.
 *
 * The gradient is exact: ∇F = Σ_i ∇f_i Π_{j≠i} f_j, also where factors vanish.
 *
 * Numerical range: the product is accumulated with a separate binary exponent, so
 * products of 10^4 or more factors neither overflow nor lose their sign. When |F|
 * itself exceeds the double range, EvaluateFunction returns ±VTK_DOUBLE_MAX (sign
 * exact), and each gradient component is clamped the same way; when r = 0 and the
 * product is non-zero but below the smallest double, the smallest denormal with the
 * product's sign is returned. EvaluateSignAndLog gives ln|F| and the sign without any
 * clamping.
 *
 * Models: SetModelJSON/GetModelJSON/LoadModel read and write the .pisurf format
 * (JSON, version 1; see Documentation/pisurf-format.md). An invalid model returns false
 * with an error that names the key or the position, and leaves the function unchanged.
 *
 * @warning Evaluation is reentrant (vtkSMPTools workers may share one vtkPiSurface).
 * Do not add factors or change parameters while other threads evaluate.
 *
 * @sa vtkPiPrimitive vtkImplicitBoolean vtkImplicitSum
 */
#ifndef vtkPiSurface_h
#define vtkPiSurface_h

#include "vtkImplicitFunction.h"
#include "vtkPiSurfacesFiltersModule.h" // for export macro

#include <memory> // for std::shared_ptr
#include <string> // for std::string

#ifndef __VTK_WRAP__
namespace pisurf
{
class ProductKernel;
struct Model;
}
#endif

class VTKPISURFACESFILTERS_EXPORT vtkPiSurface : public vtkImplicitFunction
{
public:
  static vtkPiSurface* New();
  vtkTypeMacro(vtkPiSurface, vtkImplicitFunction);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  using vtkImplicitFunction::EvaluateFunction;
  double EvaluateFunction(double x[3]) override;
  void EvaluateGradient(double x[3], double g[3]) override;
  /// Batch evaluation of a whole array of points (threaded with vtkSMPTools, no
  /// per-point virtual call for polynomial factors).
  void EvaluateFunction(vtkDataArray* input, vtkDataArray* output) override;

  /// ln|F(x)| in `logAbs` (−inf where F = 0) and the sign of F (−1, 0 or 1); exact
  /// whatever the magnitude of the product.
  int EvaluateSignAndLog(double x[3], double& logAbs);

  /// Index of the factor whose zero set is nearest to x (first-order distance
  /// |f_i|/|∇f_i|): the primitive whose patch x lies on. −1 without factors.
  int GetNearestFactor(double x[3]);

  ///@{
  /// The factors of the product.
  void AddFactor(vtkImplicitFunction* f);
  void RemoveAllFactors();
  int GetNumberOfFactors();
  vtkImplicitFunction* GetFactor(int i);
  ///@}

  ///@{
  /// The blending parameter r (default 0: the union of the primitives).
  void SetBlending(double r);
  vtkGetMacro(Blending, double);
  ///@}

  ///@{
  /// Region of interest of the model (the .pisurf "bounds"). Unset by default.
  void SetModelBounds(const double bounds[6]);
  void ClearModelBounds();
  bool HasModelBounds();
  ///@}

  /// Bounds for meshing: the model's bounds when set; otherwise, if every factor is
  /// bounded, the union of their boxes grown until F has one sign and no zero on the
  /// whole boundary (the margin starts at 10% of the largest side and doubles, at most
  /// 12 times; it depends on r through F). Returns false (with an error) otherwise.
  bool GetModelBounds(double bounds[6]);

  /// The region an algorithm works in: `requested` when it is not all zero (it must then
  /// be valid: finite with x0 < x1, y0 < y1, z0 < z1), else GetModelBounds. False with
  /// the reason in GetErrorMessage, for the calling algorithm to report.
  bool ResolveBounds(const double requested[6], double bounds[6]);

  ///@{
  /// Named model parameters, forwarded to every factor that takes parameters (a
  /// vtkPiPrimitive's expression), so that changing "a" moves the cup's handle.
  void SetParameter(const char* name, double value);
  double GetParameter(const char* name);
  int GetNumberOfParameters();
  const char* GetParameterName(int i);
  ///@}

  /// Replaces the whole function by the model in `json` (.pisurf text). On error
  /// returns false, reports it with vtkErrorMacro and leaves the function unchanged.
  bool SetModelJSON(const std::string& json);
  /// The function as .pisurf text; empty (with an error) if a factor is not a polynomial.
  std::string GetModelJSON();
  /// SetModelJSON with the contents of a file; errors name the file.
  bool LoadModel(const char* path);

  /// True if every factor is valid (vtkPiPrimitive parameters) and there is at least one.
  bool IsValid();
  /// The last error (from a model, a factor or the bounds), or empty.
  const char* GetErrorMessage();

  vtkMTimeType GetMTime() override;

#ifndef __VTK_WRAP__
  /// An immutable snapshot of the product for algorithms (rebuilt when the function or
  /// a factor changed). Thread-safe to use from many workers; nullptr if invalid.
  std::shared_ptr<const pisurf::ProductKernel> GetKernel();
  /// The model description (primitives as .pisurf specs); false if a factor is not a
  /// polynomial.
  bool GetCoreModel(pisurf::Model& model);
  /// Replace the function by a validated core model.
  void SetCoreModel(const pisurf::Model& model);
#endif

protected:
  vtkPiSurface();
  ~vtkPiSurface() override;

  double Blending = 0.0;

private:
  vtkPiSurface(const vtkPiSurface&) = delete;
  void operator=(const vtkPiSurface&) = delete;

  struct vtkInternals;
  std::unique_ptr<vtkInternals> Internals;
#ifndef __VTK_WRAP__
  const pisurf::ProductKernel* FastKernel();
#endif
};

#endif
