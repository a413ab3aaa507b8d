// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class vtkPiPrimitiveSource
 * @brief one algebraic primitive as a pipeline source: its surface and its model
 *
 * The surface f = 0 of one vtkPiPrimitive (ParaView's "Pi Primitive"), meshed by
 * vtkPiFlyingEdges with exact vertices: bounded primitives (sphere, ellipsoid,
 * superellipsoid, torus) as closed surfaces, unbounded ones clipped to Bounds. Every
 * parameter is the primitive's (see vtkPiPrimitive for the types and their
 * polynomials); this class only forwards them, so the primitive's maths lives in one
 * place.
 *
 * Output: the mesh with `Normals` and `Factor` (0), and the field-data string
 * `PiSurfaceModel`: a .pisurf model holding this one primitive with r = 0 (and the
 * Bounds for an unbounded one). "Pi Product" (vtkPiProduct) multiplies such models.
 *
 * Bounds: all zero (the default) means automatic: for a bounded primitive its box
 * grown until the surface is inside (vtkPiSurface::GetModelBounds); for an unbounded
 * one the cube of half-side 2·s about Center, s the primitive's size (Radius of a
 * cylinder, the largest of Radii of hyperboloids and paraboloids, 1 for planes, cones
 * and polynomials).
 *
 * Invalid parameters (a non-positive radius, an odd superellipsoid exponent, a
 * malformed expression, Axis together with a rotation, invalid Bounds) are reported
 * with vtkErrorMacro, naming the parameter, and the output is empty (or, with
 * KeepLastValidOutput, the last valid one).
 *
 * @sa vtkPiPrimitive vtkPiProduct vtkPiFlyingEdges
 */
#ifndef vtkPiPrimitiveSource_h
#define vtkPiPrimitiveSource_h

#include "vtkPiSurfacesFiltersModule.h" // for export macro
#include "vtkPolyDataAlgorithm.h"

#include <memory> // for std::unique_ptr

#include <string> // for std::string

class vtkPiFlyingEdges;
class vtkPiPrimitive;
class vtkPiSurface;

namespace pisurf
{
class LastValidOutput;
}

class VTKPISURFACESFILTERS_EXPORT vtkPiPrimitiveSource : public vtkPolyDataAlgorithm
{
public:
  static vtkPiPrimitiveSource* New();
  vtkTypeMacro(vtkPiPrimitiveSource, vtkPolyDataAlgorithm);
  void PrintSelf(ostream& os, vtkIndent indent) override;

  /// The primitive itself (owned by the source; its changes re-execute the source).
  vtkPiPrimitive* GetPrimitive() { return this->Primitive; }

  ///@{
  /// The primitive's parameters, forwarded to GetPrimitive() (defaults as there: a
  /// unit sphere at the origin).
  void SetType(int type);
  int GetType();
  bool SetTypeFromString(const char* type);
  void SetCenter(double x, double y, double z);
  void SetCenter(const double c[3]) { this->SetCenter(c[0], c[1], c[2]); }
  double* GetCenter() VTK_SIZEHINT(3);
  void SetRadius(double r);
  double GetRadius();
  void SetRadii(double a, double b, double c);
  void SetRadii(const double r[3]) { this->SetRadii(r[0], r[1], r[2]); }
  double* GetRadii() VTK_SIZEHINT(3);
  void SetMajorRadius(double r);
  double GetMajorRadius();
  void SetMinorRadius(double r);
  double GetMinorRadius();
  void SetExponent(int n);
  int GetExponent();
  void SetNormal(double x, double y, double z);
  void SetNormal(const double n[3]) { this->SetNormal(n[0], n[1], n[2]); }
  double* GetNormal() VTK_SIZEHINT(3);
  void SetAngle(double degrees);
  double GetAngle();
  void SetAxis(double x, double y, double z);
  void SetAxis(const double a[3]) { this->SetAxis(a[0], a[1], a[2]); }
  double* GetAxis() VTK_SIZEHINT(3);
  void SetRotationAxis(double x, double y, double z);
  void SetRotationAxis(const double a[3]) { this->SetRotationAxis(a[0], a[1], a[2]); }
  double* GetRotationAxis() VTK_SIZEHINT(3);
  void SetRotationAngle(double degrees);
  double GetRotationAngle();
  void SetOrientation(double x, double y, double z);
  void SetOrientation(const double a[3]) { this->SetOrientation(a[0], a[1], a[2]); }
  double* GetOrientation() VTK_SIZEHINT(3);
  void SetExpression(const char* expression);
  const char* GetExpression();
  void SetScale(double s);
  double GetScale();
  void SetNegate(bool negate);
  bool GetNegate();
  void SetName(const char* name);
  const char* GetName();
  ///@}

  ///@{
  /// Box the surface is meshed in, [x0,x1,y0,y1,z0,z1]; all zero (the default) =
  /// automatic (see the class description).
  vtkSetVector6Macro(Bounds, double);
  vtkGetVector6Macro(Bounds, double);
  ///@}

  ///@{
  /// Grid cells along the longest side of the box (default 64, at least 1).
  vtkSetClampMacro(Resolution, int, 1, 4096);
  vtkGetMacro(Resolution, int);
  ///@}

  /// The box the next execution meshes in; false (with the reason in `error`) if the
  /// primitive or Bounds are invalid.
  bool ResolveBounds(double bounds[6], std::string& error);

  /// The primitive as a .pisurf model (r = 0; with the resolved bounds when it is
  /// unbounded); empty, with an error, if it is invalid.
  std::string GetModelJSON();

  vtkMTimeType GetMTime() override;

  ///@{
  /// When an execution fails on a bad setting (an error is reported), keep the outputs
  /// of the last valid execution instead of empty ones (default off, VTK's convention;
  /// ParaView's proxies turn it on: the last valid surface stays while the error is
  /// shown).
  vtkSetMacro(KeepLastValidOutput, bool);
  vtkGetMacro(KeepLastValidOutput, bool);
  vtkBooleanMacro(KeepLastValidOutput, bool);
  ///@}

  /// Runs REQUEST_DATA through the last-valid-output guard (see KeepLastValidOutput).
  vtkTypeBool ProcessRequest(
    vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs) override;

protected:
  vtkPiPrimitiveSource();
  ~vtkPiPrimitiveSource() override;

  int RequestInformation(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;

  vtkPiPrimitive* Primitive;
  // The primitive alone as a Pi-surface and its mesher, kept between executions so
  // that re-meshing after an edit reuses the mesher's buffers.
  vtkPiSurface* Surface;
  vtkPiFlyingEdges* Mesher;
  double Bounds[6] = { 0, 0, 0, 0, 0, 0 };
  int Resolution = 64;

  bool KeepLastValidOutput = false;
  std::unique_ptr<pisurf::LastValidOutput> LastValid;

private:
  vtkPiPrimitiveSource(const vtkPiPrimitiveSource&) = delete;
  void operator=(const vtkPiPrimitiveSource&) = delete;
};

#endif
