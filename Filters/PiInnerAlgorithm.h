// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiInnerAlgorithm.h
 * @brief an algorithm run inside another's RequestData, as part of its work
 *
 * The outer algorithm is what ParaView sees: its progress bar and its cancel button. An
 * inner algorithm doing (part of) the outer one's work reports its progress as the
 * outer one's, mapped onto [start, start + span], and checks the outer one's cancel
 * (vtkAlgorithm::SetContainerAlgorithm).
 */
#ifndef PiInnerAlgorithm_h
#define PiInnerAlgorithm_h

#include "vtkAlgorithm.h"
#include "vtkCommand.h"
#include "vtkNew.h"

namespace pisurf
{

class ForwardProgress : public vtkCommand
{
public:
  static ForwardProgress* New() { return new ForwardProgress; }
  void Execute(vtkObject*, unsigned long, void* data) override
  {
    this->Outer->UpdateProgress(this->Start + this->Span * *static_cast<double*>(data));
  }
  vtkAlgorithm* Outer = nullptr;
  double Start = 0.0, Span = 1.0;
};

/// `inner` works for `outer`: its progress p is reported as outer's start + span·p and it
/// stops when outer is cancelled. (The observer lives as long as `inner`.)
inline void WorkFor(vtkAlgorithm* inner, vtkAlgorithm* outer, double start, double span)
{
  vtkNew<ForwardProgress> forward;
  forward->Outer = outer;
  forward->Start = start;
  forward->Span = span;
  inner->AddObserver(vtkCommand::ProgressEvent, forward);
  inner->SetContainerAlgorithm(outer);
}

}

#endif
