"""Run with `mpiexec -n 2 pvbatch TestPiMPI.py`: each rank meshes its own slab, and the
union has the serial mesh's area and triangle count."""
import os

from pitesting import area_and_triangles, check, finish, ranks_area_and_triangles, serial_model_mesh

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager



ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
check(ranks == 2, "running on 2 ranks (got %d)" % ranks)

models = os.environ["PISURF_MODELS_DIR"]
for name in ("formic_acid", "cup_a1.0"):
    path = os.path.join(models, name + ".pisurf")
    # The serial reference, in this process alone.
    serial = serial_model_mesh(path, 96)
    serial_area, serial_cells = area_and_triangles(serial.GetOutput())

    reader = PiSurfaceModelReader(FileName=path, Resolution=96)
    area, cells = ranks_area_and_triangles(reader)
    check(abs(area - serial_area) <= 1e-6 * serial_area,
          "%s: area %.12g on 2 ranks, %.12g serial" % (name, area, serial_area))
    check(cells == serial_cells, "%s: %d triangles on 2 ranks, %d serial" % (name, cells, serial_cells))
    ids = ProcessIdScalars(Input=reader)
    ids.UpdatePipeline()
    r = ids.GetDataInformation().GetPointDataInformation().GetArrayInformation("ProcessId").GetComponentRange(0)
    check(r[0] == 0 and r[1] == 1, "%s: both ranks produced triangles (ProcessId range %s)" % (name, r))
    print("%s: area %.12g (serial %.12g), %d triangles" % (name, area, serial_area, cells))

# Method = Ray Cast Triangulation: the ray lattice is not split, the first piece holds the
# whole mesh and the other is empty, so the union is the serial mesh once.
path = os.path.join(models, "cup_a1.0.pisurf")
serial = serial_model_mesh(path, 64, method=1)
serial_cells = serial.GetOutput().GetNumberOfCells()
ray = PiSurfaceModelReader(FileName=path, Resolution=64, Method="Ray Cast Triangulation")
ray.UpdatePipeline()
cells = ray.GetDataInformation().GetNumberOfCells()
check(serial_cells > 1000 and cells == serial_cells,
      "ray cast triangulation: %d triangles on 2 ranks, %d serial" % (cells, serial_cells))

# Pi Sample Function: each rank samples its own sub-extent (row by row, restricted about
# the whole grid's rows, so a piece has the whole grid's bits). The pieces cover the grid:
# the cell count and the integral of F over the box equal the serial ones.
import numpy as np
from pisurfaces import vtkPiSampleFunction, vtkPiSurface
from vtkmodules.util.numpy_support import vtk_to_numpy

cup = vtkPiSurface()
cup.LoadModel(os.path.join(models, "cup_a1.0.pisurf"))
serial = vtkPiSampleFunction()
serial.SetPiSurface(cup)
serial.SetSampleDimensions(60, 48, 36)
serial.Update()
# The integral of the trilinear interpolant, cell by cell, is the trapezoid rule on each
# axis (vtkIntegrateAttributes would talk to the other rank: this part runs on one).
grid = serial.GetOutput()
sx, sy, sz = grid.GetSpacing()
F = vtk_to_numpy(grid.GetPointData().GetScalars()).reshape(36, 48, 60)
serial_integral = np.trapz(np.trapz(np.trapz(F, dx=sx, axis=2), dx=sy, axis=1), dx=sz)
serial_cells = serial.GetOutput().GetNumberOfCells()

sample = PiSampleFunction(Input=PiSurfaceModelReader(FileName=os.path.join(models, "cup_a1.0.pisurf"),
                                                     Resolution=24),
                          SampleDimensions=[60, 48, 36])
integrated = servermanager.Fetch(IntegrateVariables(Input=sample))
integral = integrated.GetPointData().GetArray("F").GetValue(0)
cells = sample.GetDataInformation().GetNumberOfCells()
check(cells == serial_cells, "sampler: %d cells on 2 ranks, %d serial" % (cells, serial_cells))
check(abs(integral - serial_integral) <= 1e-9 * abs(serial_integral),
      "sampler: integral of F %.12g on 2 ranks, %.12g serial" % (integral, serial_integral))
ids = ProcessIdScalars(Input=sample)
ids.UpdatePipeline()
r = ids.GetDataInformation().GetPointDataInformation().GetArrayInformation("ProcessId").GetComponentRange(0)
check(r[0] == 0 and r[1] == 1, "sampler: both ranks sampled (ProcessId range %s)" % (r,))
print("sampler: integral of F %.12g (serial %.12g), %d cells" % (integral, serial_integral, cells))

finish(exit_on_success=False)
