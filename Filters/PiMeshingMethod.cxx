// SPDX-License-Identifier: BSD-3-Clause
#include "PiMeshingMethod.h"

#include "PiInnerAlgorithm.h"
#include "PiPrimitiveMeshes.h"
#include "vtkPiFlyingEdges.h"
#include "vtkPiImageTriangulator.h"
#include "vtkPiModelMesher.h"
#include "vtkPiRayCaster.h"
#include "vtkPiSurface.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

#include <algorithm>
#include <cstdlib>
#include <string>

namespace pisurf
{
namespace
{

// An inner algorithm's errors and warnings as the mesher's own: the same file, line and
// text, its name replaced by the mesher's (the output window then gives them to the
// mesher's observers, as it does the mesher's own).
class ForwardMessages : public vtkCommand
{
public:
  static ForwardMessages* New() { return new ForwardMessages; }
  void Execute(vtkObject* caller, unsigned long event, void* data) override
  {
    // The event's text: "ERROR: In <file>, line <n>\n<description>: <message>\n\n".
    std::string text = data ? static_cast<const char*>(data) : "";
    std::string file;
    int line = 0;
    const size_t in = text.find("In "), comma = text.find(", line "), end = text.find('\n');
    if (in != std::string::npos && comma != std::string::npos && end != std::string::npos &&
      in < comma && comma < end)
    {
      file = text.substr(in + 3, comma - in - 3);
      line = std::atoi(text.c_str() + comma + 7);
      text.erase(0, end + 1);
    }
    while (!text.empty() && text.back() == '\n')
    {
      text.pop_back();
    }
    const std::string inner = caller->GetObjectDescription();
    const size_t at = text.find(inner);
    if (at != std::string::npos)
    {
      text.replace(at, inner.size(), this->Outer->GetObjectDescription());
    }
    if (event == vtkCommand::ErrorEvent)
    {
      vtkOutputWindowDisplayErrorText(file.c_str(), line, text.c_str(), this->Outer);
    }
    else
    {
      vtkOutputWindowDisplayWarningText(file.c_str(), line, text.c_str(), this->Outer);
    }
  }
  vtkObject* Outer = nullptr;
};

class FlyingEdges : public MeshingMethod
{
public:
  explicit FlyingEdges(vtkPiModelMesher* mesher)
    : Mesher(mesher)
  {
    pisurf::WorkFor(this->Inner, mesher, 0.0, 1.0);
    vtkNew<ForwardMessages> forward;
    forward->Outer = mesher;
    this->Inner->AddObserver(vtkCommand::ErrorEvent, forward);
    this->Inner->AddObserver(vtkCommand::WarningEvent, forward);
    // A failed execution is reported by the mesher's executive, not twice.
    vtkNew<vtkCallbackCommand> quiet;
    this->Inner->GetExecutive()->AddObserver(vtkCommand::ErrorEvent, quiet);
  }

  int Execute(const MeshingRequest& request, vtkPolyData* mesh, vtkPolyData* primitives) override
  {
    vtkPiModelMesher* m = this->Mesher;
    vtkPiFlyingEdges* fe = this->Inner;
    fe->SetPiSurface(request.Surface);
    fe->SetBounds(m->GetBounds());
    fe->SetResolution(m->GetResolution());
    fe->SetSampleDimensions(m->GetSampleDimensions());
    fe->SetMaximumNumberOfSamples(m->GetMaximumNumberOfSamples());
    fe->SetProjectVertices(m->GetProjectVertices());
    fe->SetOuterEnvelope(m->GetOuterEnvelope());
    fe->SetComputeGradientMagnitude(m->GetComputeGradientMagnitude());
    fe->SetGeneratePrimitives(m->GetGeneratePrimitives());
    fe->SetAutomaticResolution(m->GetAutomaticResolution());
    fe->SetMaximumAutomaticResolution(m->GetMaximumAutomaticResolution());
    // Port 1 only when it is wanted: asked from port 0, it is then left as it is (asked
    // from port 1, the setting does not apply and is left, so the mesh stays up to date).
    if (request.Mesh)
    {
      fe->SetPrimitivesOnDemand(!request.Primitives);
    }
    // The same piece on both ports as the mesher's request.
    vtkNew<vtkInformationVector> requests;
    requests->SetNumberOfInformationObjects(fe->GetNumberOfOutputPorts());
    for (int port = 0; port < fe->GetNumberOfOutputPorts(); ++port)
    {
      vtkInformation* info = requests->GetInformationObject(port);
      info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_PIECE_NUMBER(), request.Asked.Piece);
      info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_PIECES(), request.Asked.Pieces);
      info->Set(vtkStreamingDemandDrivenPipeline::UPDATE_NUMBER_OF_GHOST_LEVELS(), 0);
    }
    const int result = fe->Update(request.Mesh ? 0 : 1, requests);
    if (request.Mesh)
    {
      mesh->ShallowCopy(fe->GetOutput(0));
    }
    if (request.Primitives && primitives)
    {
      primitives->ShallowCopy(fe->GetOutput(1));
    }
    return result;
  }

  int GetLastResolution() const override { return this->Inner->GetLastResolution(); }
  bool ServesPrimitivesAlone() const override { return true; }

private:
  vtkPiModelMesher* Mesher;
  vtkNew<vtkPiFlyingEdges> Inner;
};

class RayCastTriangulation : public MeshingMethod
{
public:
  explicit RayCastTriangulation(vtkPiModelMesher* mesher)
    : Mesher(mesher)
  {
    this->Triangulator->SetInputConnection(this->Caster->GetOutputPort());
    this->Triangulator->SetMergeMode(vtkPiImageTriangulator::RAY_LATTICE);
    // Their progress is the mesher's (the casts from 0 to 0.5, the triangulation from
    // 0.5 to 1), and so is its cancel.
    pisurf::WorkFor(this->Caster, mesher, 0.0, 0.5);
    pisurf::WorkFor(this->Triangulator, mesher, 0.5, 0.5);
  }

  int Execute(const MeshingRequest& request, vtkPolyData* output, vtkPolyData* primitives) override
  {
    vtkPiModelMesher* m = this->Mesher;
    if (request.Asked.Piece > 0)
    {
      // The ray lattice is not split into pieces: the first piece holds the whole mesh.
      return 1;
    }
    double bounds[6];
    if (!request.Surface->ResolveBounds(m->GetBounds(), bounds))
    {
      vtkErrorWithObjectMacro(m, << "No bounds to mesh in: " << request.Surface->GetErrorMessage());
      return 0;
    }
    int dims[3];
    double spacing[3];
    if (!m->ComputeGrid(bounds, dims, spacing))
    {
      return 0;
    }
    // One lattice resolution on the three axes (the views share their pixel counts).
    const int n = std::max(dims[0], std::max(dims[1], dims[2])) - 1;
    this->Caster->SetPiSurface(request.Surface);
    this->Caster->SetBounds(bounds);
    this->Caster->SetResolution(n, n);
    this->Caster->SetViewMode(m->GetOuterEnvelope() ? vtkPiRayCaster::SIX_AXIS_VIEWS
                                                    : vtkPiRayCaster::THREE_AXIS_DIRECTIONS);
    this->Caster->Update();
    if (m->CheckAbort())
    {
      return 1; // cancelled while casting: the triangulator has nothing to do
    }
    this->Triangulator->Update();
    if (m->CheckAbort())
    {
      return 1;
    }
    output->ShallowCopy(this->Triangulator->GetOutput());
    if (m->GetGeneratePrimitives() && primitives)
    {
      pisurf::MeshPrimitives(
        request.Surface, bounds, dims, 0, 1, m->GetProjectVertices(), m, primitives);
    }
    m->UpdateProgress(1.0);
    return 1;
  }

private:
  vtkPiModelMesher* Mesher;
  vtkNew<vtkPiRayCaster> Caster;
  vtkNew<vtkPiImageTriangulator> Triangulator;
};

}

std::unique_ptr<MeshingMethod> NewFlyingEdgesMethod(vtkPiModelMesher* mesher)
{
  return std::unique_ptr<MeshingMethod>(new FlyingEdges(mesher));
}

std::unique_ptr<MeshingMethod> NewRayCastTriangulationMethod(vtkPiModelMesher* mesher)
{
  return std::unique_ptr<MeshingMethod>(new RayCastTriangulation(mesher));
}

}
