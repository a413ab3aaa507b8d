// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiFlyingEdges.h"
#include "PiPieces.h"
#include "PiTiming.h"

#include "PiLastValidOutput.h"
#include "PiMeshingGrid.h"
#include "PiPrimitiveMeshes.h"

#include "Meshing/PiBlockGrid.h"
#include "Meshing/PiMeshingDriver.h"
#include "Meshing/PiMeshingWork.h"
#include "PiModel.h"
#include "PiProductField.h"
#include "PiProductKernel.h"
#include "vtkPiSurface.h"

#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkGarbageCollector.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkIntArray.h"
#include "vtkMassProperties.h"
#include "vtkObjectFactory.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkPolyDataConnectivityFilter.h"
#include "vtkStreamingDemandDrivenPipeline.h"
#include "vtkStringArray.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <new>
#include <sstream>
#include <string>
#include <utility>

vtkStandardNewMacro(vtkPiFlyingEdges);
vtkCxxSetObjectMacro(vtkPiFlyingEdges, PiSurface, vtkPiSurface);

struct vtkPiFlyingEdges::vtkInternals
{
  pisurf::MeshingWork Work;
  std::shared_ptr<const pisurf::Field> Field;
  // The ports the current REQUEST_DATA leaves as they are (DATA_NOT_GENERATED).
  bool SkipMesh = false, SkipPrimitives = false;
  // The grid of the last mesh (port 0), for the primitives of an execution that only
  // asks for port 1.
  double MeshBounds[6] = { 0, 0, 0, 0, 0, 0 };
  int MeshDims[3] = { 0, 0, 0 };
  pisurf::Piece MeshPiece;
  // The last primitives (port 1) and what they were meshed from: the primitives
  // without the blending, the grid, ProjectVertices and the piece.
  std::string PrimitivesKey;
  vtkSmartPointer<vtkPolyData> Primitives;
};

void vtkPiFlyingEdges::SetField(std::shared_ptr<const pisurf::Field> field)
{
  if (field != this->Internals->Field)
  {
    this->Internals->Field = std::move(field);
    this->Modified();
  }
}

vtkPiFlyingEdges::vtkPiFlyingEdges()
  : LastValid(new pisurf::LastValidOutput)
  , Internals(new vtkInternals)
{
  this->SetNumberOfInputPorts(0);
  this->SetNumberOfOutputPorts(2);
}

vtkPiFlyingEdges::~vtkPiFlyingEdges()
{
  this->SetPiSurface(nullptr);
}

vtkTypeBool vtkPiFlyingEdges::ProcessRequest(
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

void vtkPiFlyingEdges::MarkPortsNotGenerated(vtkInformation* request, vtkInformationVector* outputs)
{
  vtkInternals& in = *this->Internals;
  const pisurf::PortsNotGenerated marks = pisurf::MarkPortsNotGenerated(
    this, request, outputs, this->PrimitivesOnDemand, in.MeshDims[0] > 0, in.MeshPiece);
  in.SkipMesh = marks.Mesh;
  in.SkipPrimitives = marks.Primitives;
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

int vtkPiFlyingEdges::RequestInformation(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // Pieces are slabs of blocks along z (see RequestData).
  for (int port = 0; port < this->GetNumberOfOutputPorts(); ++port)
  {
    outputVector->GetInformationObject(port)->Set(vtkAlgorithm::CAN_HANDLE_PIECE_REQUEST(), 1);
  }
  return 1;
}

bool vtkPiFlyingEdges::ComputeGrid(const double b[6], int dims[3], double spacing[3])
{
  return this->ComputeGrid(b, this->Resolution, dims, spacing);
}

bool vtkPiFlyingEdges::ComputeGrid(
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

int vtkPiFlyingEdges::RequestData(
  vtkInformation*, vtkInformationVector**, vtkInformationVector* outputVector)
{
  // (The marks hold for this execution only.)
  struct Unmark
  {
    vtkInternals& In;
    ~Unmark() { In.SkipMesh = In.SkipPrimitives = false; }
  } unmark{ *this->Internals };
  try
  {
    if (this->Internals->SkipMesh)
    {
      this->OutputPrimitives(outputVector);
      return 1;
    }
    return this->GenerateMesh(outputVector);
  }
  catch (const std::bad_alloc&)
  {
    // The sizes are checked against MaximumNumberOfSamples first; this is a machine
    // with less memory than that cap assumes.
    vtkPolyData::GetData(outputVector, 0)->Initialize();
    vtkErrorMacro(<< "Out of memory while meshing: lower the Resolution or "
                     "MaximumNumberOfSamples");
    return 0;
  }
}

int vtkPiFlyingEdges::GenerateMesh(vtkInformationVector* outputVector)
{
  // PISURF_TIMING=1: the wall time of each pass on stderr.
  pisurf::PassTimer lap("vtkPiFlyingEdges");
  vtkPolyData* output = vtkPolyData::GetData(outputVector, 0);
  vtkPolyData* primitives = vtkPolyData::GetData(outputVector, 1);
  vtkInformation* outInfo = outputVector->GetInformationObject(0);
  const pisurf::Piece request = pisurf::PieceOf(outInfo);
  const int piece = request.Piece, pieces = request.Pieces;
  // The field set (SetField), else the product of the Pi-surface.
  std::shared_ptr<const pisurf::Field> field = this->Internals->Field;
  const bool fieldSet = field != nullptr;
  double bounds[6];
  if (fieldSet)
  {
    std::copy(this->Bounds, this->Bounds + 6, bounds);
    if (!(bounds[0] < bounds[1] && bounds[2] < bounds[3] && bounds[4] < bounds[5]))
    {
      vtkErrorMacro(<< "A field is meshed in explicit Bounds: set them");
      return 0;
    }
  }
  else
  {
    if (!this->PiSurface)
    {
      vtkErrorMacro(<< "No Pi-surface to mesh: call SetPiSurface()");
      return 0;
    }
    std::shared_ptr<const pisurf::ProductKernel> kernel = this->PiSurface->GetKernel();
    if (!kernel || kernel->GetNumberOfFactors() == 0)
    {
      vtkErrorMacro(<< "The Pi-surface is invalid or has no factors"
                    << (*this->PiSurface->GetErrorMessage() ? ": " : "")
                    << this->PiSurface->GetErrorMessage());
      return 0;
    }
    if (!this->PiSurface->ResolveBounds(this->Bounds, bounds))
    {
      vtkErrorMacro(<< "No bounds to mesh in: " << this->PiSurface->GetErrorMessage());
      return 0;
    }
    field = std::make_shared<pisurf::ProductField>(std::move(kernel));
  }

  int resolution = this->Resolution;
  const bool explicitDimensions = this->SampleDimensions[0] != 0 ||
    this->SampleDimensions[1] != 0 || this->SampleDimensions[2] != 0;
  if (this->AutomaticResolution && !explicitDimensions && !fieldSet)
  {
    resolution = this->ChooseResolution(bounds);
    if (resolution <= 0)
    {
      return 0;
    }
  }
  this->LastResolution = resolution;
  pisurf::BlockGrid g;
  if (!this->ComputeGrid(bounds, resolution, g.Dims, g.Spacing))
  {
    return 0;
  }
  for (int a = 0; a < 3; ++a)
  {
    g.Origin[a] = bounds[2 * a];
    // (dims − 1) / B + 1 blocks: the last point plane always lies in the last block at a
    // local index below BlockCells (that block may be a single plane without cells).
    g.Count[a] = (g.Dims[a] - 1) / pisurf::BlockCells + 1;
  }
  const double size = std::sqrt((bounds[1] - bounds[0]) * (bounds[1] - bounds[0]) +
    (bounds[3] - bounds[2]) * (bounds[3] - bounds[2]) +
    (bounds[5] - bounds[4]) * (bounds[5] - bounds[4]));
  const pisurf::MeshingDriver::Settings settings{ this->OuterEnvelope, this->ProjectVertices,
    this->ComputeGradientMagnitude, this->MaximumNumberOfSamples, size };
  pisurf::MeshingDriver driver(this, this->Internals->Work, lap);
  const pisurf::MeshingDriver::Result result =
    driver.Run(*field, g, piece, pieces, settings, output);
  if (result != pisurf::MeshingDriver::Meshed)
  {
    return result == pisurf::MeshingDriver::Failed ? 0 : 1;
  }
  const vtkIdType vertices = driver.GetNumberOfVertices();

  pisurf::Model model;
  if (!fieldSet && this->PiSurface->GetCoreModel(model))
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
  vtkInternals& in = *this->Internals;
  std::copy(bounds, bounds + 6, in.MeshBounds);
  std::copy(g.Dims, g.Dims + 3, in.MeshDims);
  in.MeshPiece = request;
  if (!in.SkipPrimitives && !fieldSet)
  {
    this->OutputPrimitives(outputVector);
  }
  // (One piece of several may be empty while the others are not: no warning then.)
  if (vertices == 0 && pieces == 1)
  {
    vtkWarningMacro(<< "The Pi-surface does not cross the bounds [" << bounds[0] << ", "
                    << bounds[1] << "] x [" << bounds[2] << ", " << bounds[3] << "] x ["
                    << bounds[4] << ", " << bounds[5] << "] at this resolution: empty mesh");
  }
  lap("output");
  lap.Total("total");
  this->UpdateProgress(1.0);
  return 1;
}

int vtkPiFlyingEdges::ChooseResolution(const double bounds[6])
{
  int previousComponents = -1;
  double previousArea = 0.0;
  int chosen = 0;
  for (int resolution = 32; resolution <= this->MaximumAutomaticResolution; resolution *= 2)
  {
    int dims[3];
    double spacing[3];
    const double side =
      std::max({ bounds[1] - bounds[0], bounds[3] - bounds[2], bounds[5] - bounds[4] });
    double samples = 1.0;
    for (int a = 0; a < 3; ++a)
    {
      samples *= std::ceil((bounds[2 * a + 1] - bounds[2 * a]) / side * resolution) + 1;
    }
    if (samples > static_cast<double>(this->MaximumNumberOfSamples) ||
      !this->ComputeGrid(bounds, resolution, dims, spacing))
    {
      break;
    }
    vtkNew<vtkPiFlyingEdges> mesher;
    mesher->SetPiSurface(this->PiSurface);
    mesher->SetBounds(bounds);
    mesher->SetResolution(resolution);
    mesher->SetOuterEnvelope(this->OuterEnvelope);
    mesher->SetProjectVertices(this->ProjectVertices);
    mesher->SetMaximumNumberOfSamples(this->MaximumNumberOfSamples);
    vtkNew<vtkCallbackCommand> quiet;
    mesher->AddObserver(vtkCommand::WarningEvent, quiet);
    mesher->Update();
    vtkNew<vtkPolyDataConnectivityFilter> connectivity;
    connectivity->SetInputConnection(mesher->GetOutputPort());
    connectivity->SetExtractionModeToAllRegions();
    connectivity->Update();
    const int components = connectivity->GetNumberOfExtractedRegions();
    vtkNew<vtkMassProperties> mass;
    mass->SetInputConnection(mesher->GetOutputPort());
    mass->Update();
    const double area = mesher->GetOutput()->GetNumberOfCells() > 0 ? mass->GetSurfaceArea() : 0.0;
    chosen = resolution;
    if (components > 0 && components == previousComponents &&
      std::fabs(area - previousArea) <= 0.01 * area)
    {
      return resolution;
    }
    previousComponents = components;
    previousArea = area;
    if (this->CheckAbort())
    {
      break;
    }
  }
  if (chosen == 0)
  {
    vtkErrorMacro(<< "AutomaticResolution: no resolution from 32 fits MaximumNumberOfSamples");
    return 0;
  }
  vtkWarningMacro(<< "AutomaticResolution: the mesh had not settled (components and area) by "
                  << chosen << " cells; using " << chosen);
  return chosen;
}

void vtkPiFlyingEdges::OutputPrimitives(vtkInformationVector* outputVector)
{
  vtkInternals& in = *this->Internals;
  vtkPolyData* out = vtkPolyData::GetData(outputVector, 1);
  if (!this->GeneratePrimitives || !out || in.Field || !this->PiSurface || in.MeshDims[0] == 0)
  {
    return;
  }
  // The primitives depend on the factors, not on the blending: the same factors on the
  // same grid give the same meshes, kept from the last time.
  std::ostringstream key;
  pisurf::Model model;
  const bool keyed = this->PiSurface->GetCoreModel(model);
  if (keyed)
  {
    model.Blending = 0.0;
    model.HasBounds = false;
    key.precision(17);
    key << pisurf::WriteModel(model) << "|" << this->ProjectVertices << "|" << in.MeshPiece.Piece
        << "/" << in.MeshPiece.Pieces;
    for (int a = 0; a < 6; ++a)
    {
      key << "|" << in.MeshBounds[a];
    }
    for (int a = 0; a < 3; ++a)
    {
      key << "|" << in.MeshDims[a];
    }
    if (in.Primitives && key.str() == in.PrimitivesKey)
    {
      out->ShallowCopy(in.Primitives);
      return;
    }
  }
  this->MeshPrimitives(in.MeshBounds, in.MeshDims, in.MeshPiece.Piece, in.MeshPiece.Pieces, out);
  if (keyed && !this->CheckAbort())
  {
    in.PrimitivesKey = key.str();
    in.Primitives = vtkSmartPointer<vtkPolyData>::New();
    in.Primitives->ShallowCopy(out);
  }
  else
  {
    in.PrimitivesKey.clear();
    in.Primitives = nullptr;
  }
}

void vtkPiFlyingEdges::MeshPrimitives(
  const double bounds[6], const int dims[3], int piece, int pieces, vtkPolyData* out)
{
  pisurf::MeshPrimitives(
    this->PiSurface, bounds, dims, piece, pieces, this->ProjectVertices, this, out);
}

void vtkPiFlyingEdges::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "PiSurface: " << this->PiSurface << "\n";
  os << indent << "Field: " << (this->Internals->Field ? "set" : "(none)") << "\n";
  os << indent << "Bounds: (" << this->Bounds[0] << ", " << this->Bounds[1] << ", "
     << this->Bounds[2] << ", " << this->Bounds[3] << ", " << this->Bounds[4] << ", "
     << this->Bounds[5] << ")\n";
  os << indent << "Resolution: " << this->Resolution << "\n";
  os << indent << "SampleDimensions: (" << this->SampleDimensions[0] << ", "
     << this->SampleDimensions[1] << ", " << this->SampleDimensions[2] << ")\n";
  os << indent << "MaximumNumberOfSamples: " << this->MaximumNumberOfSamples << "\n";
  os << indent << "ProjectVertices: " << (this->ProjectVertices ? "On" : "Off") << "\n";
  os << indent << "OuterEnvelope: " << (this->OuterEnvelope ? "On" : "Off") << "\n";
  os << indent << "AutomaticResolution: " << (this->AutomaticResolution ? "On" : "Off") << "\n";
  os << indent << "MaximumAutomaticResolution: " << this->MaximumAutomaticResolution << "\n";
  os << indent << "LastResolution: " << this->LastResolution << "\n";
  os << indent << "GeneratePrimitives: " << (this->GeneratePrimitives ? "On" : "Off") << "\n";
  os << indent << "ComputeGradientMagnitude: " << (this->ComputeGradientMagnitude ? "On" : "Off")
     << "\n";
}
