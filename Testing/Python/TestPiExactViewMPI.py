"""Run with `mpiexec -n 2 pvbatch TestPiExactViewMPI.py`: the Pi Exact Surface
representation in ParaView's MPI mode. Each rank casts its share of the view's pixel
rows and ParaView composites the ranks' images by depth: rank 0's hits (the
representation's HitRows) lie in its half of the rows, and the screenshot must equal the
serial picture (Testing/Baselines/ExactView.cup.png, rendered by TestPiExactView with
the same model, camera and size) and the baseline check must fail if a rank's rows were
missing (the image compared is also checked to cover both halves of the cup)."""
import os

from pitesting import check

from paraview import servermanager
from paraview.simple import (GetActiveViewOrCreate, PiSurfaceModelReader, Render,
                             SaveScreenshot, Show)
from vtkmodules.vtkIOImage import vtkPNGReader
from vtkmodules.vtkTestingRendering import vtkTesting

ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
check(ranks == 2, "running on 2 ranks (got %d)" % ranks)

models = os.environ["PISURF_MODELS_DIR"]
temp = os.environ["PISURF_TEMP_DIR"]
baseline = os.path.join(os.environ["PISURF_BASELINES_DIR"], "ExactView.cup.png")
W, H = 400, 300

view = GetActiveViewOrCreate("RenderView")
view.OrientationAxesVisibility = 0
view.Background = [0.32, 0.34, 0.43]
view.ViewSize = [W, H]
cup = PiSurfaceModelReader(FileName=os.path.join(models, "cup_a1.0.pisurf"), Resolution=32)
display = Show(cup, view)
display.SetRepresentationType("Pi Exact Surface")
display.ColorArrayName = ["POINTS", ""]
display.DiffuseColor = [0.85, 0.75, 0.55]
display.Specular = 0.3
# The camera of TestPiExactView's cup picture.
view.CameraPosition = [6, -8, 4]
view.CameraFocalPoint = [0.7, 0, -1.2]
view.CameraViewUp = [0, 0, 1]
view.CameraParallelProjection = 0
view.CameraViewAngle = 30
view.ResetCamera(False)
Render(view)
image = os.path.join(temp, "ExactViewMPI.cup.png")
SaveScreenshot(image, view, ImageResolution=[W, H])

reader = vtkPNGReader()
reader.SetFileName(image)
reader.Update()
scalars = reader.GetOutput().GetPointData().GetScalars()
background = scalars.GetTuple(0)
rows_drawn = set()
for j in range(H):
    for i in range(W):
        if scalars.GetTuple(j * W + i)[:3] != background[:3]:
            rows_drawn.add(j)
print("rows with the surface: %d (lowest %d, highest %d)"
      % (len(rows_drawn), min(rows_drawn), max(rows_drawn)))
check(min(rows_drawn) < H // 2 < max(rows_drawn), "the surface spans both ranks' rows")
# This script runs on rank 0, whose share is the rows [0, H/2): its hits lie there, so
# the picture's rows above come from rank 1's cast.
display.SMProxy.UpdatePropertyInformation()
hit_rows = display.SMProxy.GetProperty("HitRows")
first, last = hit_rows.GetElement(0), hit_rows.GetElement(1)
print("rank 0 hit rows %d to %d" % (first, last))
check(0 <= first <= last < H // 2, "rank 0 cast only its rows [0, %d)" % (H // 2))
check(first == min(rows_drawn), "rank 0's lowest hit row is the picture's lowest")
check(max(rows_drawn) > last, "the picture has rows rank 0 did not cast")
testing = vtkTesting()
for argument in ("-V", baseline, "-T", temp):
    testing.AddArgument(argument)
check(testing.RegressionTest(image, 0.05) == vtkTesting.PASSED,
      "%s differs from the serial picture %s" % (image, baseline))

import pitesting  # noqa: E402

# The view goes first, while its OpenGL context is still valid (at the interpreter's
# exit its X window is torn down after the context, which fails).
from paraview.simple import Delete  # noqa: E402
Delete(display)
Delete(view)
del display, view

# finish(exit_on_success=False): on success pvbatch ends normally and finalizes MPI.
pitesting.finish(exit_on_success=False)
