// SPDX-License-Identifier: BSD-3-Clause
#include "PiPrimitiveMeshes.h"

#include "vtkAppendPolyData.h"
#include "vtkCallbackCommand.h"
#include "vtkCommand.h"
#include "vtkDataArray.h"
#include "vtkDataObject.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkNew.h"
#include "vtkPiFlyingEdges.h"
#include "vtkPiSurface.h"
#include "vtkPointData.h"
#include "vtkPolyData.h"
#include "vtkStreamingDemandDrivenPipeline.h"

namespace pisurf
{

void MeshPrimitives(vtkPiSurface* surface, const double bounds[6], const int dims[3], int piece,
  int pieces, bool projectVertices, vtkAlgorithm* owner, vtkPolyData* out)
{
  vtkNew<vtkAppendPolyData> append;
  const int n = surface->GetNumberOfFactors();
  for (int i = 0; i < n && !owner->CheckAbort(); ++i)
  {
    vtkNew<vtkPiSurface> alone;
    alone->AddFactor(surface->GetFactor(i));
    vtkNew<vtkPiFlyingEdges> mesher;
    // A primitive may have no real points (the paper's concavity uses the "sphere"
    // −x²−y²−z²−0.01): its empty mesh is expected, not worth a warning.
    vtkNew<vtkCallbackCommand> quiet;
    mesher->AddObserver(vtkCommand::WarningEvent, quiet);
    mesher->SetPiSurface(alone);
    mesher->SetBounds(bounds);
    mesher->SetSampleDimensions(dims[0], dims[1], dims[2]);
    mesher->SetOuterEnvelope(false);
    mesher->SetGeneratePrimitives(false);
    mesher->SetProjectVertices(projectVertices);
    mesher->UpdatePiece(piece, pieces, 0);
    vtkNew<vtkPolyData> mesh;
    mesh->ShallowCopy(mesher->GetOutput());
    mesh->GetFieldData()->Initialize();
    vtkDataArray* factor = mesh->GetPointData()->GetArray("Factor");
    if (factor)
    {
      factor->Fill(i);
    }
    append->AddInputData(mesh);
  }
  if (n > 0)
  {
    append->Update();
    out->ShallowCopy(append->GetOutput());
  }
}

PortsNotGenerated MarkPortsNotGenerated(vtkAlgorithm* algorithm, vtkInformation* request,
  vtkInformationVector* outputs, bool primitivesOnDemand, bool haveMesh, const Piece& meshPiece)
{
  PortsNotGenerated marks;
  if (outputs->GetNumberOfInformationObjects() < 2 ||
    !request->Has(vtkExecutive::FROM_OUTPUT_PORT()))
  {
    return marks;
  }
  const int from = request->Get(vtkExecutive::FROM_OUTPUT_PORT());
  vtkInformation* meshInfo = outputs->GetInformationObject(0);
  vtkInformation* primitivesInfo = outputs->GetInformationObject(1);
  if (from == 0 && primitivesOnDemand)
  {
    // Port 1 only when it is asked for: it keeps its data, which the executive then
    // knows to be out of date.
    marks.Primitives = true;
  }
  else if (from == 1)
  {
    // Asked for the primitives alone: the mesh is left as it is when it is up to date
    // for the same piece (its grid is then the one the primitives take).
    auto* executive = vtkStreamingDemandDrivenPipeline::SafeDownCast(algorithm->GetExecutive());
    vtkDataObject* mesh = meshInfo->Get(vtkDataObject::DATA_OBJECT());
    const Piece asked = PieceOf(primitivesInfo);
    marks.Mesh = executive && mesh && haveMesh &&
      mesh->GetUpdateTime() > executive->GetPipelineMTime() && meshPiece.Piece == asked.Piece &&
      meshPiece.Pieces == asked.Pieces;
  }
  if (marks.Mesh)
  {
    meshInfo->Set(vtkDemandDrivenPipeline::DATA_NOT_GENERATED(), 1);
  }
  if (marks.Primitives)
  {
    primitivesInfo->Set(vtkDemandDrivenPipeline::DATA_NOT_GENERATED(), 1);
  }
  return marks;
}

}
