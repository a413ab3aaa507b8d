// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiExactSurfaceRepresentation.h"

#include "vtkAlgorithm.h"
#include "vtkDataObject.h"
#include "vtkExecutive.h"
#include "vtkFieldData.h"
#include "vtkInformation.h"
#include "vtkInformationIntegerRequestKey.h"
#include "vtkInformationVector.h"
#include "vtkMultiProcessController.h"
#include "vtkObjectFactory.h"
#include "vtkPVLODActor.h"
#include "vtkPVRenderView.h"
#include "vtkPiExactSurfaceMapper.h"
#include "vtkPiModelMesher.h"
#include "vtkPolyData.h"
#include "vtkPropCollection.h"
#include "vtkProperty.h"
#include "vtkRenderer.h"
#include "vtkSmartPointer.h"

vtkStandardNewMacro(vtkPiExactSurfaceRepresentation);

vtkPiExactSurfaceRepresentation::vtkPiExactSurfaceRepresentation()
{
  // The superclass's mappers give way to the exact ones; SetupDefaults connects them.
  this->Mapper->Delete();
  this->LODMapper->Delete();
  vtkPiExactSurfaceMapper* still = vtkPiExactSurfaceMapper::New();
  vtkPiExactSurfaceMapper* lod = vtkPiExactSurfaceMapper::New();
  for (vtkPiExactSurfaceMapper* mapper : { still, lod })
  {
    mapper->SetWarnMissingModel(false);
    mapper->SetModelData(this->ModelCarrier);
  }
  this->Mapper = still;
  this->LODMapper = lod;
  // The quad is drawn in the opaque pass whatever the Opacity: ParaView's translucent pass
  // peels depth layers with shader code the quad does not have. A translucent exact
  // surface blends over what the view drew before it (see REQUEST_RENDER).
  this->Actor->SetForceOpaque(true);
  this->SetupDefaults();
}

vtkPiExactSurfaceRepresentation::~vtkPiExactSurfaceRepresentation() = default;

vtkPiExactSurfaceMapper* vtkPiExactSurfaceRepresentation::GetExactMapper()
{
  return static_cast<vtkPiExactSurfaceMapper*>(this->Mapper);
}

int* vtkPiExactSurfaceRepresentation::GetHitRows()
{
  return this->GetExactMapper()->GetHitRows();
}

void vtkPiExactSurfaceRepresentation::SetMarkSingular(bool mark)
{
  static_cast<vtkPiExactSurfaceMapper*>(this->Mapper)->SetMarkSingular(mark);
  static_cast<vtkPiExactSurfaceMapper*>(this->LODMapper)->SetMarkSingular(mark);
}

bool vtkPiExactSurfaceRepresentation::GetMarkSingular()
{
  return this->GetExactMapper()->GetMarkSingular();
}

void vtkPiExactSurfaceRepresentation::SetInteractiveReduction(int n)
{
  static_cast<vtkPiExactSurfaceMapper*>(this->Mapper)->SetInteractiveReductionFactor(n);
  static_cast<vtkPiExactSurfaceMapper*>(this->LODMapper)->SetInteractiveReductionFactor(n);
}

int vtkPiExactSurfaceRepresentation::GetInteractiveReduction()
{
  return this->GetExactMapper()->GetInteractiveReductionFactor();
}

int vtkPiExactSurfaceRepresentation::RequestUpdateExtent(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestUpdateExtent(request, inputVector, outputVector))
  {
    return 0;
  }
  this->SetModelOnlyRequest(1);
  return 1;
}

int vtkPiExactSurfaceRepresentation::RequestData(
  vtkInformation* request, vtkInformationVector** inputVector, vtkInformationVector* outputVector)
{
  if (!this->Superclass::RequestData(request, inputVector, outputVector))
  {
    return 0;
  }
  vtkDataObject* input = inputVector[0]->GetNumberOfInformationObjects() > 0
    ? vtkDataObject::GetData(inputVector[0], 0)
    : nullptr;
  vtkFieldData* model = vtkPiExactSurfaceMapper::FindModelFieldData(input);
  if (model)
  {
    this->ModelCarrier->GetFieldData()->ShallowCopy(model);
    this->WarnedProducer = nullptr;
  }
  else
  {
    this->ModelCarrier->GetFieldData()->Initialize();
    vtkAlgorithm* producer =
      this->GetNumberOfInputConnections(0) > 0 ? this->GetInputAlgorithm(0, 0) : nullptr;
    // ParaView's pass-through vtkPVPostFilter stands between a source and its displays.
    while (producer && producer->IsA("vtkPVPostFilter") && producer->GetNumberOfInputPorts() > 0 &&
      producer->GetNumberOfInputConnections(0) > 0)
    {
      producer = producer->GetInputAlgorithm(0, 0);
    }
    if (input && producer != this->WarnedProducer)
    {
      vtkWarningMacro("Pi Exact Surface: the output of "
        << (producer ? producer->GetClassName() : "the source")
        << " has no PiSurfaceModel field data (it is not a Pi-surface); the representation "
           "draws nothing.");
      this->WarnedProducer = producer;
    }
  }
  this->ModelCarrier->Modified();
  return 1;
}

int vtkPiExactSurfaceRepresentation::ProcessViewRequest(
  vtkInformationRequestKey* request_type, vtkInformation* inInfo, vtkInformation* outInfo)
{
  if (!this->Superclass::ProcessViewRequest(request_type, inInfo, outInfo))
  {
    return 0;
  }
  if (request_type == vtkPVView::REQUEST_UPDATE())
  {
    // Every rendering process casts its rows of the view, so the view renders on all
    // of them and composites by depth.
    vtkPVRenderView::SetRequiresDistributedRendering(inInfo, this, true);
    vtkPVRenderView::SetRequiresDistributedRenderingLOD(inInfo, this, true);
  }
  else if (request_type == vtkPVView::REQUEST_RENDER())
  {
    // The view's updates are done. The producer's output information is shared by every
    // consumer of that output: the next one asks for the mesh unless it says otherwise.
    this->SetModelOnlyRequest(0);
    auto* view = vtkPVRenderView::SafeDownCast(this->GetView());
    // A translucent exact surface blends over what the renderer drew before it, so it
    // goes last among the renderer's props: after the opaque objects it may lie in front
    // of (the Primitives of a Pi Surface, a Pi Product's inputs). The collection is
    // reordered in place; vtkRenderer::RemoveActor would release the mapper's resources.
    if (view && this->Actor->GetProperty()->GetOpacity() < 1.0)
    {
      vtkPropCollection* props = view->GetRenderer()->GetViewProps();
      if (props->IsItemPresent(this->Actor) && props->GetLastProp() != this->Actor)
      {
        vtkSmartPointer<vtkPVLODActor> actor = this->Actor;
        props->RemoveItem(actor);
        props->AddItem(actor);
      }
    }
    vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
    const bool lod = this->Actor->GetEnableLOD() != 0;
    const bool distributed = view &&
      (lod ? view->GetUseDistributedRenderingForLODRender()
           : view->GetUseDistributedRenderingForRender());
    int piece = 0, pieces = 1;
    if (distributed && controller && controller->GetNumberOfProcesses() > 1)
    {
      piece = controller->GetLocalProcessId();
      pieces = controller->GetNumberOfProcesses();
    }
    for (vtkMapper* mapper : { this->Mapper, this->LODMapper })
    {
      static_cast<vtkPiExactSurfaceMapper*>(mapper)->SetPiece(piece);
      static_cast<vtkPiExactSurfaceMapper*>(mapper)->SetNumberOfPieces(pieces);
    }
  }
  return 1;
}

void vtkPiExactSurfaceRepresentation::SetModelOnlyRequest(int modelOnly)
{
  for (int i = 0; i < this->GetNumberOfInputConnections(0); ++i)
  {
    this->GetExecutive()->GetInputInformation(0, i)->Set(vtkPiModelMesher::MODEL_ONLY(), modelOnly);
  }
}

void vtkPiExactSurfaceRepresentation::SetVisibility(bool visible)
{
  if (!visible)
  {
    this->SetModelOnlyRequest(0);
  }
  this->Superclass::SetVisibility(visible);
}

void vtkPiExactSurfaceRepresentation::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
  os << indent << "MarkSingular: " << this->GetMarkSingular() << "\n";
  os << indent << "InteractiveReduction: " << this->GetInteractiveReduction() << "\n";
}
