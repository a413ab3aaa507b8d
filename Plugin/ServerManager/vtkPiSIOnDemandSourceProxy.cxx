// SPDX-License-Identifier: BSD-3-Clause
#include "vtkPiSIOnDemandSourceProxy.h"

#include "vtkAlgorithm.h"
#include "vtkAlgorithmOutput.h"
#include "vtkExecutive.h"
#include "vtkInformation.h"
#include "vtkInformationExecutivePortVectorKey.h"
#include "vtkObjectFactory.h"
#include "vtkPVDataRepresentation.h"

vtkStandardNewMacro(vtkPiSIOnDemandSourceProxy);

vtkPiSIOnDemandSourceProxy::vtkPiSIOnDemandSourceProxy() = default;

vtkPiSIOnDemandSourceProxy::~vtkPiSIOnDemandSourceProxy() = default;

bool vtkPiSIOnDemandSourceProxy::IsPortWanted(int port)
{
  // The proxy's port is the output of ParaView's post filter on the algorithm's port:
  // the representations and filters are connected to that.
  vtkAlgorithmOutput* output = this->GetOutputPort(port);
  vtkAlgorithm* producer = output ? output->GetProducer() : nullptr;
  if (!producer)
  {
    return false;
  }
  vtkInformation* info = producer->GetExecutive()->GetOutputInformation(output->GetIndex());
  const int count = vtkExecutive::CONSUMERS()->Length(info);
  vtkExecutive** consumers = vtkExecutive::CONSUMERS()->GetExecutives(info);
  for (int i = 0; i < count; ++i)
  {
    vtkAlgorithm* consumer = consumers[i] ? consumers[i]->GetAlgorithm() : nullptr;
    if (!consumer || consumer->IsA("vtkPVExtractSelection"))
    {
      continue; // selections are extracted when there is one, from the data at hand
    }
    auto* representation = vtkPVDataRepresentation::SafeDownCast(consumer);
    if (!representation || representation->GetVisibility())
    {
      return true;
    }
  }
  return false;
}

void vtkPiSIOnDemandSourceProxy::UpdatePipeline(int port, double time, bool doTime)
{
  if (port == 0 || this->IsPortWanted(port))
  {
    this->Superclass::UpdatePipeline(port, time, doTime);
  }
}

void vtkPiSIOnDemandSourceProxy::PrintSelf(ostream& os, vtkIndent indent)
{
  this->Superclass::PrintSelf(os, indent);
}
