"""Behind a Pi Exact Surface display, the meshing proxies output the model, not a mesh.

Pi Surface, Pi Surface Model Reader and Pi Product (vtkPiModelMesher) mesh port 0
unless the only visible displays of port 0 are Pi Exact Surface representations
(vtkPiSIOnDemandSourceProxy's mesh demand). Checked in pvpython:

1. A Pi Product of two Pi Primitives shown as Pi Exact Surface: moving a primitive
   re-casts the picture (the image changes) while the
   product's port 0 holds the model alone (no cells, the 8 corners of the box with a
   Factor array over the model's factor indices, the field data PiModelOnly and
   PiSurfaceModel with the moved primitive).
2. The same display switched to Surface: the next render meshes again (cells), and the
   picture is the mesh's.
3. Back to Pi Exact Surface, an edit leaves the model alone again; a Clip filter on the
   product then gets the mesh (its output has cells).
4. Pi Surface shown as Pi Exact Surface in one view and as Surface in a second view:
   the mesh is computed (the Surface display needs it).
5. A hidden exact display with nothing else: the mesh is computed on update (what
   `UpdatePipeline` and a later display expect).
"""
import os

from paraview.simple import (Clip, CreateView, Delete, GetActiveViewOrCreate, Hide, PiPrimitive,
                             PiProduct, PiSurface, Render, Show)
from vtkmodules.vtkCommonCore import vtkUnsignedCharArray

import pisurfaces  # noqa: F401 (the client-side objects as vtkPiModelMesher)

from pitesting import check, finish

W, H = 320, 240


def new_view(view=None):
    view = view or GetActiveViewOrCreate("RenderView")
    view.OrientationAxesVisibility = 0
    view.ViewSize = [W, H]
    view.CameraPosition = [0, -9, 3]
    view.CameraFocalPoint = [0, 0, 0]
    view.CameraViewUp = [0, 0, 1]
    return view


def pixels(view):
    Render(view)
    window = view.GetRenderWindow()
    data = vtkUnsignedCharArray()
    window.GetRGBACharPixelData(0, 0, W - 1, H - 1, 1, data)
    return bytes(memoryview(data))


def port0(proxy):
    algorithm = proxy.GetClientSideObject()
    return algorithm, algorithm.GetOutputDataObject(0)


def model_only(proxy, what):
    algorithm, data = port0(proxy)
    fd = data.GetFieldData()
    check(algorithm.GetLastOutputModelOnly(), "%s: port 0 is not the model alone" % what)
    check(data.GetNumberOfCells() == 0 and data.GetNumberOfPoints() == 8,
          "%s: port 0 has %d cells and %d points, not the box's 8 corners"
          % (what, data.GetNumberOfCells(), data.GetNumberOfPoints()))
    check(fd.GetArray("PiModelOnly") is not None and fd.GetAbstractArray("PiSurfaceModel"),
          "%s: no PiModelOnly / PiSurfaceModel field data" % what)
    # Coloring offers Factor, over the model's factor indices, as for the mesh.
    factor = data.GetPointData().GetArray("Factor")
    factors = algorithm.GetPiSurface().GetNumberOfFactors()
    check(factor is not None and factor.GetRange() == (0.0, float(factors - 1)),
          "%s: the corners' Factor does not run over 0 .. %d (%s)"
          % (what, factors - 1, factor.GetRange() if factor else None))
    return fd.GetAbstractArray("PiSurfaceModel").GetValue(0) if fd.GetAbstractArray(
        "PiSurfaceModel") else ""


def meshed(proxy, what):
    algorithm, data = port0(proxy)
    check(not algorithm.GetLastOutputModelOnly(), "%s: port 0 is the model alone" % what)
    check(data.GetNumberOfCells() > 1000, "%s: port 0 has %d cells, not a mesh"
          % (what, data.GetNumberOfCells()))


# --- 1. Pi Product as Pi Exact Surface: an edit re-casts, no mesh ------------------------
view = new_view()
a = PiPrimitive(Type="Sphere", Center=[-0.6, 0, 0], Radius=1.0)
b = PiPrimitive(Type="Sphere", Center=[0.6, 0, 0], Radius=1.0)
product = PiProduct(Input=[a, b], Blending=0.3, Resolution=64)
display = Show(product, view)
display.SetRepresentationType("Pi Exact Surface")
view.ResetCamera()
before = pixels(view)
b.Center = [1.4, 0, 0]
after = pixels(view)
check(after != before, "moving a primitive did not change the exact picture")
text = model_only(product, "Pi Product after an edit")
check("1.4" in text, "the product's model does not hold the moved primitive: %s" % text[:200])

# --- 2. Switched to Surface: meshed again ------------------------------------------------
display.SetRepresentationType("Surface")
surface_picture = pixels(view)
meshed(product, "Pi Product shown as Surface")
check(surface_picture != after, "the Surface picture equals the exact one bit for bit")

# --- 3. Back to exact, then a Clip on the product gets the mesh --------------------------
display.SetRepresentationType("Pi Exact Surface")
b.Center = [1.2, 0, 0]
pixels(view)
model_only(product, "Pi Product back in Pi Exact Surface after an edit")
clip = Clip(Input=product)
clip.ClipType = "Plane"
clip.ClipType.Normal = [0, 1, 0]
clip.UpdatePipeline()
cells = clip.GetClientSideObject().GetOutputDataObject(0).GetNumberOfCells()
check(cells > 500, "a Clip of the product got %d cells: the mesh did not come back" % cells)
meshed(product, "Pi Product under a Clip")
Delete(clip)
del clip

# --- 4. Exact in one view, Surface in another: meshed ------------------------------------
model = ('{"pisurf": 1, "blending": 0.2, "primitives": ['
         '{"type": "torus", "major_radius": 1, "minor_radius": 0.4}]}')
source = PiSurface(Model=model, Resolution=64)
exact_display = Show(source, view)
exact_display.SetRepresentationType("Pi Exact Surface")
second = new_view(CreateView("RenderView"))
Show(source, second)
Render(view)
Render(second)
source.Blending = 0.3
Render(view)
Render(second)
meshed(source, "Pi Surface shown exact in one view and Surface in another")

# --- 5. Hidden exact display, nothing else: UpdatePipeline meshes ------------------------
Hide(source, second)
Hide(source, view)
source.Blending = 0.25
source.UpdatePipeline()
meshed(source, "Pi Surface with only a hidden display, after UpdatePipeline")

finish(exit_on_success=False)
