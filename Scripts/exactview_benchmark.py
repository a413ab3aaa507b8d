"""Frame times of the exact view (vtkPiExactSurfaceMapper) at 1280 x 800.

Usage: pvpython Scripts/exactview_benchmark.py MODELS_DIR [FRAMES]

Each frame turns the camera by 1 degree (so every frame casts again) and times
vtkRenderWindow::Render: the cast, the shading and the drawing. Full resolution
(ReductionFactor 1, a still render) and one ray per 2 x 2 and 4 x 4 pixels (the
interactive renders). The cup model, the cube with its dent and ubiquitin (1ubq, 602
atoms without waters... as freesasa's test file has them, Molecular Pi Surface in Local
mode); vtkSMPTools' threads.
The best and the median of FRAMES frames (default 10).

Then the same in a ParaView render view of 1280 x 800 with the plugin's defaults (what a
user of the GUI or pvpython gets): the cup as Pi Exact Surface in still renders and in
interactive ones (InteractiveReduction 2, the default, and 4), beside a Cone source
shown as Surface in interactive renders: ParaView's own cost of a frame with anything in
it on this machine's OpenGL, the floor under every interactive frame."""
import os
import statistics
import sys
import time

from pisurfaces import (vtkPiExactSurfaceMapper, vtkPiMoleculeReader, vtkPiMoleculeSurface,
                        vtkPiSurfaceModelReader)
from vtkmodules.vtkCommonCore import vtkSMPTools
from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401

models = sys.argv[1]
frames = int(sys.argv[2]) if len(sys.argv) > 2 else 10
vtkSMPTools.SetBackend("STDThread")


def source_of(name):
    """The model reader of a .pisurf file (meshed coarsely: the mapper casts its model),
    or for "1ubq" the molecule in Local mode (the mapper casts the molecule's field)."""
    if name == "1ubq":
        reader = vtkPiMoleculeReader()
        reader.SetFileName("/usr/share/freesasa/test-data/1ubq.pdb")
        surface = vtkPiMoleculeSurface()
        surface.SetInputConnection(reader.GetOutputPort())
        surface.SetMode(vtkPiMoleculeSurface.LOCAL)
        surface.SetSpacing(2.0)
        surface.Update()
        return surface
    reader = vtkPiSurfaceModelReader()
    reader.SetFileName(os.path.join(models, name))
    reader.SetResolution(8)
    reader.Update()
    return reader


def measure(name, reduction):
    source = source_of(name)
    mapper = vtkPiExactSurfaceMapper()
    mapper.SetInputConnection(source.GetOutputPort())
    mapper.SetReductionFactor(reduction)
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(1280, 800)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    renderer.GetActiveCamera().Elevation(25)
    window.Render()
    times = []
    for _ in range(frames):
        renderer.GetActiveCamera().Azimuth(1.0)
        renderer.ResetCameraClippingRange()
        t0 = time.perf_counter()
        window.Render()
        times.append(time.perf_counter() - t0)
    return min(times), statistics.median(times), mapper.GetCastResolution()


print("Exact view frame time at 1280 x 800 (%s, %d threads), %d frames"
      % (vtkSMPTools.GetBackend(), vtkSMPTools.GetEstimatedNumberOfThreads(), frames))
print("| model | rays per pixel | cast | best | median |")
print("|---|---|---|---|---|")
for model in ("cup_a1.0.pisurf", "rounded_cube_sphere_2.pisurf", "1ubq"):
    for reduction in ((1, 2, 4) if model != "1ubq" else (1, 2)):
        best, median, cast = measure(model, reduction)
        print("| %s | 1/%d | %d x %d | %.1f ms | %.1f ms |" % (
            model, reduction * reduction, cast[0], cast[1], 1e3 * best, 1e3 * median))
        sys.stdout.flush()


def paraview_frames(view, render):
    """Best and median of `render()` over FRAMES frames, the camera moving each time."""
    times = []
    for k in range(frames):
        view.CameraPosition = [6 + 0.05 * k, -8, 4]
        t0 = time.perf_counter()
        render()
        times.append(time.perf_counter() - t0)
    return min(times), statistics.median(times)


from paraview import simple  # noqa: E402

view = simple.CreateRenderView()
view.ViewSize = [1280, 800]
view.OrientationAxesVisibility = 0
cone = simple.Cone()
cone_display = simple.Show(cone, view)
view.CameraFocalPoint = [0.7, 0, -1.2]
view.CameraViewUp = [0, 0, 1]
simple.Render(view)
rows = [("Cone source, Surface", "interactive", paraview_frames(view, view.InteractiveRender))]
cone_display.Visibility = 0
cup = simple.PiSurfaceModelReader(FileName=os.path.join(models, "cup_a1.0.pisurf"))
cup_display = simple.Show(cup, view)
cup_display.SetRepresentationType("Pi Exact Surface")
view.ResetCamera(False)
simple.Render(view)
rows.append(("cup, Pi Exact Surface", "still", paraview_frames(view, view.StillRender)))
for reduction in (2, 4):
    cup_display.InteractiveReduction = reduction
    rows.append(("cup, Pi Exact Surface", "interactive, InteractiveReduction %d" % reduction,
                 paraview_frames(view, view.InteractiveRender)))
print()
print("ParaView render view, 1280 x 800 (%s, %d threads), %d frames"
      % (vtkSMPTools.GetBackend(), vtkSMPTools.GetEstimatedNumberOfThreads(), frames))
print("| display | render | best | median |")
print("|---|---|---|---|")
for display, render, (best, median) in rows:
    print("| %s | %s | %.1f ms | %.1f ms |" % (display, render, 1e3 * best, 1e3 * median))
sys.stdout.flush()
# The render view goes before the interpreter's exit tears its X window down.
simple.Delete(view)
del view
os._exit(0)
