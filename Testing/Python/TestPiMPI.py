"""Run with `mpiexec -n 2 pvbatch TestPiMPI.py`: each rank meshes its own slab, and the
union has the serial mesh's area and triangle count."""
import os

from pitesting import check, finish

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from pisurfaces import vtkPiSurfaceModelReader
from vtkmodules.vtkFiltersCore import vtkMassProperties



ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
check(ranks == 2, "running on 2 ranks (got %d)" % ranks)

models = os.environ["PISURF_MODELS_DIR"]
for name in ("formic_acid", "cup_a1.0"):
    path = os.path.join(models, name + ".pisurf")
    # The serial reference, in this process alone.
    serial = vtkPiSurfaceModelReader()
    serial.SetFileName(path)
    serial.SetResolution(96)
    serial.Update()
    mass = vtkMassProperties()
    mass.SetInputData(serial.GetOutput())
    mass.Update()
    serial_area = mass.GetSurfaceArea()
    serial_cells = serial.GetOutput().GetNumberOfCells()

    reader = PiSurfaceModelReader(FileName=path, Resolution=96)
    integrated = servermanager.Fetch(IntegrateVariables(Input=reader))
    area = integrated.GetCellData().GetArray("Area").GetValue(0)
    cells = reader.GetDataInformation().GetNumberOfCells()
    check(abs(area - serial_area) <= 1e-6 * serial_area,
          "%s: area %.12g on 2 ranks, %.12g serial" % (name, area, serial_area))
    check(cells == serial_cells, "%s: %d triangles on 2 ranks, %d serial" % (name, cells, serial_cells))
    ids = ProcessIdScalars(Input=reader)
    ids.UpdatePipeline()
    r = ids.GetDataInformation().GetPointDataInformation().GetArrayInformation("ProcessId").GetComponentRange(0)
    check(r[0] == 0 and r[1] == 1, "%s: both ranks produced triangles (ProcessId range %s)" % (name, r))
    print("%s: area %.12g (serial %.12g), %d triangles" % (name, area, serial_area, cells))

finish(exit_on_success=False)
