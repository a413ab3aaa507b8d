// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiModelMesher.h"

#include "PiLastValidOutput.h"
#include "PiMeshingGrid.h"
#include "PiMeshingMethod.h"
#include "PiPieces.h"
#include "PiPrimitiveMeshes.h"
#include "RayCasting/PiRayPointOutput.h"
#include "vtkPiSurface.h"

#include "vtkDataObject.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerRequestKey.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkNew.h"
#include "vtkPointData.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cmath>
#include <dlfcn.h>
#include <string>

struct vtkPiModelMesher::vtkInternals
{
  vtkNew<vtkPiSurface> Surface;
  std::unique_ptr<pisurf::MeshingMethod> FlyingEdges, RayCast;
  // The ports the current REQUEST_DATA leaves as they are (DATA_NOT_GENERATED).
  bool SkipMesh = false, SkipPrimitives = false;
  // Whether port 0 holds a flying-edges mesh, and for which piece: port 1 alone is then
  // meshed on its grid.
  bool HasMesh = false;
  pisurf::Piece MeshPiece;
  // Whether port 0 holds the model alone.
  bool ModelOnly = false;
};

namespace
{
// MODEL_ONLY(): copied upstream with the update request (vtkInformationIntegerRequestKey).
// An algorithm re-executes for it only when the mesh is asked for (0) and its output
// holds the model alone (the field data PiModelOnly): a mesh serves a model-only request,
// and the pass-through filters between the mesher and its consumers (ParaView's post
// filter) re-execute, and so forward the request, exactly when the mesher must.
class ModelOnlyRequestKey : public vtkInformationIntegerRequestKey
{
public:
  ModelOnlyRequestKey(const char* name, const char* location)
    : vtkInformationIntegerRequestKey(name, location)
  {
  }
  bool NeedToExecute(vtkInformation* pipelineInfo, vtkInformation*) override
  {
    vtkDataObject* data = pipelineInfo->Get(vtkDataObject::DATA_OBJECT());
    return pipelineInfo->Get(this) == 0 && data && data->GetFieldData() &&
      data->GetFieldData()->GetAbstractArray("PiModelOnly");
  }
  void StoreMetaData(vtkInformation*, vtkInformation*, vtkInformation*) override {}
};
}

vtkInformationIntegerRequestKey* vtkPiModelMesher::MODEL_ONLY()
{
  static vtkInformationIntegerRequestKey* key = []()
  {
    // VTK's key manager (which the key's constructor registers it with) deletes the key
    // when VTK's library is finalized. This library, which holds the key's class, must
    // still be loaded then: a plugin that brought it in may be unloaded before.
    Dl_info self;
    if (dladdr(reinterpret_cast<void*>(&vtkPiModelMesher::MODEL_ONLY), &self) && self.dli_fname)
    {
      dlopen(self.dli_fname, RTLD_NOW | RTLD_NOLOAD | RTLD_NODELETE);
    }
    return new ModelOnlyRequestKey("MODEL_ONLY", "vtkPiModelMesher");
  }();
  return key;
}

vtkPiModelMesher::vtkPiModelMesher()
  : LastValid(new pisurf::LastValidOutput)
  , Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(2);
  this->Internals->FlyingEdges = pisurf::NewFlyingEdgesMethod(this);
  this->Internals->RayCast = pisurf::NewRayCastTriangulationMethod(this);
}

vtkPiModelMesher::~vtkPiModelMesher() = default;

bool vtkPiModelMesher::GetLastOutputModelOnly()
{
  return this->Internals->ModelOnly;
}

vtkPiSurface* vtkPiModelMesher::GetPiSurface()
{
  return this->Internals->Surface;
}

bool vtkPiModelMesher::ComputeGrid(const double b[6], int dims[3], double spacing[3])
{
  return this->ComputeGrid(b, this->Resolution, dims, spacing);
}

bool vtkPiModelMesher::ComputeGrid(
  const double b[6], int resolution, int dims[3], double spacing[3])
{
  std::string error;
  if (!pisurf::ComputeMeshingGrid(
        b, resolution, this->SampleDimensions, this->MaximumNumberOfSamples, dims, spacing, error))
  {
    vtkErrorMacro(<< error);
    return false;
  }
  return true;
}

vtkTypeBool vtkPiModelMesher::ProcessRequest(
  vtkInformation* request, vtkInformationVector** inputs, vtkInformationVector* outputs)
{
  if (request->Has(vtkDemandDrivenPipeline::REQUEST_DATA_NOT_GENERATED()))
  {
    this->MarkPortsNotGenerated(request, outputs);
    return 1;
  }
  return this->LastValid->Process(request, this->KeepLastValidOutput, outputs,
    [&]() { return this->Superclass::ProcessRequest(request, inputs, outputs); });
}

void vtkPiModelMesher::MarkPortsNotGenerated(vtkInformation* request, vtkInformationVector* outputs)
{
  vtkInternals& in = *this->Internals;
  const pisurf::PortsNotGenerated marks = pisurf::MarkPortsNotGenerated(this, request, outputs,
    this->PrimitivesOnDemand, in.HasMesh && this->Method == FLYING_EDGES, in.MeshPiece);
  in.SkipMesh = marks.Mesh;
  in.SkipPrimitives = marks.Primitives;
}

int vtkPiModelMesher::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  for (int port = 0; port < this->GetNumberOfOutputPorts(); ++port)
  {
    outputVector->GetInformationObject(port)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  }
  return 1;
}

int vtkPiModelMesher::RequestData(
  vtkInformation*, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  vtkInternals& in = *this->Internals;
  // (The marks hold for this execution only.)
  struct Unmark
  {
    vtkInternals& In;
    ~Unmark() { In.SkipMesh = In.SkipPrimitives = false; }
  } unmark{ in };
  const bool overrideBlending = this->OverrideBlending && this->CanOverrideBlending();
  if (overrideBlending && !std::isfinite(this->Blending))
  {
    vtkErrorMacro(<< "Blending must be a finite number");
    return 0;
  }
  // Port 1 alone (SkipMesh) follows a successful mesh with the same settings and inputs:
  // the surface holds its model already, and reloading it would re-mesh port 0 inside.
  if (!in.SkipMesh)
  {
    in.HasMesh = false;
    if (!this->LoadModel(inputVector, in.Surface))
    {
      return 0;
    }
    if (overrideBlending)
    {
      in.Surface->SetBlending(this->Blending);
    }
  }
  // The model alone when the request asks only for it and port 1 is not asked for (its
  // primitives are meshed on the mesh's grid).
  if (!in.SkipMesh)
  {
    in.ModelOnly = false;
    vtkInformation* meshInfo = outputVector->GetInformationObject(0);
    if ((in.SkipPrimitives || !this->GeneratePrimitives) && meshInfo->Has(MODEL_ONLY()) &&
      meshInfo->Get(MODEL_ONLY()) == 1)
    {
      return this->OutputModelOnly(vtkPolyData::GetData(outputVector, 0));
    }
  }
  pisurf::MeshingRequest request;
  request.Surface = in.Surface;
  request.Asked = pisurf::PieceOf(outputVector->GetInformationObject(in.SkipMesh ? 1 : 0));
  request.Mesh = !in.SkipMesh;
  request.Primitives = !in.SkipPrimitives;
  const bool flyingEdges = this->Method == FLYING_EDGES;
  pisurf::MeshingMethod& method = flyingEdges ? *in.FlyingEdges : *in.RayCast;
  const int result = method.Execute(
    request, vtkPolyData::GetData(outputVector, 0), vtkPolyData::GetData(outputVector, 1));
  if (flyingEdges)
  {
    this->LastResolution = method.GetLastResolution();
  }
  if (request.Mesh)
  {
    in.HasMesh = result != 0 && method.ServesPrimitivesAlone();
    in.MeshPiece = request.Asked;
  }
  return result;
}

int vtkPiModelMesher::OutputModelOnly(vtkPolyData* output)
{
  vtkInternals& in = *this->Internals;
  double b[6];
  if (!in.Surface->ResolveBounds(this->Bounds, b))
  {
    vtkErrorMacro(<< "No bounds: set Bounds, or give the model bounds or bounded primitives");
    return 0;
  }
  output->Initialize();
  vtkNew<vtkPoints> corners;
  corners->SetDataTypeToDouble();
  for (int k = 0; k < 8; ++k)
  {
    corners->InsertNextPoint(b[k & 1], b[2 + ((k >> 1) & 1)], b[4 + ((k >> 2) & 1)]);
  }
  output->SetPoints(corners);
  // Factor on the corners runs over the model's factor indices 0 .. n-1, so that
  // ParaView offers colouring by Factor with the model's range, as for the mesh.
  vtkNew<vtkIntArray> factor;
  factor->SetName("Factor");
  const int last = std::max(in.Surface->GetNumberOfFactors() - 1, 0);
  for (int k = 0; k < 8; ++k)
  {
    factor->InsertNextValue(static_cast<int>(std::lround(k * last / 7.0)));
  }
  output->GetPointData()->AddArray(factor);
  pisurf::RayPointOutput::AddModel(*in.Surface, b, output);
  vtkNew<vtkIntArray> flag;
  flag->SetName("PiModelOnly");
  flag->InsertNextValue(1);
  output->GetFieldData()->AddArray(flag);
  in.ModelOnly = true;
  return 1;
}

void vtkPiModelMesher::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PiSurface: " << this->Internals->Surface.GetPointer() << "\n";
  os << indent << "Method: " << this->Method << "\n";
  os << indent << "OverrideBlending: " << (this->OverrideBlending ? "On" : "Off") << "\n";
  os << indent << "Blending: " << this->Blending << "\n";
  os << indent << "Bounds: (" << this->Bounds[0] << ", " << this->Bounds[1] << ", "
     << this->Bounds[2] << ", " << this->Bounds[3] << ", " << this->Bounds[4] << ", "
     << this->Bounds[5] << ")\n";
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "SampleDimensions: (" << this->SampleDimensions[0] << ", "
     << this->SampleDimensions[1] << ", " << this->SampleDimensions[2] << ")\n";
  os << indent << "MaximumNumberOfSamples: " << this->MaximumNumberOfSamples << "\n";
  os << indent << "ProjectVertices: " << (this->ProjectVertices ? "On" : "Off") << "\n";
  os << indent << "OuterEnvelope: " << (this->OuterEnvelope ? "On" : "Off") << "\n";
  os << indent << "ComputeGradientMagnitude: " << (this->ComputeGradientMagnitude ? "On" : "Off")
     << "\n";
  os << indent << "GeneratePrimitives: " << (this->GeneratePrimitives ? "On" : "Off") << "\n";
  os << indent << "PrimitivesOnDemand: " << (this->PrimitivesOnDemand ? "On" : "Off") << "\n";
  os << indent << "AutomaticResolution: " << (this->AutomaticResolution ? "On" : "Off") << "\n";
  os << indent << "MaximumAutomaticResolution: " << this->MaximumAutomaticResolution << "\n";
  os << indent << "LastResolution: " << this->LastResolution << "\n";
  os << indent << "KeepLastValidOutput: " << (this->KeepLastValidOutput ? "On" : "Off") << "\n";
  os << indent << "LastOutputModelOnly: " << (this->Internals->ModelOnly ? "yes" : "no") << "\n";
}
