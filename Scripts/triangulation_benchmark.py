"""Image-based triangulation benchmark (./run bench): one ray-cast cloud, three meshes.

    pvpython triangulation_benchmark.py MODELS_DIR [N [MODEL,...]]   (N pixels per side,
        default 512; models default cup_a1.0,formic_acid)

On the six axis views (first hits, N x N each) of the cup and formic acid, with the
STDThread backend (our meshes: the median of six runs, three just before vtkDelaunay2D and
three just after it, so that they sample the same stretch of the shared host's speed as
its 40 s; flying edges: the median of five runs):
  ours      vtkPiImageTriangulator on the whole cloud (ray lattice, closed mesh), with
            its default EdgeFlipRounds 1 and with 0 (no flips, polygons fanned)
  delaunay  vtkDelaunay2D on each view's hits (projected on the view's image plane),
            what a VTK user would write to connect one view's samples
  srf       vtkSurfaceReconstructionFilter + vtkContourFilter on the hits (an
            unorganized cloud), in a child process: on the full cloud with a budget of
            60 s (its time grows as the square of the cloud), and on the 128² views'
            cloud in full, against ours on that cloud
  fe        vtkPiFlyingEdges at the resolution giving about the same vertex count
Accuracy: max and RMS |F|/|grad F| at the vertices relative to the model size, the
RMS |F|/|grad F| at triangle centroids (how far the triangles leave the surface), and
the distance from the exact surface to the mesh: 4000 points of F = 0 (vertices of a
much finer flying-edges mesh at a resolution unrelated to either lattice, chosen at
random) to their closest point of the mesh (vtkStaticCellLocator), RMS and max,
relative to the model size.
"""
import math
import random
import statistics
import sys
import time

from pisurfaces import vtkPiFlyingEdges, vtkPiImageTriangulator, vtkPiRayCaster, vtkPiSurface
from vtkmodules.vtkCommonCore import vtkSMPTools
from vtkmodules.vtkCommonDataModel import vtkPolyData, vtkStaticCellLocator
from vtkmodules.vtkFiltersCore import vtkDelaunay2D, vtkThreshold
from vtkmodules.vtkFiltersGeneral import vtkTransformFilter


def load_model(models, name):
    """The model `name` of the folder `models` and its size (the diagonal of its bounds)."""
    surface = vtkPiSurface()
    surface.LoadModel("%s/%s.pisurf" % (models, name))
    b = [0.0] * 6
    surface.GetModelBounds(b)
    return surface, math.sqrt(sum((b[2 * a + 1] - b[2 * a]) ** 2 for a in range(3)))


def six_views(surface, n):
    """A ray caster of the six axis views, n x n first hits each (not yet updated)."""
    caster = vtkPiRayCaster()
    caster.SetPiSurface(surface)
    caster.SetViewMode(vtkPiRayCaster.SIX_AXIS_VIEWS)
    caster.SetResolution(n, n)
    return caster


def distance(surface, p):
    g = [0.0, 0.0, 0.0]
    f = surface.EvaluateFunction(p)
    surface.EvaluateGradient(p, g)
    return abs(f) / max(math.sqrt(sum(x * x for x in g)), 1e-300)


def accuracy(surface, mesh, size, samples=4000):
    n = mesh.GetNumberOfPoints()
    step = max(1, n // samples)
    d = [distance(surface, mesh.GetPoint(k)) / size for k in range(0, n, step)]
    cells = mesh.GetNumberOfCells()
    cstep = max(1, cells // samples)
    c = []
    for k in range(0, cells, cstep):
        ids = mesh.GetCell(k).GetPointIds()
        if ids.GetNumberOfIds() != 3:
            continue
        q = [sum(mesh.GetPoint(ids.GetId(v))[a] for v in range(3)) / 3 for a in range(3)]
        c.append(distance(surface, q) / size)
    rms = lambda x: math.sqrt(sum(v * v for v in x) / max(len(x), 1))
    return max(d), rms(d), rms(c)


def run_times(algorithm, runs):
    """The wall times of `runs` executions (the 2-core machine's timings vary by tens of
    percent from one run to the next; vtkDelaunay2D, 40 s a view set, runs once)."""
    times = []
    for _ in range(runs):
        algorithm.Modified()
        t = time.perf_counter()
        algorithm.Update()
        times.append(time.perf_counter() - t)
    return times


def median_time(algorithm, runs=5):
    """The median wall time of `runs` executions."""
    return statistics.median(run_times(algorithm, runs))


def surface_points(surface, count=4000, resolution=701):
    """Points of F = 0: vertices of a fine flying-edges mesh (exact to ~1e-13), at random."""
    fine = vtkPiFlyingEdges()
    fine.SetPiSurface(surface)
    fine.SetResolution(resolution)
    fine.Update()
    mesh = fine.GetOutput()
    rng = random.Random(7)
    return [mesh.GetPoint(rng.randrange(mesh.GetNumberOfPoints())) for _ in range(count)]


def surface_to_mesh(points, mesh, size):
    """RMS and max distance from the surface points to the mesh, relative to `size`."""
    locator = vtkStaticCellLocator()
    locator.SetDataSet(mesh)
    locator.BuildLocator()
    closest = [0.0, 0.0, 0.0]
    from vtkmodules.vtkCommonCore import mutable
    cell, sub, d2 = mutable(0), mutable(0), mutable(0.0)
    d = []
    for p in points:
        locator.FindClosestPoint(p, closest, cell, sub, d2)
        d.append(math.sqrt(float(d2)) / size)
    return math.sqrt(sum(v * v for v in d) / len(d)), max(d)


RECONSTRUCTION = r"""
import sys, time
from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter
from vtkmodules.vtkImagingHybrid import vtkSurfaceReconstructionFilter
from vtkmodules.vtkFiltersCore import vtkContourFilter
reader = vtkXMLPolyDataReader()
reader.SetFileName(sys.argv[1])
reader.Update()
t = time.perf_counter()
srf = vtkSurfaceReconstructionFilter()
srf.SetInputConnection(reader.GetOutputPort())
contour = vtkContourFilter()
contour.SetInputConnection(srf.GetOutputPort())
contour.SetValue(0, 0.0)
contour.Update()
print(time.perf_counter() - t)
writer = vtkXMLPolyDataWriter()
writer.SetInputConnection(contour.GetOutputPort())
writer.SetFileName(sys.argv[2])
writer.Write()
"""


def reconstruction(cloud, budget):
    """vtkSurfaceReconstructionFilter + vtkContourFilter on the cloud's points (what a
    VTK user would write for an unorganized cloud), in a child pvpython so that it can
    be stopped after `budget` seconds: (time, mesh) or (None, None) if it ran out."""
    import os
    import shutil
    import subprocess
    import tempfile
    from vtkmodules.vtkIOXML import vtkXMLPolyDataReader, vtkXMLPolyDataWriter
    with tempfile.TemporaryDirectory() as tmp:
        points = vtkPolyData()
        points.SetPoints(cloud.GetPoints())
        writer = vtkXMLPolyDataWriter()
        writer.SetInputData(points)
        writer.SetFileName(os.path.join(tmp, "cloud.vtp"))
        writer.Write()
        script = os.path.join(tmp, "reconstruct.py")
        with open(script, "w") as f:
            f.write(RECONSTRUCTION)
        try:
            run = subprocess.run([shutil.which("pvpython") or sys.executable, script, os.path.join(tmp, "cloud.vtp"),
                                  os.path.join(tmp, "mesh.vtp")], capture_output=True,
                                 text=True, timeout=budget)
        except subprocess.TimeoutExpired:
            return None, None
        if run.returncode != 0:
            return None, None
        reader = vtkXMLPolyDataReader()
        reader.SetFileName(os.path.join(tmp, "mesh.vtp"))
        reader.Update()
        mesh = vtkPolyData()
        mesh.DeepCopy(reader.GetOutput())
        return float(run.stdout.split()[0]), mesh


def main():
    models = sys.argv[1]
    n = int(sys.argv[2]) if len(sys.argv) > 2 else 512
    vtkSMPTools.SetBackend("STDThread")
    print("\nImage-based triangulation, six axis views of %d x %d first hits, STDThread" % (n, n))
    print("%-12s %-22s %9s %9s %9s %11s %11s %11s %11s %11s" % (
        "model", "method", "time s", "vertices", "ratio", "max vtx", "rms vtx", "rms centr",
        "rms surf", "max surf"))
    for name in (sys.argv[3].split(",") if len(sys.argv) > 3 else ("cup_a1.0", "formic_acid")):
        surface, size = load_model(models, name)
        caster = six_views(surface, n)
        t = time.perf_counter()
        caster.Update()
        cast = time.perf_counter() - t
        cloud = caster.GetOutput()

        tri = vtkPiImageTriangulator()
        tri.SetInputData(cloud)
        ours_times = run_times(tri, 3)
        mesh = tri.GetOutput()
        # The same without edge flips (polygons fanned as marching cubes does).
        fast = vtkPiImageTriangulator()
        fast.SetInputData(cloud)
        fast.SetEdgeFlipRounds(0)
        unflipped_times = run_times(fast, 3)

        # vtkDelaunay2D per view: each view's hits, in the view's (u, v) image plane.
        t = time.perf_counter()
        delaunay_triangles = 0
        for view in range(6):
            threshold = vtkThreshold()
            threshold.SetInputData(cloud)
            threshold.SetInputArrayToProcess(0, 0, 0, 0, "ViewIndex")
            threshold.SetLowerThreshold(view - 0.5)
            threshold.SetUpperThreshold(view + 0.5)
            threshold.Update()
            points = threshold.GetOutput().GetPoints()
            if points is None:
                continue
            poly = vtkPolyData()
            poly.SetPoints(points)
            d2 = vtkDelaunay2D()
            d2.SetInputData(poly)
            d2.SetProjectionPlaneMode(2)  # best-fitting plane: the view's image plane
            d2.Update()
            delaunay_triangles += d2.GetOutput().GetNumberOfCells()
        delaunay = time.perf_counter() - t
        # Ours again, just after: the medians of the six runs around vtkDelaunay2D.
        ours = statistics.median(ours_times + run_times(tri, 3))
        unflipped = statistics.median(unflipped_times + run_times(fast, 3))

        # Flying edges at about our vertex count.
        fe = vtkPiFlyingEdges()
        fe.SetPiSurface(surface)
        res = int(n / 2)
        for _ in range(6):
            fe.SetResolution(res)
            fe.Update()
            ratio = mesh.GetNumberOfPoints() / max(fe.GetOutput().GetNumberOfPoints(), 1)
            if abs(ratio - 1) < 0.05:
                break
            res = max(8, int(round(res * math.sqrt(ratio))))
        # (a new mesher for every run: a re-executed one keeps its factors' row
        # restrictions and skips that pass)
        fetimes = []
        for _ in range(5):
            fresh = vtkPiFlyingEdges()
            fresh.SetPiSurface(surface)
            fresh.SetResolution(res)
            t = time.perf_counter()
            fresh.Update()
            fetimes.append(time.perf_counter() - t)
        fetime = statistics.median(fetimes)

        exact = surface_points(surface)
        print("%-12s %-22s %9.3f %9d" % (name, "ray cast (input)", cast, cloud.GetNumberOfPoints()))
        print("%-12s %-22s %9.3f %9d %9s %11.2e %11.2e %11.2e %11.2e %11.2e" % ((name,
            "ImageTriangulator", ours, mesh.GetNumberOfPoints(), "1") +
            accuracy(surface, mesh, size) + surface_to_mesh(exact, mesh, size)))
        print("%-12s %-22s %9.3f %9d %8.1fx %11.2e %11.2e %11.2e %11.2e %11.2e" % ((name,
            "  EdgeFlipRounds 0", unflipped, fast.GetOutput().GetNumberOfPoints(),
            unflipped / ours) + accuracy(surface, fast.GetOutput(), size) +
            surface_to_mesh(exact, fast.GetOutput(), size)))
        print("%-12s %-22s %9.3f %9d %8.1fx   (%.1fx the time without flips)" % (name,
            "Delaunay2D per view", delaunay, cloud.GetNumberOfPoints(), delaunay / ours,
            delaunay / unflipped))
        print("%-12s %-22s %9.3f %9d %8.1fx %11.2e %11.2e %11.2e %11.2e %11.2e" % ((name,
            "FlyingEdges res %d" % res, fetime, fe.GetOutput().GetNumberOfPoints(), fetime / ours) +
            accuracy(surface, fe.GetOutput(), size) + surface_to_mesh(exact, fe.GetOutput(), size)))
        # vtkSurfaceReconstructionFilter + contour: its time grows as the square of the
        # cloud (17 s for the cup's 49 000 hits of 128² views), so on the full cloud it
        # gets a budget; on a 128² cloud it is compared with ours in full.
        budget = 60
        srf_time, _ = reconstruction(cloud, budget)
        print("%-12s %-22s %9s %9d %8s" % (name, "SurfaceReconstruction", "%.3f" % srf_time
            if srf_time else "> %d" % budget, cloud.GetNumberOfPoints(), "%.1fx" % (srf_time / ours)
            if srf_time else "> %.0fx" % (budget / ours)))
        small = six_views(surface, 128)
        small.Update()
        small_tri = vtkPiImageTriangulator()
        small_tri.SetInputData(small.GetOutput())
        small_time = median_time(small_tri)
        srf_time, srf_mesh = reconstruction(small.GetOutput(), 10 * budget)
        print("%-12s %-22s %9.3f %9d %9s %11.2e %11.2e %11.2e %11.2e %11.2e" % ((name,
            "  128²: ImageTriangulator", small_time, small_tri.GetOutput().GetNumberOfPoints(), "1") +
            accuracy(surface, small_tri.GetOutput(), size) +
            surface_to_mesh(exact, small_tri.GetOutput(), size)))
        if srf_mesh is not None:
            print("%-12s %-22s %9.3f %9d %8.1fx %11.2e %11.2e %11.2e %11.2e %11.2e" % ((name,
                "  128²: SurfaceReconstr.", srf_time, srf_mesh.GetNumberOfPoints(),
                srf_time / small_time) + accuracy(surface, srf_mesh, size) +
                surface_to_mesh(exact, srf_mesh, size)))


if __name__ == "__main__":
    main()
