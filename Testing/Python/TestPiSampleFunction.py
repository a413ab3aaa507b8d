"""Pi Sample Function (vtkPiSampleFunction): F on a regular grid, a row at a time.
Its values are F (as vtkSampleFunction over the same vtkPiSurface computes them, up to
rounding), contouring them with vtkFlyingEdges3D gives the same triangles as contouring
vtkSampleFunction's grid, a sub-extent holds the same values as the whole grid, bad
settings are errors, and the ParaView proxy samples the model its input carries."""
import os

import numpy as np
from pitesting import check, finish

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from pisurfaces import vtkPiSampleFunction, vtkPiSurface
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkCommonCore import vtkCommand
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D
from vtkmodules.vtkImagingHybrid import vtkSampleFunction

models = os.environ["PISURF_MODELS_DIR"]


def values(image):
    return vtk_to_numpy(image.GetPointData().GetScalars())


def errors_of(algorithm):
    messages = []
    algorithm.AddObserver(vtkCommand.ErrorEvent, lambda caller, event: messages.append(event))
    return messages


for name in ("cup_a1.0", "table", "formic_acid"):
    surface = vtkPiSurface()
    check(surface.LoadModel(os.path.join(models, name + ".pisurf")), name + " loads")
    sampler = vtkPiSampleFunction()
    sampler.SetPiSurface(surface)
    sampler.SetSampleDimensions(41, 33, 29)
    sampler.Update()
    image = sampler.GetOutput()
    check(image.GetDimensions() == (41, 33, 29), "%s: dimensions %s" % (name, image.GetDimensions()))
    F = values(image)
    check(image.GetPointData().GetScalars().GetName() == "F", name + ": scalars named F")

    reference = vtkSampleFunction()
    reference.SetImplicitFunction(surface)
    reference.SetSampleDimensions(41, 33, 29)
    reference.SetModelBounds(image.GetBounds())
    reference.SetOutputScalarTypeToDouble()
    reference.ComputeNormalsOff()
    reference.Update()
    G = values(reference.GetOutput())
    scale = np.abs(G) + 1e-9 * np.max(np.abs(G))
    worst = float(np.max(np.abs(F - G) / scale))
    check(worst < 1e-8, "%s: F agrees with vtkSampleFunction (worst relative %.1e)" % (name, worst))

    # The zero contour: the same triangles as contouring vtkSampleFunction's grid.
    contours = []
    for source in (sampler, reference):
        fe = vtkFlyingEdges3D()
        fe.SetInputConnection(source.GetOutputPort())
        fe.SetValue(0, 0.0)
        fe.Update()
        contours.append(fe.GetOutput().GetNumberOfCells())
    check(contours[0] > 100 and contours[0] == contours[1],
          "%s: %d contour triangles, %d from vtkSampleFunction" % (name, contours[0], contours[1]))

    # A sub-extent (asked of a fresh sampler: one that holds the whole grid already
    # need not execute again) holds the whole grid's values there.
    piece = vtkPiSampleFunction()
    piece.SetPiSurface(surface)
    piece.SetSampleDimensions(41, 33, 29)
    piece.UpdateExtent((5, 30, 2, 20, 7, 11))
    part = piece.GetOutput()
    check(part.GetExtent() == (5, 30, 2, 20, 7, 11), "%s: sub-extent %s" % (name, part.GetExtent()))
    whole = F.reshape(29, 33, 41)[7:12, 2:21, 5:31].ravel()
    check(np.array_equal(values(part), whole), name + ": the sub-extent has the whole grid's bits")

# Overflow-safe: 2000 spheres far apart multiply far beyond 1e308; F keeps its sign.
crowd = vtkPiSurface()
for i in range(2000):
    from pisurfaces import vtkPiPrimitive
    p = vtkPiPrimitive()
    p.SetCenter(i % 20, (i // 20) % 10, i // 200)
    p.SetRadius(0.45)
    crowd.AddFactor(p)
crowd.SetBlending(1.0)
big = vtkPiSampleFunction()
big.SetPiSurface(crowd)
# Points on the centres (inside one sphere: F < 0) and half-way between them (outside
# every sphere: F > 0).
big.SetSampleDimensions(39, 10, 10)
big.SetModelBounds(0, 19, 0, 9, 0, 9)
big.Update()
B = values(big.GetOutput())
check(np.all(np.isfinite(B)), "2000 factors: every value finite")
check(np.max(np.abs(B)) == 1.7976931348623157e308,
      "2000 factors: |F| beyond the double range is DBL_MAX (range %g %g)" % (B.min(), B.max()))
check(np.sum(B < 0) > 0 and np.sum(B > 0) > 0, "2000 factors: both signs")

# Bad settings: errors, no crash.
bad = vtkPiSampleFunction()
messages = errors_of(bad)
bad.Update()
check(any("No Pi-surface" in str(m) for m in messages) or len(messages) > 0, "no surface: an error")
bad.SetPiSurface(surface)
for dims, word in (((1, 10, 10), "at least 2"), ((5000, 5000, 5000), "MiB")):
    messages.clear()
    bad.SetSampleDimensions(*dims)
    bad.Update()
    check(len(messages) > 0, "SampleDimensions %s: an error" % (dims,))

# The ParaView proxy samples its input's model.
pi = PiSurface(Resolution=16)
sample = PiSampleFunction(Input=pi, SampleDimensions=[30, 20, 20])
sample.UpdatePipeline()
info = sample.GetDataInformation()
check(info.GetNumberOfPoints() == 30 * 20 * 20, "proxy: %d points" % info.GetNumberOfPoints())
r = info.GetPointDataInformation().GetArrayInformation("F").GetComponentRange(0)
check(r[0] < 0 < r[1], "proxy: F changes sign in the box %s" % (r,))

finish()
