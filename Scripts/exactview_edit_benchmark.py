"""Edit to picture: the exact view against the mesh whose silhouette matches its pixel.

    pvpython exactview_edit_benchmark.py MODELS_DIR [ROUNDS]    (./run bench; 5)

The cup (Pi Surface, the model as JSON text) in a 1280 x 800 render view, STDThread
backend, the camera as a user frames it (ResetCamera, 25 degrees up).

1. The matching resolution. For Resolution R in RESOLUTIONS, the pixels the Surface
   display of the mesh covers (the Z buffer below 1) against those the Pi Exact
   Surface display covers: the silhouette displacement is the number of pixels covered
   by one and not the other divided by the number of silhouette pixels of the exact
   picture (covered pixels with an uncovered 4-neighbour), i.e. the mean distance in
   pixels between the two outlines; the largest displacement is the farthest such pixel
   from the exact outline (in steps to one of the 8 neighbours). The mesh path uses the
   smallest R whose largest displacement is one pixel (the exact view's own error is
   below one pixel).
2. Edit to picture, side by side (taking turns, best and median of ROUNDS): the handle
   moved (the model's parameter `a` between 1.0 and 1.02, a primitive edit), then a still
   Render of the view. Exact: the source outputs the model alone (nothing but the exact
   display shows it) and the view casts 1280 x 800 rays. Mesh: the source meshes at R
   and the view draws the triangles.
"""
import json
import os
import statistics
import sys
import time

import numpy
import pisurfaces  # noqa: F401 (the client-side objects as vtkPiModelMesher)
from paraview.simple import GetActiveViewOrCreate, PiSurface, Render, Show
from vtkmodules.vtkCommonCore import vtkFloatArray, vtkSMPTools
from vtkmodules.util.numpy_support import vtk_to_numpy

RESOLUTIONS = (32, 48, 64, 96, 128, 192, 256, 384)
W, H = 1280, 800


def coverage(view):
    Render(view)
    window = view.GetRenderWindow()
    z = vtkFloatArray()
    window.GetZbufferData(0, 0, W - 1, H - 1, z)
    return vtk_to_numpy(z).reshape(H, W) < 1.0


def silhouette(mask):
    inner = mask.copy()
    inner[1:, :] &= mask[:-1, :]
    inner[:-1, :] &= mask[1:, :]
    inner[:, 1:] &= mask[:, :-1]
    inner[:, :-1] &= mask[:, 1:]
    return mask & ~inner


def dilated(mask):
    out = mask.copy()
    out[1:, :] |= mask[:-1, :]
    out[:-1, :] |= mask[1:, :]
    out[:, 1:] |= mask[:, :-1]
    out[:, :-1] |= mask[:, 1:]
    out[1:, 1:] |= mask[:-1, :-1]
    out[:-1, :-1] |= mask[1:, 1:]
    out[1:, :-1] |= mask[:-1, 1:]
    out[:-1, 1:] |= mask[1:, :-1]
    return out


def largest_displacement(differ, outline, limit=32):
    """The largest distance in pixels (8-neighbourhood steps) from a pixel covered by
    one display only to the exact outline; limit + 1 if beyond."""
    reach = outline
    for k in range(limit + 1):
        if not (differ & ~reach).any():
            return k
        reach = dilated(reach)
    return limit + 1


def with_a(model, a):
    model = dict(model)
    model["parameters"] = dict(model.get("parameters", {}), a=a)
    return json.dumps(model)


def main():
    models = sys.argv[1]
    rounds = int(sys.argv[2]) if len(sys.argv) > 2 else 5
    vtkSMPTools.SetBackend("STDThread")
    with open(os.path.join(models, "cup_a1.0.pisurf")) as f:
        model = json.load(f)

    view = GetActiveViewOrCreate("RenderView")
    view.ViewSize = [W, H]
    view.OrientationAxesVisibility = 0
    exact_source = PiSurface(Model=with_a(model, 1.0), Resolution=64)
    exact = Show(exact_source, view)
    exact.SetRepresentationType("Pi Exact Surface")
    view.ResetCamera()
    camera = view.GetActiveCamera()
    camera.Elevation(25)
    view.ResetCamera()
    truth = coverage(view)
    edge = silhouette(truth)
    outline = max(1, int(edge.sum()))

    print("Cup, %d x %d view, %s with %d threads, load average %.2f"
          % (W, H, vtkSMPTools.GetBackend(), vtkSMPTools.GetEstimatedNumberOfThreads(),
             os.getloadavg()[0]))
    print("| Resolution | pixels covered by one display only | mean displacement | largest |")
    print("|---|---|---|---|")
    exact.Visibility = 0
    mesh_source = PiSurface(Model=with_a(model, 1.0))
    mesh = Show(mesh_source, view)
    chosen = None
    for r in RESOLUTIONS:
        mesh_source.Resolution = r
        mask = coverage(view) != truth
        differ = int(mask.sum())
        largest = largest_displacement(mask, edge)
        print("| %d | %d | %.2f px | %d px |" % (r, differ, differ / outline, largest))
        if chosen is None and largest <= 1:
            chosen = r
    if chosen is None:
        chosen = RESOLUTIONS[-1]
        print("(no resolution up to %d is within one pixel; the mesh path uses %d)"
              % (chosen, chosen))
    mesh_source.Resolution = chosen
    Render(view)

    def edit(source, shown, hidden, state):
        """Shows one display alone, moves the handle, renders: the seconds."""
        hidden.Visibility = 0
        shown.Visibility = 1
        state["a"] = 1.02 if state["a"] == 1.0 else 1.0
        t = time.perf_counter()
        source.Model = with_a(model, state["a"])
        Render(view)
        return time.perf_counter() - t

    times = {"exact": [], "mesh": []}
    states = {"exact": {"a": 1.0}, "mesh": {"a": 1.0}}
    for _ in range(rounds):
        times["exact"].append(edit(exact_source, exact, mesh, states["exact"]))
        times["mesh"].append(edit(mesh_source, mesh, exact, states["mesh"]))
    model_only = exact_source.GetClientSideObject().GetLastOutputModelOnly()
    print()
    print("| path | best | median | mesh / exact (median) |")
    print("|---|---|---|---|")
    e, m = statistics.median(times["exact"]), statistics.median(times["mesh"])
    print("| Pi Exact Surface, 1280 x 800 rays%s | %.0f ms | %.0f ms | |"
          % ("" if model_only else " (the source still meshed!)",
             1e3 * min(times["exact"]), 1e3 * e))
    print("| Surface, mesh at Resolution %d | %.0f ms | %.0f ms | %.1fx |"
          % (chosen, 1e3 * min(times["mesh"]), 1e3 * m, m / e))


if __name__ == "__main__":
    main()
