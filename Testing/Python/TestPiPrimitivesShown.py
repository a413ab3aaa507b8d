"""The Primitives port (port 1) of Pi Surface, the model reader and Pi Product in
ParaView: computed when shown (or used by a filter), not when only the Pi-surface is
shown or updated; the same primitives as the VTK algorithm computes; a hidden port
left alone while the surface is re-meshed, and brought up to date when shown again.

    pvpython TestPiPrimitivesShown.py   (PISURF_MODELS_DIR: Testing/Data/Models)
"""
import os

from pitesting import check, finish

from paraview.simple import (Clip, CreateRenderView, Hide, OutputPort, PiProduct,
                             PiPrimitive, PiSurface, PiSurfaceModelReader, Render, Show,
                             UpdatePipeline)
from pisurfaces import vtkPiSurfaceModelReader

MODELS = os.environ.get("PISURF_MODELS_DIR",
                        os.path.join(os.path.dirname(__file__), "..", "Data", "Models"))
CUP = os.path.join(MODELS, "cup_a1.0.pisurf")


def cells(proxy, port):
    return proxy.GetClientSideObject().GetOutputDataObject(port).GetNumberOfCells()


def executions(proxy):
    count = [0]
    algorithm = proxy.GetClientSideObject()
    tag = algorithm.AddObserver("StartEvent", lambda *args: count.__setitem__(0, count[0] + 1))
    return count, lambda: algorithm.RemoveObserver(tag)


view = CreateRenderView()
reader = PiSurfaceModelReader(FileName=CUP)
reader.Resolution = 64
runs, stop_counting = executions(reader)
Show(reader, view)
Render(view)
check(cells(reader, 0) > 0, "Show(reader): the Pi-surface is meshed")
check(cells(reader, 1) == 0, "Show(reader): the Primitives port is not meshed")
UpdatePipeline(proxy=reader)
check(cells(reader, 1) == 0, "UpdatePipeline(reader): the Primitives port is not meshed")

# The VTK algorithm with both ports computed gives the reference primitives.
eager = vtkPiSurfaceModelReader()
eager.SetFileName(CUP)
eager.SetResolution(64)
eager.Update()

before = runs[0]
Show(OutputPort(reader, 1), view)
Render(view)
check(cells(reader, 1) == eager.GetOutput(1).GetNumberOfCells(),
      "shown, the Primitives port holds every primitive (%d cells, %d expected)"
      % (cells(reader, 1), eager.GetOutput(1).GetNumberOfCells()))
check(runs[0] == before + 1, "showing the Primitives port executes once, not the surface "
      "again (%d executions)" % (runs[0] - before))

stop_counting()  # (a Python observer left on a ParaView object crashes pvpython's exit)

# Hidden, the port keeps its last primitives while the Pi-surface is re-meshed.
Hide(OutputPort(reader, 1), view)
old = cells(reader, 1)
reader.Resolution = 40
Render(view)
check(cells(reader, 1) == old, "hidden, the Primitives port is left as it was")
eager.SetResolution(40)
eager.Update()
Show(OutputPort(reader, 1), view)
Render(view)
check(cells(reader, 1) == eager.GetOutput(1).GetNumberOfCells(),
      "shown again, the Primitives port is meshed on the new grid")

# A filter on the Primitives port gets them, the port itself hidden.
Hide(OutputPort(reader, 1), view)
reader.Resolution = 48
clip = Clip(Input=OutputPort(reader, 1))
UpdatePipeline(proxy=clip)
check(clip.GetDataInformation().GetNumberOfCells() > 0, "a filter on the port gets primitives")

# Pi Surface and Pi Product behave alike.
others = (("Pi Surface", PiSurface(Resolution=48)),
          ("Pi Product", PiProduct(Input=[PiPrimitive(), PiPrimitive(Center=[1.5, 0, 0])],
                                   GeneratePrimitives=1, Resolution=48)))
for label, source in others:
    Show(source, view)
    Render(view)
    check(cells(source, 0) > 0 and cells(source, 1) == 0,
          "Show(%s): only the Pi-surface is meshed" % label)
    Show(OutputPort(source, 1), view)
    Render(view)
    check(cells(source, 1) > 0, "%s: the shown Primitives port is meshed" % label)

# pvpython crashes in sys.exit() after a render (its render view's OpenGL context is
# released after the X connection): on success the script just ends.
finish(exit_on_success=False)
