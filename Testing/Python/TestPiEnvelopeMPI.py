"""Run with `mpiexec -n 4 pvbatch TestPiEnvelopeMPI.py`: the outer envelope flooded slab by
slab. Each rank classifies and samples only its slab (and one block layer on each side),
and the ranks flood the outside region together, handing each other the reached points
of the planes their slabs share. The cup's cavity is reached only through its opening at
the top of the grid, so on four ranks the lower slabs learn it from the ranks above (two
rounds of exchanges); formic acid's two interior shells must be left out on every rank.
The union of the ranks' meshes must be the serial mesh: the same triangles and area."""
import os

from pitesting import area_and_triangles, check, finish, ranks_area_and_triangles, serial_model_mesh

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from vtkmodules.vtkFiltersCore import vtkPolyDataConnectivityFilter

ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
check(ranks == 4, "running on 4 ranks (got %d)" % ranks)

models = os.environ["PISURF_MODELS_DIR"]
for name, components in (("cup_a1.0", 1), ("formic_acid", 1)):
    path = os.path.join(models, name + ".pisurf")
    serial = serial_model_mesh(path, 96)
    serial_area, serial_cells = area_and_triangles(serial.GetOutput())
    # (What the envelope leaves: the outer sheet alone.)
    connectivity = vtkPolyDataConnectivityFilter()
    connectivity.SetInputData(serial.GetOutput())
    connectivity.SetExtractionModeToAllRegions()
    connectivity.Update()
    check(connectivity.GetNumberOfExtractedRegions() == components,
          "%s: the serial mesh has %d component(s) (got %d)"
          % (name, components, connectivity.GetNumberOfExtractedRegions()))

    reader = PiSurfaceModelReader(FileName=path, Resolution=96)
    area, cells = ranks_area_and_triangles(reader)
    check(abs(area - serial_area) <= 1e-9 * serial_area,
          "%s: area %.12g on 4 ranks, %.12g serial" % (name, area, serial_area))
    check(cells == serial_cells, "%s: %d triangles on 4 ranks, %d serial" % (name, cells, serial_cells))
    # With the envelope off every sheet is kept: formic acid's shells come back (the
    # same on 4 ranks as serially).
    serial.SetOuterEnvelope(False)
    serial.Update()
    reader.OuterEnvelope = 0
    reader.UpdatePipeline()
    cells_all = reader.GetDataInformation().GetNumberOfCells()
    check(cells_all == serial.GetOutput().GetNumberOfCells(),
          "%s without the envelope: %d triangles on 4 ranks, %d serial"
          % (name, cells_all, serial.GetOutput().GetNumberOfCells()))
    if name == "formic_acid":
        check(cells_all > cells, "formic acid: the envelope leaves out the interior shells "
              "(%d triangles with it, %d without)" % (cells, cells_all))
    ids = ProcessIdScalars(Input=reader)
    ids.UpdatePipeline()
    r = ids.GetDataInformation().GetPointDataInformation().GetArrayInformation("ProcessId").GetComponentRange(0)
    check(r[0] == 0 and r[1] == 3, "%s: the ranks 0 to 3 produced triangles (ProcessId range %s)" % (name, r))
    print("%s: area %.12g (serial %.12g), %d triangles" % (name, area, serial_area, cells))

finish(exit_on_success=False)
