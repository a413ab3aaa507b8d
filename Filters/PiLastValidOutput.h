// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file LastValidOutput.h
 * @brief keeps a source's last valid output through a bad setting
 *
 * ParaView's Pi Surface, Pi Product and Pi Primitive refuse an invalid value (a negative
 * radius, an odd exponent, a malformed expression, an empty product) with an error in
 * the output window and keep showing the last valid surface. Process() wraps the
 * source's REQUEST_DATA pass: an execution that fails (returns 0 or says it failed) leaves the
 * outputs of the last valid execution of the same piece request in place (empty if
 * there was none); a valid one is remembered. With `keep` off, failures leave the
 * outputs as the execution left them (empty: VTK's convention).
 */
#ifndef PiLastValidOutput_h
#define PiLastValidOutput_h

#include "vtkSmartPointer.h"

#include <functional>
#include <vector>

class vtkDataObject;
class vtkInformation;
class vtkInformationVector;

namespace pisurf
{

class LastValidOutput
{
public:
  /// The algorithm's ProcessRequest: `process` (the superclass's) for `request`, through
  /// the guard when it is REQUEST_DATA. Errors are reported by the algorithm itself
  /// (vtkErrorMacro): nothing here observes or hides them.
  int Process(vtkInformation* request, bool keep, vtkInformationVector* outputs,
    const std::function<int()>& process);

  /// Called by a REQUEST_DATA pass that refuses a setting yet returns 1 (an empty
  /// output, not a pipeline failure): the pass counts as failed.
  void Fail() { this->Failed = true; }

  /// Forgets the remembered outputs.
  void Clear();

private:
  std::vector<vtkSmartPointer<vtkDataObject>> Outputs;
  int Piece = -1, Pieces = -1;
  bool Failed = false; // set by Fail() during the current pass
};

}

#endif
