// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiPrimitiveSource.h"
#include "PiPieces.h"

#include "PiLastValidOutput.h"

#include "PiModel.h"
#include "PiPrimitiveCatalogue.h"
#include "vtkPiFlyingEdges.h"
#include "vtkPiPrimitive.h"
#include "vtkPiSurface.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkObjectFactory.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <string>

vtkStandardNewMacro(vtkPiPrimitiveSource);

vtkPiPrimitiveSource::vtkPiPrimitiveSource()
  : Primitive(vtkPiPrimitive::New())
  , Surface(vtkPiSurface::New())
  , Mesher(vtkPiFlyingEdges::New())
  , LastValid(new pisurf::LastValidOutput)
{
  this->SetNumberOfInputPorts(0);
  this->Surface->AddFactor(this->Primitive);
  this->Mesher->SetPiSurface(this->Surface);
  this->Mesher->SetOuterEnvelope(false); // every sheet of the primitive (hyperboloid2 has two)
  this->Mesher->SetProjectVertices(true);
  this->Mesher->SetGeneratePrimitives(false);
  this->Mesher->SetContainerAlgorithm(this);
  // The primitive reports invalid parameters itself when it is built; this source
  // reports them (once, naming itself) in RequestData instead.
  vtkNew<vtkCallbackCommand> quiet;
  this->Primitive->AddObserver(vtkCommand::ErrorEvent, quiet);
}

vtkPiPrimitiveSource::~vtkPiPrimitiveSource()
{
  this->Mesher->Delete();
  this->Surface->Delete();
  this->Primitive->Delete();
}

vtkTypeBool vtkPiPrimitiveSource::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs)
{
  return this->LastValid->Process(request, this->KeepLastValidOutput, outputs,
    [&]() { return this->Superclass::ProcessRequest(request, inputs, outputs); });
}

vtkMTimeType vtkPiPrimitiveSource::GetMTime()
{
  return std::max(this->Superclass::GetMTime(), this->Primitive->GetMTime());
}

// Forwarding: the primitive holds every parameter (and its defaults).
void vtkPiPrimitiveSource::SetType(int type)
{
  this->Primitive->SetType(type);
}
int vtkPiPrimitiveSource::GetType()
{
  return this->Primitive->GetType();
}
bool vtkPiPrimitiveSource::SetTypeFromString(const char* type)
{
  return this->Primitive->SetTypeFromString(type);
}
void vtkPiPrimitiveSource::SetCenter(double x, double y, double z)
{
  this->Primitive->SetCenter(x, y, z);
}
double* vtkPiPrimitiveSource::GetCenter()
{
  return this->Primitive->GetCenter();
}
void vtkPiPrimitiveSource::SetRadius(double r)
{
  this->Primitive->SetRadius(r);
}
double vtkPiPrimitiveSource::GetRadius()
{
  return this->Primitive->GetRadius();
}
void vtkPiPrimitiveSource::SetRadii(double a, double b, double c)
{
  this->Primitive->SetRadii(a, b, c);
}
double* vtkPiPrimitiveSource::GetRadii()
{
  return this->Primitive->GetRadii();
}
void vtkPiPrimitiveSource::SetMajorRadius(double r)
{
  this->Primitive->SetMajorRadius(r);
}
double vtkPiPrimitiveSource::GetMajorRadius()
{
  return this->Primitive->GetMajorRadius();
}
void vtkPiPrimitiveSource::SetMinorRadius(double r)
{
  this->Primitive->SetMinorRadius(r);
}
double vtkPiPrimitiveSource::GetMinorRadius()
{
  return this->Primitive->GetMinorRadius();
}
void vtkPiPrimitiveSource::SetExponent(int n)
{
  this->Primitive->SetExponent(n);
}
int vtkPiPrimitiveSource::GetExponent()
{
  return this->Primitive->GetExponent();
}
void vtkPiPrimitiveSource::SetNormal(double x, double y, double z)
{
  this->Primitive->SetNormal(x, y, z);
}
double* vtkPiPrimitiveSource::GetNormal()
{
  return this->Primitive->GetNormal();
}
void vtkPiPrimitiveSource::SetAngle(double degrees)
{
  this->Primitive->SetAngle(degrees);
}
double vtkPiPrimitiveSource::GetAngle()
{
  return this->Primitive->GetAngle();
}
void vtkPiPrimitiveSource::SetAxis(double x, double y, double z)
{
  this->Primitive->SetAxis(x, y, z);
}
double* vtkPiPrimitiveSource::GetAxis()
{
  return this->Primitive->GetAxis();
}
void vtkPiPrimitiveSource::SetRotationAxis(double x, double y, double z)
{
  this->Primitive->SetRotationAxis(x, y, z);
}
double* vtkPiPrimitiveSource::GetRotationAxis()
{
  return this->Primitive->GetRotationAxis();
}
void vtkPiPrimitiveSource::SetRotationAngle(double degrees)
{
  this->Primitive->SetRotationAngle(degrees);
}
double vtkPiPrimitiveSource::GetRotationAngle()
{
  return this->Primitive->GetRotationAngle();
}
void vtkPiPrimitiveSource::SetOrientation(double x, double y, double z)
{
  this->Primitive->SetOrientation(x, y, z);
}
double* vtkPiPrimitiveSource::GetOrientation()
{
  return this->Primitive->GetOrientation();
}
void vtkPiPrimitiveSource::SetExpression(const char* expression)
{
  this->Primitive->SetExpression(expression);
}
const char* vtkPiPrimitiveSource::GetExpression()
{
  return this->Primitive->GetExpression();
}
void vtkPiPrimitiveSource::SetScale(double s)
{
  this->Primitive->SetScale(s);
}
double vtkPiPrimitiveSource::GetScale()
{
  return this->Primitive->GetScale();
}
void vtkPiPrimitiveSource::SetNegate(bool negate)
{
  this->Primitive->SetNegate(negate);
}
bool vtkPiPrimitiveSource::GetNegate()
{
  return this->Primitive->GetNegate();
}
void vtkPiPrimitiveSource::SetName(const char* name)
{
  this->Primitive->SetName(name);
}
const char* vtkPiPrimitiveSource::GetName()
{
  return this->Primitive->GetName();
}

bool vtkPiPrimitiveSource::ResolveBounds(double bounds[6], std::string& error)
{
  vtkPiPrimitive* p = this->Primitive;
  if (!p->IsValid())
  {
    error = std::string("Invalid ") + p->GetTypeAsString() + ": " + p->GetErrorMessage();
    return false;
  }
  const bool automatic = pisurf::UnsetBounds(this->Bounds);
  if (!automatic)
  {
    if (!pisurf::ValidBounds(this->Bounds))
    {
      error = "Bounds must be finite with x0 < x1, y0 < y1, z0 < z1 (or all 0: automatic)";
      return false;
    }
    std::copy(this->Bounds, this->Bounds + 6, bounds);
    return true;
  }
  if (p->IsBounded())
  {
    // The primitive's box grown until f has one sign on it (the model's automatic bounds).
    vtkNew<vtkPiSurface> alone;
    alone->AddFactor(p);
    if (!alone->GetModelBounds(bounds))
    {
      error = std::string("no automatic bounds: ") + alone->GetErrorMessage();
      return false;
    }
    return true;
  }
  // The largest of the type's lengths (a cylinder's radius, a hyperboloid's semi-axes),
  // or 1 for a type without one.
  double size = 1.0;
  bool sized = false;
  pisurf::PrimitiveSpec spec = p->GetSpec();
  for (const pisurf::ParameterInfo& parameter :
    pisurf::CatalogueEntry(static_cast<pisurf::PrimitiveType>(p->GetType())).Parameters)
  {
    if (parameter.Kind == pisurf::ParameterKind::Number && std::string(parameter.Unit) == "length")
    {
      const double* v = parameter.Numbers(spec);
      for (int i = 0; i < parameter.Count; ++i)
      {
        size = sized ? std::max(size, v[i]) : v[i];
        sized = true;
      }
    }
  }
  const double* c = p->GetCenter();
  for (int a = 0; a < 3; ++a)
  {
    bounds[2 * a] = c[a] - 2 * size;
    bounds[2 * a + 1] = c[a] + 2 * size;
  }
  return true;
}

std::string vtkPiPrimitiveSource::GetModelJSON()
{
  double bounds[6];
  std::string error;
  if (!this->ResolveBounds(bounds, error))
  {
    vtkErrorMacro(<< error);
    return std::string();
  }
  pisurf::Model model;
  model.Blending = 0.0;
  model.Primitives.push_back(this->Primitive->GetSpec());
  if (!this->Primitive->IsBounded())
  {
    model.HasBounds = true;
    std::copy(bounds, bounds + 6, model.Bounds);
  }
  return pisurf::WriteModel(model);
}

int vtkPiPrimitiveSource::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // The mesher splits its grid into slabs of blocks along z.
  outputVector->GetInformationObject(0)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  return 1;
}

int vtkPiPrimitiveSource::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const pisurf::Piece request = pisurf::PieceOf(outInfo);
  const int piece = request.Piece, pieces = request.Pieces;
  double bounds[6];
  std::string error;
  if (!this->ResolveBounds(bounds, error))
  {
    vtkErrorMacro(<< error);
    this->LastValid->Fail();
    return 1; // an empty output, not a pipeline failure: downstream sees "no model"
  }
  if (this->Primitive->IsBounded())
  {
    this->Surface->ClearModelBounds();
  }
  else
  {
    // The model in the field data must say where an unbounded primitive is looked at.
    this->Surface->SetModelBounds(bounds);
  }
  this->Mesher->SetBounds(bounds);
  this->Mesher->SetResolution(this->Resolution);
  this->Mesher->UpdatePiece(piece, pieces, 0);
  output->ShallowCopy(this->Mesher->GetOutput());
  return 1;
}

void vtkPiPrimitiveSource::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "Primitive:\n";
  this->Primitive->PrintSelf(os, indent.GetNextIndent());
  os << indent << "Bounds: (" << this->Bounds[0] << ", " << this->Bounds[1] << ", "
     << this->Bounds[2] << ", " << this->Bounds[3] << ", " << this->Bounds[4] << ", "
     << this->Bounds[5] << ")\n";
  os << indent << "Resolution: " << this->Resolution << "\n";
}
