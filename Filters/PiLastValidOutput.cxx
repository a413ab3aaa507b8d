// SPDX-License-Identifier: BSD-3-Clause
#include "PiLastValidOutput.h"
#include "PiPieces.h"

#include "vtkDataObject.h"
#include "vtkDemandDrivenPipeline.h"
#include "vtkInformation.h"
#include "vtkInformationVector.h"
#include "vtkStreamingDemandDrivenPipeline.h"

namespace pisurf
{

int LastValidOutput::Process(vtkInformation* request, bool keep, vtkInformationVector* outputs,
  const std::function<int()>& process)
{
  if (!request->Has(vtkDemandDrivenPipeline::REQUEST_DATA()))
  {
    return process();
  }
  this->Failed = false;
  const int result = process();
  if (!keep)
  {
    this->Clear();
    return result;
  }
  const bool failed = this->Failed || result == 0;

  const pisurf::Piece asked = PieceOf(outputs->GetInformationObject(0));
  const int piece = asked.Piece, pieces = asked.Pieces;
  const int n = outputs->GetNumberOfInformationObjects();
  if (!failed)
  {
    this->Outputs.assign(n, nullptr);
    for (int port = 0; port < n; ++port)
    {
      vtkDataObject* output = vtkDataObject::GetData(outputs, port);
      if (output)
      {
        this->Outputs[port] = vtkSmartPointer<vtkDataObject>::Take(output->NewInstance());
        this->Outputs[port]->ShallowCopy(output);
      }
    }
    this->Piece = piece;
    this->Pieces = pieces;
    return result;
  }
  // The error is reported; the outputs are the last valid ones (or empty).
  const bool same =
    piece == this->Piece && pieces == this->Pieces && static_cast<int>(this->Outputs.size()) == n;
  for (int port = 0; port < n; ++port)
  {
    vtkDataObject* output = vtkDataObject::GetData(outputs, port);
    if (!output)
    {
      continue;
    }
    if (same && this->Outputs[port])
    {
      output->ShallowCopy(this->Outputs[port]);
    }
    else
    {
      output->Initialize();
    }
  }
  return 1;
}

void LastValidOutput::Clear()
{
  this->Outputs.clear();
  this->Piece = this->Pieces = -1;
}
}
