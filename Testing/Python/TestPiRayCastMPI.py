"""Run with `mpiexec -n 2 pvbatch TestPiRayCastMPI.py`: Pi Ray Cast and Image Based
Triangulation in ParaView's MPI mode. Each rank casts its own slab of image rows, so
the ranks' hits together are the serial hits (same pixels, same points, none twice);
the triangulation triangulates the whole cloud on each rank and keeps its share of
triangles, so the union is the serial mesh."""
import os

from pitesting import check, finish

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from pisurfaces import vtkPiImageTriangulator, vtkPiRayCaster, vtkPiSurfaceModelReader
from vtkmodules.vtkFiltersCore import vtkMassProperties

ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
check(ranks == 2, "running on 2 ranks (got %d)" % ranks)

W, H = 96, 80
path = os.path.join(os.environ["PISURF_MODELS_DIR"], "cup_a1.0.pisurf")


def hits_of(poly):
    """Each hit keyed by (view, i, j, hit index), with its point."""
    pd = poly.GetPointData()
    pixel, view, index = (pd.GetArray(n) for n in ("PixelIndex", "ViewIndex", "HitIndex"))
    hits = {}
    for k in range(poly.GetNumberOfPoints()):
        key = (int(view.GetValue(k)), int(pixel.GetComponent(k, 0)),
               int(pixel.GetComponent(k, 1)), int(index.GetValue(k)))
        check(key not in hits, "hit %s appears once" % (key,))
        hits[key] = poly.GetPoint(k)
    return hits


def both_ranks(proxy, what):
    ids = ProcessIdScalars(Input=proxy)
    ids.UpdatePipeline()
    r = ids.GetDataInformation().GetPointDataInformation().GetArrayInformation(
        "ProcessId").GetComponentRange(0)
    check(r[0] == 0 and r[1] == 1, "%s: both ranks have data (ProcessId range %s)" % (what, r))


# The serial reference, in this process alone.
reader = vtkPiSurfaceModelReader()
reader.SetFileName(path)
reader.SetResolution(48)
caster = vtkPiRayCaster()
caster.SetInputConnection(reader.GetOutputPort())
caster.SetViewMode(vtkPiRayCaster.SIX_AXIS_VIEWS)
caster.SetResolution(W, H)
triangulator = vtkPiImageTriangulator()
triangulator.SetInputConnection(caster.GetOutputPort())
triangulator.Update()
serial_hits = hits_of(caster.GetOutput())
serial_depth = caster.GetOutputDataObject(1).GetPointData().GetArray("Depth").GetRange()
mass = vtkMassProperties()
mass.SetInputData(triangulator.GetOutput())
mass.Update()
serial_area = mass.GetSurfaceArea()
serial_triangles = triangulator.GetOutput().GetNumberOfCells()
check(len(serial_hits) > 5000, "serial: %d hits" % len(serial_hits))

# On 2 ranks.
model = PiSurfaceModelReader(FileName=path, Resolution=48)
cast = PiRayCast(Input=model, ViewMode="Six Axis Views", Resolution=[W, H])
hits = hits_of(servermanager.Fetch(cast))
check(set(hits) == set(serial_hits),
      "the ranks' hits are the serial pixels and hits (%d vs %d; %d missing, %d extra)"
      % (len(hits), len(serial_hits), len(set(serial_hits) - set(hits)),
         len(set(hits) - set(serial_hits))))
worst = max((max(abs(a - b) for a, b in zip(hits[k], serial_hits[k]))
             for k in hits if k in serial_hits), default=0.0)
check(worst == 0.0, "the ranks' hit points equal the serial ones (largest difference %g)" % worst)
both_ranks(cast, "ray cast")

# The image port: row slabs of the whole image, the serial depth range.
image = cast.GetDataInformation(1)
check(tuple(image.GetExtent()) == (0, W - 1, 0, H - 1, 0, 5),
      "image: whole extent %s" % (image.GetExtent(),))
depth = image.GetPointDataInformation().GetArrayInformation("Depth").GetComponentRange(0)
check(tuple(depth) == tuple(serial_depth),
      "image: Depth range %s on 2 ranks, %s serial" % (depth, serial_depth))

mesh = ImageBasedTriangulation(Input=cast)
integrated = servermanager.Fetch(IntegrateVariables(Input=mesh))
area = integrated.GetCellData().GetArray("Area").GetValue(0)
triangles = mesh.GetDataInformation().GetNumberOfCells()
check(triangles == serial_triangles,
      "triangulation: %d triangles on 2 ranks, %d serial" % (triangles, serial_triangles))
check(abs(area - serial_area) <= 1e-9 * serial_area,
      "triangulation: area %.12g on 2 ranks, %.12g serial" % (area, serial_area))
both_ranks(mesh, "triangulation")
print("ray cast: %d hits; triangulation: %d triangles, area %.9g" % (len(hits), triangles, area))

finish(exit_on_success=False)
