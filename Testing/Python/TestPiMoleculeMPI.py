"""Run with `mpiexec -n 2 pvbatch TestPiMoleculeMPI.py`: Molecular Pi Surface in
ParaView's MPI mode. The molecule reader gives its atoms to the first piece only; the
filter asks every rank for the whole molecule and meshes the rank's slab of the grid.
The union has the serial mesh's triangles and area, and both ranks mesh (rank 1 used to
get no atoms and fail). Pi Ray Cast downstream (on the molecule's own field) gives the
serial hits."""
from pitesting import check, finish

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from pisurfaces import vtkPiMoleculeReader, vtkPiMoleculeSurface, vtkPiRayCaster

ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
check(ranks == 2, "running on 2 ranks (got %d)" % ranks)

path = "/usr/share/freesasa/test-data/1ubq.pdb"
for mode in ("Global", "Local"):
    # The serial reference, in this process alone.
    reader = vtkPiMoleculeReader()
    reader.SetFileName(path)
    serial = vtkPiMoleculeSurface()
    serial.SetInputConnection(reader.GetOutputPort())
    serial.SetSpacing(0.6)
    serial.SetMode(vtkPiMoleculeSurface.LOCAL if mode == "Local" else vtkPiMoleculeSurface.GLOBAL)
    serial.Update()
    serial_area = serial.GetOutput().GetFieldData().GetArray("SurfaceArea").GetValue(0)
    serial_triangles = serial.GetOutput().GetNumberOfCells()
    check(serial_triangles > 10000, "%s serial: %d triangles" % (mode, serial_triangles))

    surface = MolecularPiSurface(Input=PiMoleculeReader(FileName=path), Spacing=0.6, Mode=mode)
    integrated = servermanager.Fetch(IntegrateVariables(Input=surface))
    area = integrated.GetCellData().GetArray("Area").GetValue(0)
    triangles = surface.GetDataInformation().GetNumberOfCells()
    check(triangles == serial_triangles,
          "%s: %d triangles on 2 ranks, %d serial" % (mode, triangles, serial_triangles))
    check(abs(area - serial_area) <= 1e-9 * serial_area,
          "%s: area %.12g on 2 ranks, %.12g serial" % (mode, area, serial_area))
    ids = ProcessIdScalars(Input=surface)
    ids.UpdatePipeline()
    r = ids.GetDataInformation().GetPointDataInformation().GetArrayInformation(
        "ProcessId").GetComponentRange(0)
    check(r[0] == 0 and r[1] == 1, "%s: both ranks meshed (ProcessId range %s)" % (mode, r))
    print("%s: %d triangles, area %.9g (serial %.9g)" % (mode, triangles, area, serial_area))

    # Pi Ray Cast downstream, on the molecule's field: each rank casts its slab of rows;
    # together the serial hits.
    caster = vtkPiRayCaster()
    caster.SetInputConnection(serial.GetOutputPort())
    caster.SetViewMode(vtkPiRayCaster.SIX_AXIS_VIEWS)
    caster.SetResolution(40, 40)
    caster.Update()
    serial_hits = caster.GetOutput().GetNumberOfPoints()
    rays = PiRayCast(Input=surface, ViewMode="Six Axis Views", Resolution=[40, 40])
    rays.UpdatePipeline()
    hits = rays.GetDataInformation().GetNumberOfPoints()
    check(serial_hits > 1000 and hits == serial_hits,
          "%s: %d ray hits on 2 ranks, %d serial" % (mode, hits, serial_hits))
    print("%s: %d ray hits on 2 ranks, %d serial" % (mode, hits, serial_hits))

finish(exit_on_success=False)
