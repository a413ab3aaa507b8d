// SPDX-License-Identifier: BSD-3-Clause
// PieceExchange on vtkMultiProcessController's global controller.
#include "PiPieceExchange.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"

namespace pisurf
{
namespace
{
class ControllerExchange : public PieceExchange
{
public:
  explicit ControllerExchange(vtkMultiProcessController* controller)
    : Controller(controller)
  {
  }
  void Send(const unsigned char* data, vtkIdType size, int other, int tag) override
  {
    this->Controller->Send(data, size, other, tag);
  }
  void Receive(unsigned char* data, vtkIdType size, int other, int tag) override
  {
    this->Controller->Receive(data, size, other, tag);
  }
  int Maximum(int value) override
  {
    int maximum = value;
    this->Controller->AllReduce(&value, &maximum, 1, vtkCommunicator::MAX_OP);
    return maximum;
  }
  void Sum(const vtkIdType* values, vtkIdType* sums, vtkIdType count) override
  {
    this->Controller->AllReduce(values, sums, count, vtkCommunicator::SUM_OP);
  }

private:
  vtkMultiProcessController* Controller;
};
}

std::unique_ptr<PieceExchange> PieceExchange::ForPiece(int piece, int pieces)
{
  vtkMultiProcessController* controller = vtkMultiProcessController::GetGlobalController();
  if (!controller || controller->GetNumberOfProcesses() != pieces ||
    controller->GetLocalProcessId() != piece)
  {
    return nullptr;
  }
  return std::unique_ptr<PieceExchange>(new ControllerExchange(controller));
}
}
