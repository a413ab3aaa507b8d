"""The plugin's proxies from pvpython: the model reader (also via OpenDataFile) gives a
closed surface with the model attached; Clip by the Pi Surface Function cuts a wavelet."""
import os

from pitesting import check, finish

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from vtkmodules.vtkFiltersCore import vtkFeatureEdges



models = os.environ["PISURF_MODELS_DIR"]
two_spheres = os.path.join(models, "two_spheres_d0.9.pisurf")

reader = PiSurfaceModelReader(FileName=two_spheres)

# The XML defaults are the C++ defaults.
from pisurfaces import vtkPiSurfaceModelReader, vtkPiSurfaceFunction
cxx = vtkPiSurfaceModelReader()
check(reader.Resolution == cxx.GetResolution(), "Resolution default")
check(reader.OverrideBlending == int(cxx.GetOverrideBlending()), "OverrideBlending default")
check(reader.Blending == cxx.GetBlending(), "Blending default")
check(list(reader.Bounds) == list(cxx.GetBounds()), "Bounds default")
check(reader.OuterEnvelope == int(cxx.GetOuterEnvelope()), "OuterEnvelope default")
check(reader.AutomaticResolution == int(cxx.GetAutomaticResolution()), "AutomaticResolution default")
check(reader.ProjectVertices == int(cxx.GetProjectVertices()), "ProjectVertices default")
check(reader.GeneratePrimitives == int(cxx.GetGeneratePrimitives()), "GeneratePrimitives default")
check(reader.ComputeGradientMagnitude == int(cxx.GetComputeGradientMagnitude()),
      "ComputeGradientMagnitude default")
from pisurfaces import vtkPiSurfaceSource
source = PiSurface()
check(source.Model == vtkPiSurfaceSource().GetModel(), "Model default (the paper's two spheres)")
# The Primitives port is computed when shown (TestPiPrimitivesShown), or with every
# update with PrimitivesOnDemand off.
source.PrimitivesOnDemand = 0
source.UpdatePipeline()
check(source.GetDataInformation(0).GetNumberOfCells() > 1000, "Pi Surface source meshes its model")
check(source.GetDataInformation(1).GetNumberOfCells() > 1000, "Pi Surface source: primitives port")
# The translucent grey default display is the GUI's (pqPiDisplayBehavior): pvpython's
# Show() keeps ParaView's own defaults (opaque, solid white here).
display = Show(source, CreateView("RenderView"))
check(display.Opacity == 1 and display.ColorArrayName[1] == "",
      "pvpython Show() keeps ParaView's defaults: Opacity %g" % display.Opacity)
formic = PiSurface(Model=open(os.path.join(models, "formic_acid.pisurf")).read(), Resolution=64,
                   PrimitivesOnDemand=0)
formic.UpdatePipeline()
check(formic.GetDataInformation(1).DataInformation.GetArrayInformation("Factor", 0) is not None,
      "primitives carry Factor")
function = Clip(Input=Wavelet(), ClipType="Pi Surface Function").ClipType
cxx_function = vtkPiSurfaceFunction()
check(function.Model == cxx_function.GetModel() and function.FileName == cxx_function.GetFileName(),
      "Pi Surface Function defaults")
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

# Pi Ray Cast on the Pi Surface output: hits with the fixed array names; XML defaults are
# the C++ defaults.
from pisurfaces import vtkPiRayCaster
rays = PiRayCast(Input=source, Resolution=[64, 64])
rays.UpdatePipeline()
info = rays.GetDataInformation()
check(info.GetNumberOfPoints() > 500, "Pi Ray Cast hits: %d" % info.GetNumberOfPoints())
for name in ("Normals", "GradientMagnitude", "Depth", "PixelIndex", "ViewIndex", "HitIndex",
             "Singular", "Tangent", "Factor"):
    check(info.GetPointDataInformation().GetArrayInformation(name) is not None, "ray array " + name)
fresh = PiRayCast(Input=source)
cxx_rays = vtkPiRayCaster()
check(list(fresh.Resolution) == list(cxx_rays.GetResolution()), "Resolution default")
check(fresh.ViewMode == "-Z" and cxx_rays.GetViewMode() == vtkPiRayCaster.MINUS_Z, "ViewMode default")
check(list(fresh.CameraPosition) == list(cxx_rays.GetCameraPosition()), "CameraPosition default")
check(fresh.ViewAngle == cxx_rays.GetViewAngle(), "ViewAngle default")
rays.ViewMode = "Six Axis Views"
rays.UpdatePipeline()
check(rays.GetDataInformation().GetPointDataInformation().GetArrayInformation("ViewIndex").GetComponentRange(0)[1] == 5,
      "six views")

# Image Based Triangulation of the six views: a closed mesh of exact hits; its defaults
# are the C++ defaults; the source's Method gives the same kind of mesh.
from pisurfaces import vtkPiImageTriangulator, vtkPiSurfaceSource
triangulation = ImageBasedTriangulation(Input=rays)
cxx_tri = vtkPiImageTriangulator()
check(triangulation.MergeMode == "Automatic" and cxx_tri.GetMergeMode() == 0, "MergeMode default")
check(triangulation.SheetTolerance == cxx_tri.GetSheetTolerance(), "SheetTolerance default")
check(triangulation.SingularTolerance == cxx_tri.GetSingularTolerance(), "SingularTolerance default")
tri_mesh = servermanager.Fetch(triangulation)
check(tri_mesh.GetNumberOfCells() > 1000, "triangulation has triangles")
check(tri_mesh.GetFieldData().GetArray("BoundaryEdges").GetValue(0) == 0, "triangulation is closed")
check(tri_mesh.GetPointData().GetArray("Singular") is not None, "Singular on the mesh")
check(triangulation.EdgeFlipRounds == cxx_tri.GetEdgeFlipRounds() == 1, "EdgeFlipRounds default")
unflipped = ImageBasedTriangulation(Input=rays, EdgeFlipRounds=0)
unflipped_mesh = servermanager.Fetch(unflipped)
check(unflipped_mesh.GetNumberOfPoints() == tri_mesh.GetNumberOfPoints() and
      unflipped_mesh.GetNumberOfCells() == tri_mesh.GetNumberOfCells() and
      unflipped_mesh.GetFieldData().GetArray("BoundaryEdges").GetValue(0) == 0,
      "EdgeFlipRounds 0: the same vertices and triangle count, closed")
edges = lambda m: set(tuple(sorted((m.GetCell(c).GetPointId(k), m.GetCell(c).GetPointId((k + 1) % 3))))
                      for c in range(m.GetNumberOfCells()) for k in range(3))
check(edges(unflipped_mesh) != edges(tri_mesh), "EdgeFlipRounds changes the edges")
check(source.Method == "Flying Edges" and vtkPiSurfaceSource().GetMethod() == 0, "Method default")
by_rays = PiSurface(Method="Ray Cast Triangulation", Resolution=48)
by_rays_mesh = servermanager.Fetch(by_rays)
check(by_rays_mesh.GetNumberOfCells() > 1000 and
      by_rays_mesh.GetFieldData().GetArray("BoundaryEdges").GetValue(0) == 0, "Method Ray Cast Triangulation")

extract = ExtractCellsByRegion(Input=wavelet, IntersectWith="Pi Surface Function")
extract.IntersectWith.Model = model
extract.UpdatePipeline()
extracted = extract.GetDataInformation().GetNumberOfCells()
check(0 < extracted < cells, "extract cells by region: %d of %d" % (extracted, cells))

# A bad model is an error, not a crash, and the clip keeps working on the last valid model.
clip.ClipType.Model = '{"pisurf": 1, "blending": 0.25, "primitives": [{"type": "sphere", "radius": -1}]}'
clip.UpdatePipeline()
check(clip.GetDataInformation().GetNumberOfCells() == outside, "invalid model keeps the last valid one")

finish()
