"""The exact view in an 8192 x 8192 window: the cast stays within the ray caster's cap.

A full cast of 8192 x 8192 rays would exceed the caster's memory cap (2 GiB), so
vtkPiExactSurfaceMapper casts one ray per 3 x 3 pixels (2731 x 2731 rays), warns once
(not again at the next render), and draws the cup. The process's peak memory grows by
less than the cap from a render at one ray per 16 x 16 pixels to the full render (the
window's own buffers, about 4 GiB with Mesa, are there in both).
"""
import resource

from vtkmodules.vtkCommonCore import vtkFloatArray, vtkOutputWindow, vtkStringOutputWindow

from pitesting import check, exact_view_of_cup, finish

SIZE = 8192
CAP_MIB = 2048

mapper, renderer, window = exact_view_of_cup(SIZE, SIZE)
mapper.SetReductionFactor(16)

messages = vtkStringOutputWindow()
previous = vtkOutputWindow.GetInstance()
vtkOutputWindow.SetInstance(messages)
window.Render()
small = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
mapper.SetReductionFactor(1)
window.Render()
full = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0
renderer.GetActiveCamera().Azimuth(5)
window.Render()
vtkOutputWindow.SetInstance(previous)
text = messages.GetOutput()
print("peak memory: %.0f MiB at 1/256 of the rays, %.0f MiB at full size" % (small, full))
print(text)

check(tuple(mapper.GetCastResolution()) == (2731, 2731),
      "cast %s rays, not one per 3 x 3 pixels" % (mapper.GetCastResolution(),))
check(text.count("exceeds the ray caster's memory cap") == 1,
      "one warning about the cap over two renders: %r" % text)
check(full - small < CAP_MIB, "the full render grew the peak memory by %.0f MiB" % (full - small))
z = vtkFloatArray()
window.GetZbufferData(SIZE // 2 - 50, SIZE // 2 - 50, SIZE // 2 + 49, SIZE // 2 + 49, z)
check(any(z.GetValue(n) < 1.0 for n in range(z.GetNumberOfTuples())),
      "nothing drawn at the centre of the view")
finish()
