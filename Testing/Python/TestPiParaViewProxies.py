"""The plugin's proxies from pvpython: the model reader (also via OpenDataFile) gives a
closed surface with the model attached; Clip by the Pi Surface Function cuts a wavelet."""
import os
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from vtkmodules.vtkFiltersCore import vtkFeatureEdges

failures = 0


def check(cond, what):
    global failures
    if not cond:
        failures += 1
        print("FAILED:", what)


models = os.environ["PISURF_MODELS_DIR"]
two_spheres = os.path.join(models, "two_spheres_d0.9.pisurf")

reader = PiSurfaceModelReader(FileName=two_spheres)
check(reader.Resolution[0] if hasattr(reader.Resolution, "__getitem__") else reader.Resolution == 128,
      "default resolution")
reader.Resolution = 64
mesh = servermanager.Fetch(reader)
check(mesh.GetNumberOfCells() > 1000, "reader output has %d cells" % mesh.GetNumberOfCells())
edges = vtkFeatureEdges()
edges.SetInputData(mesh)
edges.BoundaryEdgesOn()
edges.NonManifoldEdgesOn()
edges.FeatureEdgesOff()
edges.ManifoldEdgesOff()
edges.Update()
check(edges.GetOutput().GetNumberOfCells() == 0, "closed surface")
check(mesh.GetFieldData().GetAbstractArray("PiSurfaceModel") is not None, "PiSurfaceModel field")
check(mesh.GetPointData().GetArray("Factor") is not None, "Factor array")

# OverrideBlending inflates: more area, larger bounds.
reader.OverrideBlending = 1
reader.Blending = 2.0
inflated = servermanager.Fetch(reader)
check(inflated.GetBounds()[1] > mesh.GetBounds()[1] + 0.1, "r = 2 inflates the surface")

# OpenDataFile picks our reader for .pisurf.
opened = OpenDataFile(two_spheres)
check(opened is not None and opened.GetXMLName() == "PiSurfaceModelReader",
      "OpenDataFile chooses the Pi Surface Model Reader")

# Clip a wavelet by the Pi-surface function (model as text, then as a file).
wavelet = Wavelet(WholeExtent=[-10, 10, -10, 10, -10, 10])
wavelet.UpdatePipeline()
cells = wavelet.GetDataInformation().GetNumberOfCells()
model = ('{"pisurf": 1, "blending": 0.25, "primitives": ['
         '{"type": "sphere", "center": [4, 0, 0], "radius": 5},'
         '{"type": "sphere", "center": [-4, 0, 0], "radius": 5}]}')
clip = Clip(Input=wavelet, ClipType="Pi Surface Function")
clip.ClipType.Model = model
clip.Invert = 1
clip.UpdatePipeline()
inside = clip.GetDataInformation().GetNumberOfCells()
check(0 < inside and inside != cells, "clip by model text: %d of %d cells" % (inside, cells))
clip.Invert = 0
clip.UpdatePipeline()
outside = clip.GetDataInformation().GetNumberOfCells()
check(outside > 0 and outside != inside and outside != cells, "inverted clip: %d cells" % outside)

clip2 = Clip(Input=wavelet, ClipType="Pi Surface Function")
clip2.ClipType.FileName = os.path.join(models, "two_spheres_d0.9.pisurf")
clip2.Scalars = ["POINTS", "RTData"]
clip2.UpdatePipeline()
check(clip2.GetDataInformation().GetNumberOfCells() not in (0, cells), "clip by model file")

slice_ = Slice(Input=wavelet, SliceType="Pi Surface Function")
slice_.SliceType.Model = model
slice_.UpdatePipeline()
check(slice_.GetDataInformation().GetNumberOfCells() > 0, "slice by the Pi-surface")

print("%d failures" % failures)
sys.exit(1 if failures else 0)
