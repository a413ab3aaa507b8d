"""vtkPiExactSurfaceMapper in a VTK window driven by VTK's interactor.

While a trackball rotation is under way (vtkInteractorStyle::StartRotate sets the
window's desired update rate to the interactor's, 15 frames a second) renders cast one
ray per InteractiveReductionFactor x InteractiveReductionFactor pixels (2 by default,
then 4); when it ends (EndRotate: the still rate) the render casts every pixel again.
ReductionFactor, if larger, wins in both; InteractiveReductionFactor 1 casts every pixel.
"""
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
finish()
