"""Shared helpers of the Python tests: record failures, report them at the end."""
import sys

failures = 0


def check(cond, what):
    """Records a failure (and prints `what`) unless `cond` holds."""
    global failures
    if not cond:
        failures += 1
        print("FAILED:", what)


def finish(exit_on_success=True):
    """Prints the count; exits 1 on failure. pvbatch under MPI must end normally on
    success (exit_on_success=False) so that it finalizes MPI on every rank."""
    print("%d failures" % failures)
    if failures:
        sys.exit(1)
    if exit_on_success:
        sys.exit(0)


def area_and_triangles(polydata):
    """The surface area (vtkMassProperties) and the cell count of a serial mesh."""
    from vtkmodules.vtkFiltersCore import vtkMassProperties
    mass = vtkMassProperties()
    mass.SetInputData(polydata)
    mass.Update()
    return mass.GetSurfaceArea(), polydata.GetNumberOfCells()


def ranks_area_and_triangles(proxy):
    """The area (Integrate Variables) and the cell count of a proxy's output summed over
    the MPI ranks (paraview.simple)."""
    from paraview import servermanager
    from paraview.simple import IntegrateVariables
    integrated = servermanager.Fetch(IntegrateVariables(Input=proxy))
    return (integrated.GetCellData().GetArray("Area").GetValue(0),
            proxy.GetDataInformation().GetNumberOfCells())


def serial_model_mesh(path, resolution, method=0):
    """A vtkPiSurfaceModelReader of `path` at `resolution` (Method `method`), updated in
    this process alone: the serial reference of the MPI tests."""
    from pisurfaces import vtkPiSurfaceModelReader
    reader = vtkPiSurfaceModelReader()
    reader.SetFileName(path)
    reader.SetResolution(resolution)
    reader.SetMethod(method)
    reader.Update()
    return reader


def exact_view_of_cup(width, height):
    """The cup (coarse model reader) drawn by a vtkPiExactSurfaceMapper in an offscreen
    VTK window of width x height, the camera reset on it: (mapper, renderer, window)."""
    import os
    from pisurfaces import vtkPiExactSurfaceMapper, vtkPiSurfaceModelReader
    from vtkmodules.vtkRenderingCore import vtkActor, vtkRenderer, vtkRenderWindow
    import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
    reader = vtkPiSurfaceModelReader()
    reader.SetFileName(os.path.join(os.environ["PISURF_MODELS_DIR"], "cup_a1.0.pisurf"))
    reader.SetResolution(8)
    mapper = vtkPiExactSurfaceMapper()
    mapper.SetInputConnection(reader.GetOutputPort())
    actor = vtkActor()
    actor.SetMapper(mapper)
    renderer = vtkRenderer()
    renderer.AddActor(actor)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(width, height)
    window.AddRenderer(renderer)
    renderer.ResetCamera()
    return mapper, renderer, window
