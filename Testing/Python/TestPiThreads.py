"""pvpython loading the plugin (`TestPiThreads.py PLUGIN_FILE`, without PV_PLUGIN_PATH):
the process's SMP backend. A process on VTK's Sequential default (Debian's build: one
thread for every vtkSMPTools loop) runs STDThread once the plugin is loaded, on more
than one thread where the machine has more than one core; a backend the user chose
with VTK_SMP_BACKEND_IN_USE, or that the build made the default, is kept.
"""
import os
import sys

from paraview.simple import LoadPlugin
from vtkmodules.vtkCommonCore import vtkSMPTools

from pitesting import check, finish

chosen = os.environ.get("VTK_SMP_BACKEND_IN_USE")
before = vtkSMPTools.GetBackend()
LoadPlugin(sys.argv[1], ns=globals())
check("PiSurface" in globals(), "the plugin is loaded")
after = vtkSMPTools.GetBackend()
threads = vtkSMPTools.GetEstimatedNumberOfThreads()
print("VTK_SMP_BACKEND_IN_USE=%s: backend %s before the plugin, %s after, %d threads"
      % (chosen, before, after, threads))
if chosen or before != "Sequential":
    check(after == before, "the backend %s is kept (now %s)" % (before, after))
else:
    check(after == "STDThread", "STDThread after the plugin, not %s" % after)
    if (os.cpu_count() or 1) > 1:
        check(threads > 1, "STDThread runs on %d thread(s)" % threads)
finish()
