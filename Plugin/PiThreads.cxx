// SPDX-License-Identifier: BSD-3-Clause
// The SMP backend of a ParaView process that loads the plugin. A VTK built with the
// Sequential backend as its default (Debian's) runs every vtkSMPTools loop on one
// thread; loading the plugin then selects STDThread, so that meshing, ray casting and
// the exact view use the machine's cores. A backend chosen by the user
// (VTK_SMP_BACKEND_IN_USE) or by the build (anything but Sequential) is kept; the
// number of threads stays VTK's (VTK_SMP_MAX_THREADS, ParaView's settings).
#include "vtkSMPTools.h"

#include <cstdlib>
#include <cstring>

namespace
{
struct ThreadedBackend
{
  ThreadedBackend()
  {
    const char* backend = vtkSMPTools::GetBackend();
    if (!std::getenv("VTK_SMP_BACKEND_IN_USE") && backend &&
      std::strcmp(backend, "Sequential") == 0)
    {
      vtkSMPTools::SetBackend("STDThread");
    }
  }
};
const ThreadedBackend threadedBackend;
}
