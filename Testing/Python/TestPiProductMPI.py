"""Run with `mpiexec -n 2 pvbatch TestPiProductMPI.py`: a Pi Product of Pi Primitive
sources in ParaView's MPI mode. Each rank's inputs are pieces that all carry the
primitive's model; each rank meshes its own slab of the product, and the union has the
serial product's area and triangle count."""
from pitesting import area_and_triangles, check, finish, ranks_area_and_triangles

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from pisurfaces import vtkPiPrimitiveSource, vtkPiProduct

ranks = servermanager.vtkProcessModule.GetProcessModule().GetNumberOfLocalPartitions()
check(ranks == 2, "running on 2 ranks (got %d)" % ranks)

# The serial reference, in this process alone: a torus and a negated sphere on it.
torus = vtkPiPrimitiveSource()
torus.SetType(3)
torus.SetMajorRadius(1)
torus.SetMinorRadius(0.35)
dent = vtkPiPrimitiveSource()
dent.SetCenter(1, 0, 0.3)
dent.SetRadius(0.3)
dent.SetNegate(True)
serial = vtkPiProduct()
serial.AddInputConnection(torus.GetOutputPort())
serial.AddInputConnection(dent.GetOutputPort())
serial.SetBlending(0.02)
serial.SetResolution(96)
serial.Update()
serial_area, serial_cells = area_and_triangles(serial.GetOutput())

a = PiPrimitive(Type="Torus", MajorRadius=1, MinorRadius=0.35)
b = PiPrimitive(Center=[1, 0, 0.3], Radius=0.3, Negate=1)
product = PiProduct(Input=[a, b], Blending=0.02, Resolution=96)
area, cells = ranks_area_and_triangles(product)
check(serial_cells > 1000, "serial product: %d triangles" % serial_cells)
check(abs(area - serial_area) <= 1e-6 * serial_area,
      "product: area %.12g on 2 ranks, %.12g serial" % (area, serial_area))
check(cells == serial_cells, "product: %d triangles on 2 ranks, %d serial" % (cells, serial_cells))
ids = ProcessIdScalars(Input=product)
ids.UpdatePipeline()
r = ids.GetDataInformation().GetPointDataInformation().GetArrayInformation("ProcessId").GetComponentRange(0)
check(r[0] == 0 and r[1] == 1, "both ranks produced triangles (ProcessId range %s)" % (r,))
print("product: area %.12g (serial %.12g), %d triangles" % (area, serial_area, cells))

finish(exit_on_success=False)
