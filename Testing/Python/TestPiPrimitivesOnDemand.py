"""The Primitives port (port 1) of the meshing sources: computed only when asked for
with PrimitivesOnDemand, the same meshes as when computed with the surface, and kept
when only the blending changes.

    python3 TestPiPrimitivesOnDemand.py   (PISURF_MODELS_DIR: Testing/Data/Models)
"""
import hashlib
import os

from pitesting import check, finish

from pisurfaces import vtkPiSurfaceModelReader
from vtkmodules.util.numpy_support import vtk_to_numpy

MODELS = os.environ.get("PISURF_MODELS_DIR",
                        os.path.join(os.path.dirname(__file__), "..", "Data", "Models"))


def reader(name, on_demand):
    r = vtkPiSurfaceModelReader()
    r.SetFileName(os.path.join(MODELS, name + ".pisurf"))
    r.SetResolution(64)
    r.SetPrimitivesOnDemand(on_demand)
    return r


def digest(polydata):
    if polydata.GetNumberOfPoints() == 0:
        return "empty"
    h = hashlib.sha1(vtk_to_numpy(polydata.GetPoints().GetData()).tobytes())
    h.update(vtk_to_numpy(polydata.GetPolys().GetConnectivityArray()).tobytes())
    return h.hexdigest()


def executions(algorithm):
    count = [0]
    algorithm.AddObserver("StartEvent", lambda *args: count.__setitem__(0, count[0] + 1))
    return count


for name in ("cup_a1.0", "table"):
    eager = reader(name, False)
    eager.Update()
    check(eager.GetOutput(1).GetNumberOfCells() > 0,
          "%s: without PrimitivesOnDemand, Update() meshes the primitives too" % name)

    lazy = reader(name, True)
    runs = executions(lazy)
    lazy.Update()
    check(runs[0] == 1 and lazy.GetOutput(1).GetNumberOfCells() == 0,
          "%s: with PrimitivesOnDemand, Update() leaves port 1 alone" % name)
    check(digest(lazy.GetOutput(0)) == digest(eager.GetOutput(0)),
          "%s: the same surface either way" % name)
    mesh = lazy.GetOutput(0).GetPoints().GetData()
    lazy.Update(1)
    check(runs[0] == 2, "%s: asking for port 1 executes once more" % name)
    check(lazy.GetOutput(0).GetPoints().GetData() is mesh,
          "%s: asking for port 1 does not mesh the surface again" % name)
    check(digest(lazy.GetOutput(1)) == digest(eager.GetOutput(1)),
          "%s: the primitives asked for equal those meshed with the surface" % name)
    lazy.Update(1)
    check(runs[0] == 2, "%s: an up-to-date port 1 does not execute" % name)

    # Only the blending changes: the primitives are kept, the surface is re-meshed.
    primitives = eager.GetOutput(1).GetPoints().GetData()
    surface = digest(eager.GetOutput(0))
    eager.SetOverrideBlending(True)
    eager.SetBlending(0.5)
    eager.Update()
    check(digest(eager.GetOutput(0)) != surface, "%s: a new blending, a new surface" % name)
    check(eager.GetOutput(1).GetPoints().GetData() is primitives,
          "%s: the primitives are kept when only the blending changes" % name)
    eager.SetResolution(48)
    eager.Update()
    check(eager.GetOutput(1).GetPoints().GetData() is not primitives,
          "%s: a new grid meshes the primitives again" % name)

finish()
