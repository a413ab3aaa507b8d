"""Scripted GUI test (run by `paraview --script=...` under Xvfb, the plugin loaded with
--plugins=PiSurfaces): build the paper's two-spheres product from two Pi Primitive
sources, check the GUI's default display of the product (translucent grey), change their
distance, and compare the render view with a baseline
(Testing/Baselines/PiProductGUI.png). Exits with os._exit(rc) so that the GUI quits."""
import os
import sys
import traceback

rc = 1


def say(text):
    # The GUI sends print() to its Output Messages window: write to the terminal.
    sys.__stderr__.write(text + "\n")


try:
    from paraview.simple import *  # noqa: F401,F403
    from vtkmodules.vtkTestingRendering import vtkTesting

    temp = os.environ["PISURF_TEMP_DIR"]
    baseline = os.path.join(os.environ["PISURF_BASELINES_DIR"], "PiProductGUI.png")
    right = PiPrimitive(registrationName="right", Center=[0.9, 0, 0])
    left = PiPrimitive(registrationName="left", Center=[-0.9, 0, 0])
    product = PiProduct(registrationName="two_spheres", Input=[right, left], Blending=0.25,
                        Resolution=64)
    view = GetActiveViewOrCreate("RenderView")
    view.OrientationAxesVisibility = 0
    view.Background = [0.32, 0.34, 0.43]
    shown = Show(product, view)
    # The plugin's display behaviour (GUI only): the Pi-surface translucent solid grey.
    say("product shown with opacity %g, colour array %r" % (shown.Opacity, shown.ColorArrayName[1]))
    if not shown.Opacity < 1 or shown.ColorArrayName[1]:
        raise RuntimeError("the GUI did not give the Pi Product its translucent grey look")
    shown.DiffuseColor = [0.8, 0.8, 0.8]
    for source, colour in ((right, [0.9, 0.3, 0.2]), (left, [0.2, 0.5, 0.9])):
        d = Show(source, view)
        d.DiffuseColor = colour
        d.Representation = "Wireframe"
    # Change the distance: d = 0.9 -> 1.1 on the right sphere; the product follows.
    right.Center = [1.1, 0, 0]
    view.CameraPosition = [0.1, -9, 0]
    view.CameraFocalPoint = [0.1, 0, 0]
    view.CameraViewUp = [0, 0, 1]
    view.CameraParallelProjection = 1
    view.CameraParallelScale = 1.6
    Render(view)
    cells = product.GetDataInformation().GetNumberOfCells()
    bounds = product.GetDataInformation().GetBounds()
    say("product: %d cells, x in [%g, %g]" % (cells, bounds[0], bounds[1]))
    if cells < 1000 or bounds[1] < 2.0:
        raise RuntimeError("the product did not follow the moved primitive")
    image = os.path.join(temp, "PiProductGUI.png")
    SaveScreenshot(image, view, ImageResolution=[400, 300])
    testing = vtkTesting()
    for argument in ("-V", baseline, "-T", temp):
        testing.AddArgument(argument)
    if not os.path.exists(baseline):
        say("no baseline yet: look at %s and copy it to %s" % (image, baseline))
    elif testing.RegressionTest(image, 0.05) == vtkTesting.PASSED:
        rc = 0
    else:
        say("Failed Image Test: %s differs from %s" % (image, baseline))
except Exception:
    say(traceback.format_exc())
sys.__stderr__.flush()
os._exit(rc)
