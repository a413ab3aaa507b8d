"""vtkPiExactSurfaceMapper in a VTK window driven by VTK's interactor.

While a trackball rotation is under way (vtkInteractorStyle::StartRotate sets the
window's desired update rate to the interactor's, 15 frames a second) renders cast one
ray per InteractiveReductionFactor x InteractiveReductionFactor pixels (2 by default,
then 4); when it ends (EndRotate: the still rate) the render casts every pixel again.
ReductionFactor, if larger, wins in both; InteractiveReductionFactor 1 casts every pixel.

Translucency: an actor of opacity 0.5 in a renderer with depth peeling (or VTK's default
order-independent translucency) draws nothing and warns once; with ForceOpaque on it
draws, blended over the background.
"""
from vtkmodules.vtkCommonCore import vtkOutputWindow, vtkStringOutputWindow
from vtkmodules.vtkInteractionStyle import vtkInteractorStyleTrackballCamera
from vtkmodules.vtkRenderingCore import vtkRenderWindowInteractor

from pitesting import check, exact_view_of_cup, finish

W, H = 301, 200
mapper, renderer, window = exact_view_of_cup(W, H)
interactor = vtkRenderWindowInteractor()
interactor.SetRenderWindow(window)
style = vtkInteractorStyleTrackballCamera()
interactor.SetInteractorStyle(style)
window.Render()


def cast_after(render, what, expected):
    renderer.GetActiveCamera().Azimuth(2.0)
    render()
    got = tuple(mapper.GetCastResolution())
    print("%s: cast %d x %d (desired update rate %g)" % (what, got[0], got[1],
                                                         window.GetDesiredUpdateRate()))
    check(got == expected, "%s casts %s rays, not %s" % (what, expected, got))
    check(mapper.GetDrawn(), "%s draws the cup" % what)


def reduced(n):
    return ((W + n - 1) // n, (H + n - 1) // n)


cast_after(window.Render, "a still render", (W, H))
style.StartRotate()
cast_after(window.Render, "rotating", reduced(2))
mapper.SetInteractiveReductionFactor(4)
cast_after(window.Render, "rotating, InteractiveReductionFactor 4", reduced(4))
mapper.SetReductionFactor(5)
cast_after(window.Render, "rotating, ReductionFactor 5", reduced(5))
mapper.SetReductionFactor(1)
mapper.SetInteractiveReductionFactor(1)
cast_after(window.Render, "rotating, InteractiveReductionFactor 1", (W, H))
mapper.SetInteractiveReductionFactor(2)
cast_after(window.Render, "rotating again", reduced(2))
style.EndRotate()  # renders at the still rate
cast_after(window.Render, "after the rotation", (W, H))

actor = renderer.GetActors().GetLastActor()
actor.GetProperty().SetOpacity(0.5)
messages = vtkStringOutputWindow()
previous = vtkOutputWindow.GetInstance()
vtkOutputWindow.SetInstance(messages)
for peeling in (1, 0):  # peeling, then VTK's order-independent translucency
    renderer.SetUseDepthPeeling(peeling)
    for _ in range(2):
        window.Render()
        check(not mapper.GetDrawn(), "a translucent actor draws nothing (peeling %d)" % peeling)
vtkOutputWindow.SetInstance(previous)
text = messages.GetOutput()
print("translucent actor: " + text.strip())
check(text.count("translucent exact surface") == 1, "one warning for the translucent actor")
actor.ForceOpaqueOn()
window.Render()
check(mapper.GetDrawn(), "with ForceOpaque the translucent actor draws")
finish()
