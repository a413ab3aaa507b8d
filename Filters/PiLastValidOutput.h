// SPDX-License-Identifier: BSD-3-Clause
/**
 * @file PiLastValidOutput.h
 * @brief keeps a source's last valid output through a bad setting
 *
 * ParaView's Pi Surface, Pi Product and Pi Primitive refuse an invalid value (a negative
 * radius, an odd exponent, a malformed expression, an empty product) with an error in
 * the output window and keep showing the last valid surface. Run() wraps the source's
 * REQUEST_DATA pass: an execution that fails (returns 0 or says it failed) leaves the
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
class vtkInformationVector;

class PiLastValidOutput
{
public:
  /// Runs `execute` (the algorithm's REQUEST_DATA pass, which sets `failed` when it
  /// refused a setting but returned 1) with `outputs`. Errors are reported by the
  /// algorithm itself (vtkErrorMacro): nothing here observes or hides them.
  int Run(bool keep, vtkInformationVector* outputs,
    const std::function<int(bool& failed)>& execute);

  /// Forgets the remembered outputs.
  void Clear();

private:
  std::vector<vtkSmartPointer<vtkDataObject>> Outputs;
  int Piece = -1, Pieces = -1;
};

#endif
