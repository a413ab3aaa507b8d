"""PiSurfaces benchmarks: ratios against the VTK pipeline a user would otherwise write.

    pvpython benchmark.py MODELS_DIR [N]      (./run bench; N = grid points per axis, 256)

For each model and each vtkSMPTools backend (Sequential, STDThread), measured side by
side in one run (best of 5, the pipelines compared taking turns, one execution each per
round: on a shared 2-core machine single runs vary by half, in phases of seconds, and
turns let a slow phase slow every side alike):
  grid eval   vtkSampleFunction over vtkImplicitSum of the same factors (VTK's own way
              to compose functions: a virtual call per point per factor; a sum, but the
              same cost as a hand-written product), vtkSampleFunction over vtkPiSurface
              (one virtual call per point), vtkPiSurface.FunctionValue on the same
              grid points (batched blocks) and vtkPiSampleFunction (the same grid, a
              row at a time: each factor restricted to each row once, then Horner's
              rule several points at a time); ComputeNormals off everywhere
  mesh        vtkSampleFunction + vtkFlyingEdges3D with its normals
              versus vtkPiFlyingEdges at its defaults (row-restricted sampling, flying
              edges, exact normals, vertices moved onto F = 0, outer envelope) and with
              ProjectVertices and OuterEnvelope off (the same work as VTK's pipeline:
              linear vertices, every sheet; the same triangles); a new vtkPiFlyingEdges
              for every execution (a re-executed one keeps its factors' row
              restrictions and would skip that pass)
"""
import os
import sys
import time

from pisurfaces import vtkPiFlyingEdges, vtkPiPrimitive, vtkPiSampleFunction, vtkPiSurface
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkSMPTools
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D
from vtkmodules.vtkCommonDataModel import vtkImplicitSum
from vtkmodules.vtkImagingHybrid import vtkSampleFunction


def best_of(functions, n=5):
    """The best time and the last result of each function, over n rounds in which each
    runs once, in turn."""
    best = [float("inf")] * len(functions)
    results = [None] * len(functions)
    for _ in range(n):
        for k, f in enumerate(functions):
            t = time.perf_counter()
            results[k] = f()
            best[k] = min(best[k], time.perf_counter() - t)
    return list(zip(best, results))


def ten_spheres():
    s = vtkPiSurface()
    for i in range(10):
        p = vtkPiPrimitive()
        p.SetCenter(1.2 * (i % 5) - 2.4, 1.2 * (i // 5) - 0.6, 0.1 * i)
        p.SetRadius(0.8)
        s.AddFactor(p)
    s.SetBlending(0.5)
    return s


def load(path):
    s = vtkPiSurface()
    if not s.LoadModel(path):
        raise RuntimeError(path)
    return s


def grid_points(bounds, n):
    pts = vtkDoubleArray()
    pts.SetNumberOfComponents(3)
    pts.SetNumberOfTuples(n * n * n)
    h = [(bounds[2 * k + 1] - bounds[2 * k]) / (n - 1) for k in range(3)]
    i = 0
    import numpy as np
    from vtkmodules.util.numpy_support import vtk_to_numpy
    a = vtk_to_numpy(pts)
    z, y, x = np.meshgrid(*(bounds[2 * k] + h[k] * np.arange(n) for k in (2, 1, 0)), indexing="ij")
    a[:, 0] = x.ravel()
    a[:, 1] = y.ravel()
    a[:, 2] = z.ravel()
    return pts


def sampler(function, bounds, n):
    sample = vtkSampleFunction()
    sample.SetImplicitFunction(function)
    sample.SetModelBounds(bounds)
    sample.SetSampleDimensions(n, n, n)
    sample.ComputeNormalsOff()
    return sample


def run(name, surface, n):
    bounds = [0.0] * 6
    surface.GetModelBounds(bounds)
    rows = []
    pts = grid_points(bounds, n)
    for backend in ("Sequential", "STDThread"):
        vtkSMPTools.SetBackend(backend)

        sample = sampler(surface, bounds, n)

        def vtk_eval():
            sample.Modified()
            sample.Update()
            return sample.GetOutput()

        out = vtkDoubleArray()

        def pi_eval():
            surface.FunctionValue(pts, out)
            return out

        composed = vtkImplicitSum()
        for i in range(surface.GetNumberOfFactors()):
            composed.AddFunction(surface.GetFactor(i))
        sample_sum = sampler(composed, bounds, n)

        def sum_eval():
            sample_sum.Modified()
            sample_sum.Update()

        grid = vtkPiSampleFunction()
        grid.SetPiSurface(surface)
        grid.SetModelBounds(bounds)
        grid.SetSampleDimensions(n, n, n)

        def grid_eval():
            grid.Modified()
            grid.Update()

        (t_sum_eval, _), (t_vtk_eval, _), (t_pi_eval, _), (t_grid_eval, _) = best_of(
            [sum_eval, vtk_eval, pi_eval, grid_eval])

        sample_n = sampler(surface, bounds, n)
        contour = vtkFlyingEdges3D()
        contour.SetInputConnection(sample_n.GetOutputPort())
        contour.SetValue(0, 0.0)
        contour.ComputeNormalsOn()

        def vtk_mesh():
            sample_n.Modified()
            contour.Update()
            return contour.GetOutput().GetNumberOfCells()

        # A new mesher for every execution: a re-executed one would find every factor's
        # row restrictions of its last execution in its cache (kept for edits that change
        # a few factors) and skip that pass, which VTK's pipeline cannot.
        meshers = {}

        def fresh_mesh(key, project):
            meshers.pop(key, None)  # (the last one released inside the timing, as VTK's)
            mesher = meshers[key] = vtkPiFlyingEdges()
            mesher.SetPiSurface(surface)
            mesher.SetBounds(bounds)
            mesher.SetSampleDimensions(n, n, n)
            mesher.SetProjectVertices(project)
            mesher.SetOuterEnvelope(project)
            mesher.Update()
            return mesher.GetOutput().GetNumberOfCells()

        def pi_mesh():
            return fresh_mesh("defaults", True)

        def pi_plain():
            return fresh_mesh("plain", False)

        (t_vtk_mesh, cells_vtk), (t_pi_mesh, cells_pi), (t_pi_plain, cells_plain) = best_of(
            [vtk_mesh, pi_mesh, pi_plain])
        rows.append((name, backend, t_sum_eval, t_vtk_eval, t_pi_eval, t_grid_eval, t_vtk_mesh,
                     t_pi_mesh, cells_vtk, cells_pi, t_pi_plain, cells_plain))
    return rows


def main():
    models = sys.argv[1]
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 256
    cases = [
        ("10 spheres", ten_spheres()),
        ("table", load(os.path.join(models, "table.pisurf"))),
        ("cup", load(os.path.join(models, "cup_a1.0.pisurf"))),
    ]
    print("grid %d^3, load average %.2f, %d cores" % (n, os.getloadavg()[0], os.cpu_count()))
    print("| model | backend | SampleFunction(ImplicitSum) | SampleFunction(PiSurface) | "
          "PiSurface batch | vtkPiSampleFunction | grid ratio to ImplicitSum / PiSurface | "
          "SampleFunction+FlyingEdges3D | vtkPiFlyingEdges | ratio | triangles VTK / Pi | "
          "vtkPiFlyingEdges, projection and envelope off | ratio | triangles |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for name, surface in cases:
        for r in run(name, surface, n):
            print("| %s | %s | %.3f s | %.3f s | %.3f s | %.3f s | %.1fx / %.1fx | %.3f s | %.3f s "
                  "| %.1fx | %d / %d | %.3f s | %.1fx | %d |"
                  % (r[0], r[1], r[2], r[3], r[4], r[5], r[2] / r[5], r[3] / r[5], r[6], r[7],
                     r[6] / r[7], r[8], r[9], r[10], r[6] / r[10], r[11]))


if __name__ == "__main__":
    main()
