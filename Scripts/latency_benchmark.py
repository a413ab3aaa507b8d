"""Latency of the live Pi Product: time from a property change to the new mesh.

Usage: pvpython Scripts/latency_benchmark.py MODELS_DIR [RESOLUTION] [MOVES]

Two scenes built from Pi Primitive sources, as in the paper's interactive figures:
the cup (handle torus, base ellipsoid, bowl torus; r = 10) with the handle moving, and
the rounded cube x^6+y^6+z^6-1 with a negative sphere (radius sqrt(0.05), r = 0.01)
moving into its +x face. Each move sets the moving primitive's Center and times
UpdatePipeline() of the product: the moved primitive re-meshes itself (Resolution 64)
and the product re-meshes at RESOLUTION (default 96) cells along its longest side.
Both vtkSMPTools backends; the best, the median and the worst of MOVES moves (default
20): on a shared machine the best is the closest to the unloaded cost."""
import json
import os
import statistics
import sys
import time

from paraview.simple import PiPrimitive, PiProduct, Delete
from vtkmodules.vtkCommonCore import vtkSMPTools

models = sys.argv[1]
resolution = int(sys.argv[2]) if len(sys.argv) > 2 else 96
moves = int(sys.argv[3]) if len(sys.argv) > 3 else 20


def cup_scene():
    cup = json.load(open(os.path.join(models, "cup_a1.0.pisurf")))
    handle = PiPrimitive(Type="Polynomial", Center=[2.2, 0, -1],
                         Expression="(x^2+z^2+y^2+0.5-0.01)^2-2*(x^2+z^2)")
    base = PiPrimitive(Type="Polynomial", Expression="1/8*x^2+1/8*y^2+(z+2)^2-0.1")
    bowl = PiPrimitive(Type="Polynomial", Expression="((z+1)^2+10*x^2+10*y^2+19)^2-800*(x^2+y^2)")
    product = PiProduct(Input=[handle, base, bowl], Blending=cup["blending"],
                        Bounds=cup["bounds"], Resolution=resolution)
    # The handle slides along x (a = 1.0 .. 1.25 in the paper's family of cups).
    positions = [[2.2 + 0.55 * k / moves, 0, -1] for k in range(1, moves + 1)]
    return product, handle, positions, [handle, base, bowl]


def cube_scene():
    cube_model = json.load(open(os.path.join(models, "rounded_cube_sphere_1.pisurf")))
    cube = PiPrimitive(Type="Polynomial", Expression="x^6+y^6+z^6-1")
    dent = PiPrimitive(Type="Sphere", Radius=0.05 ** 0.5, Negate=1, Center=[1.6, 0, 0])
    product = PiProduct(Input=[cube, dent], Blending=cube_model["blending"],
                        Bounds=cube_model["bounds"], Resolution=resolution)
    # The negative sphere approaches the face x = 1 (the paper's positions 1 to 3).
    positions = [[1.6 - 0.6 * k / moves, 0, 0] for k in range(1, moves + 1)]
    return product, dent, positions, [cube, dent]


def measure(scene):
    product, moving, positions, sources = scene()
    product.UpdatePipeline()  # first execution: not a latency
    times = []
    cells = 0
    for p in positions:
        moving.Center = p
        t0 = time.perf_counter()
        product.UpdatePipeline()
        times.append(time.perf_counter() - t0)
        cells = max(cells, product.GetDataInformation().GetNumberOfCells())
    Delete(product)
    for s in sources:
        Delete(s)
    return min(times), statistics.median(times), max(times), cells


print("Pi Product latency: property change -> new mesh (UpdatePipeline), Resolution %d, "
      "%d moves" % (resolution, moves))
print("| scene | backend | best | median | worst | triangles | median within 50 ms |")
print("|---|---|---|---|---|---|---|")
for backend in ("Sequential", "STDThread"):
    vtkSMPTools.SetBackend(backend)
    for name, scene in (("cup, moving handle", cup_scene),
                        ("rounded cube, moving negative sphere", cube_scene)):
        best, median, worst, cells = measure(scene)
        print("| %s | %s | %.1f ms | %.1f ms | %.1f ms | %d | %s |" % (
            name, vtkSMPTools.GetBackend(), 1e3 * best, 1e3 * median, 1e3 * worst, cells,
            "yes" if median <= 0.050 else "no"))
        sys.stdout.flush()
