"""The wrapped `pisurfaces` package: importable without the plugin, exact evaluation,
models, meshing. Runs under /usr/bin/python3 and pvpython."""
import math
import os

from pitesting import check, finish

from pisurfaces import vtkPiSurface, vtkPiPrimitive, vtkPiFlyingEdges, vtkPiSurfaceModelReader
from vtkmodules.vtkCommonCore import reference
from vtkmodules.vtkCommonDataModel import vtkSphere



# The paper's two spheres, F = ((x-d)^2+y^2+z^2-1)((x+d)^2+y^2+z^2-1) - 0.25
d = 0.9
s = vtkPiSurface()
a = vtkPiPrimitive()
a.SetCenter(d, 0, 0)
b = vtkSphere()
b.SetCenter(-d, 0, 0)
b.SetRadius(1)
s.AddFactor(a)
s.AddFactor(b)
s.SetBlending(0.25)
for p in [(0, 0, 0), (0.3, -0.2, 0.5), (2, 1, -1)]:
    x, y, z = p
    expected = ((x - d) ** 2 + y * y + z * z - 1) * ((x + d) ** 2 + y * y + z * z - 1) - 0.25
    check(abs(s.EvaluateFunction(p) - expected) < 1e-12, "value at %s" % (p,))
check(abs(s.EvaluateFunction(0, math.sqrt(1.5 - d * d), 0)) < 1e-12, "neck radius")
g = s.FunctionGradient(0.3, 0.2, 0.1)
check(all(math.isfinite(v) for v in g), "gradient")

# Overflow-safe sign and log for a product of 2000 factors.
many = vtkPiSurface()
prims = []
for i in range(2000):
    p = vtkPiPrimitive()
    p.SetCenter(3.0 * i, 0, 0)
    p.SetRadius(1)
    prims.append(p)
    many.AddFactor(p)
many.SetBlending(1.0)
log_abs = reference(0.0)
sign = many.EvaluateSignAndLog([100.5, 50, 0], log_abs)
check(sign == 1 and float(log_abs) > 700, "sign/log beyond the double range: %s %s" % (sign, log_abs))
check(many.EvaluateFunction(100.5, 50, 0) == 1.7976931348623157e308, "clamped to DBL_MAX")

# Models round-trip through JSON and files.
models = os.environ.get("PISURF_MODELS_DIR")
m = vtkPiSurface()
check(m.LoadModel(os.path.join(models, "eggplant_r0.25.pisurf")), "load eggplant")
check(m.GetNumberOfFactors() == 2, "eggplant has two factors")
again = vtkPiSurface()
check(again.SetModelJSON(m.GetModelJSON()), "JSON round trip")
for p in [(0, 0, 0), (1, 0.5, -0.2), (-3, 0.1, 0.1)]:
    check(abs(again.EvaluateFunction(p) - m.EvaluateFunction(p)) < 1e-12, "round trip value")

# Meshing from Python.
mesher = vtkPiFlyingEdges()
mesher.SetPiSurface(s)
mesher.SetResolution(48)
mesher.Update()
check(mesher.GetOutput().GetNumberOfPolys() > 500, "mesh of two spheres")
reader = vtkPiSurfaceModelReader()
reader.SetFileName(os.path.join(models, "formic_acid.pisurf"))
reader.Update()
check(reader.GetOutput().GetNumberOfPolys() > 500, "mesh of formic acid")

finish()
