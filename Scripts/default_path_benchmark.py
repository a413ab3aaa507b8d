"""The default path: Pi Surface and the model reader as a ParaView user meets them.

    pvpython default_path_benchmark.py MODELS_DIR [RESOLUTION]    (./run bench; 255)

For the ten spheres, the table and the cup in a cube about the model's bounds at
RESOLUTION cells per side (255: a 256^3 grid), STDThread backend, measured side by side in one run (best of 5,
taking turns; see benchmark.py): a new proxy each time, updated as ParaView's Show and
UpdatePipeline update it (every output port through the server manager):
  defaults      Pi Surface (the model as JSON text) and Pi Surface Model Reader at
                their defaults: GeneratePrimitives on, the Primitives port computed
                when shown (PrimitivesOnDemand, vtkPiSIOnDemandSourceProxy), so port 0
  eager         the same with PrimitivesOnDemand off: both ports on every update
  no primitives GeneratePrimitives off
  re-executed   one proxy at its defaults, made once, updated again after each change of
                its Bounds (moved by a millionth of the box and back: what Apply after
                an edit costs, without the proxy's creation)
  VTK           vtkSampleFunction over vtkPiSurface + vtkFlyingEdges3D with its normals
                on the same grid (the pipeline a user would otherwise write; its objects
                are made once, so it compares with "re-executed")
"""
import os
import sys
import tempfile

from benchmark import best_of, load, ten_spheres
from paraview.simple import Delete, PiSurface, PiSurfaceModelReader
from pisurfaces import vtkPiFlyingEdges
from vtkmodules.vtkCommonCore import vtkSMPTools
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D
from vtkmodules.vtkImagingHybrid import vtkSampleFunction


def timed_proxy(make, **properties):
    """A function that makes the proxy, updates it, and returns its port-0 cells."""
    def run():
        proxy = make(**properties)
        proxy.UpdatePipeline()
        cells = proxy.GetClientSideObject().GetOutputDataObject(0).GetNumberOfCells()
        Delete(proxy)
        return cells
    return run


def timed_update(proxy, bounds):
    """A function that moves the proxy's Bounds a little, updates it, and returns its
    port-0 cells: the proxy re-executes each time, as after an edit and Apply."""
    size = max(bounds[2 * k + 1] - bounds[2 * k] for k in range(3))
    state = {"moved": False}

    def run():
        shift = 1e-6 * size if not state["moved"] else 0.0
        state["moved"] = not state["moved"]
        proxy.Bounds = [b + shift for b in bounds]
        proxy.UpdatePipeline()
        return proxy.GetClientSideObject().GetOutputDataObject(0).GetNumberOfCells()
    return run


def main():
    models = sys.argv[1]
    resolution = int(sys.argv[2]) if len(sys.argv) > 2 else 255
    vtkSMPTools.SetBackend("STDThread")
    spheres = ten_spheres()
    spheres_file = os.path.join(tempfile.mkdtemp(), "ten_spheres.pisurf")
    with open(spheres_file, "w") as f:
        f.write(spheres.GetModelJSON())
    cases = [("10 spheres", spheres, spheres_file)]
    for name, stem in (("table", "table"), ("cup", "cup_a1.0")):
        path = os.path.join(models, stem + ".pisurf")
        cases.append((name, load(path), path))
    print("Resolution %d, STDThread, load average %.2f, %d cores"
          % (resolution, os.getloadavg()[0], os.cpu_count()))
    print("| model | grid | source | defaults | eager (both ports) | no primitives | "
          "defaults / no primitives | re-executed | SampleFunction+FlyingEdges3D | "
          "VTK / defaults | VTK / re-executed |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for name, surface, path in cases:
        box = [0.0] * 6
        surface.GetModelBounds(box)
        # A cube about the model's bounds: RESOLUTION + 1 points on every axis (256^3).
        half = max(box[2 * k + 1] - box[2 * k] for k in range(3)) / 2
        bounds = []
        for k in range(3):
            middle = (box[2 * k] + box[2 * k + 1]) / 2
            bounds += [middle - half, middle + half]
        dims, spacing = [0, 0, 0], [0.0, 0.0, 0.0]
        vtkPiFlyingEdges().ComputeGrid(bounds, resolution, dims, spacing)
        sample = vtkSampleFunction()
        sample.SetImplicitFunction(surface)
        sample.SetModelBounds(bounds)
        sample.SetSampleDimensions(dims)
        sample.ComputeNormalsOff()
        contour = vtkFlyingEdges3D()
        contour.SetInputConnection(sample.GetOutputPort())
        contour.SetValue(0, 0.0)
        contour.ComputeNormalsOn()

        def vtk_mesh():
            sample.Modified()
            contour.Update()
            return contour.GetOutput().GetNumberOfCells()

        text = surface.GetModelJSON()
        sources = (
            ("Pi Surface", PiSurface, dict(Model=text)),
            ("model reader", PiSurfaceModelReader, dict(FileName=path)),
        )
        for label, make, given in sources:
            common = dict(given, Bounds=bounds, Resolution=resolution)
            kept = make(**common)
            kept.UpdatePipeline()
            (t_def, c_def), (t_eager, c_eager), (t_off, c_off), (t_re, c_re), \
                (t_vtk, c_vtk) = best_of([
                    timed_proxy(make, **common),
                    timed_proxy(make, PrimitivesOnDemand=0, **common),
                    timed_proxy(make, GeneratePrimitives=0, **common),
                    timed_update(kept, bounds),
                    vtk_mesh])
            Delete(kept)
            assert c_def == c_eager == c_off, (c_def, c_eager, c_off)
            print("| %s | %dx%dx%d | %s | %.3f s | %.3f s | %.3f s | %.2fx | %.3f s | %.3f s "
                  "| %.1fx | %.1fx |"
                  % (name, dims[0], dims[1], dims[2], label, t_def, t_eager, t_off,
                     t_def / t_off, t_re, t_vtk, t_vtk / t_def, t_vtk / t_re))


if __name__ == "__main__":
    main()
