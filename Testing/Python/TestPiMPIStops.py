"""Run with `mpiexec -n 2 pvbatch --symmetric TestPiMPIStops.py`: with the outer envelope,
the ranks of an MPI run flood it together, so a rank that cannot go on must not leave
the others waiting. 300 small spheres in the upper half of the bounds: the upper rank's
rows exceed a MaximumNumberOfSamples that the lower rank's fit, so the upper rank
reports the cap and the lower one stops too, saying why, and neither hangs (the test's
timeout would catch that). With a cap both fit, both mesh."""
import array
import random

from pitesting import check, finish

from pisurfaces import vtkPiFlyingEdges, vtkPiPrimitive, vtkPiSurface
from vtkmodules.vtkCommonCore import VTK_STRING, vtkCommand
from vtkmodules.util.misc import calldata_type
from vtkmodules.vtkParallelCore import vtkCommunicator, vtkMultiProcessController

controller = vtkMultiProcessController.GetGlobalController()
rank = controller.GetLocalProcessId()
ranks = controller.GetNumberOfProcesses()
check(ranks == 2, "running on 2 ranks (got %d)" % ranks)

rng = random.Random(3)
surface = vtkPiSurface()
for i in range(300):
    p = vtkPiPrimitive()
    p.SetCenter(rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(1, 4))
    p.SetRadius(0.3)
    surface.AddFactor(p)
surface.SetBlending(0.01)


def mesh(cap):
    errors = []

    @calldata_type(VTK_STRING)
    def on_error(obj, event, message):
        errors.append(message)

    mesher = vtkPiFlyingEdges()
    mesher.AddObserver(vtkCommand.ErrorEvent, on_error)
    mesher.SetPiSurface(surface)
    mesher.SetBounds(-5, 5, -5, 5, -5, 5)
    mesher.SetResolution(64)
    mesher.SetMaximumNumberOfSamples(cap)
    ok = mesher.UpdatePiece(rank, ranks, 0)
    return ok, mesher.GetOutput().GetNumberOfCells(), errors


# The rows of the upper rank's slab need 14.7 MiB of coefficients, the lower rank's 4.0 MiB.
ok, cells, errors = mesh(1000000)
check(not ok, "rank %d: the mesh fails on every rank when one rank is over the cap" % rank)
# The upper rank names the cap; the lower one, whose rows fit, says why it stops.
expected = "the limit is" if rank == 1 else "Another piece of the mesh failed"
check(any(expected in e for e in errors), "rank %d: an error saying '%s' (got %s)" % (rank, expected, errors))
check(cells == 0, "rank %d: no partial mesh (%d triangles)" % (rank, cells))

ok, cells, errors = mesh(100000000)
sent = array.array('d', [float(cells)])
summed = array.array('d', [0.0])
controller.AllReduce(sent, summed, 1, vtkCommunicator.SUM_OP)
check(ok and not errors, "rank %d: with room for both, both mesh (%s)" % (rank, errors))
check(summed[0] > 30000, "the union has the spheres' triangles (%d)" % summed[0])
print("rank %d: %d triangles of %d" % (rank, cells, summed[0]))
finish(exit_on_success=False)
