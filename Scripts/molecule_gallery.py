"""Sigma versus Pi on real molecules: Blinn's Gaussian Sigma-surface (vtkGaussianSplatter +
vtkFlyingEdges3D, what a VTK user would build) beside the molecular Pi-surfaces (Global:
the paper's product over all atoms; Local: the localized factors), for one drug (diazepam,
from chemical-structures-data) and one protein (ubiquitin, 1ubq, from freesasa's test data).

    pvbatch molecule_gallery.py OUT_DIR        (./run demo does this)
"""
import math
import os
import sys

from pisurfaces import vtkPiMoleculeReader, vtkPiMoleculeSurface
from vtkmodules.vtkCommonCore import vtkLookupTable, vtkPoints
from vtkmodules.vtkCommonDataModel import vtkPolyData
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D
from vtkmodules.vtkImagingHybrid import vtkGaussianSplatter
from vtkmodules.vtkIOChemistry import vtkCMLMoleculeReader
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (
    vtkActor,
    vtkPolyDataMapper,
    vtkRenderWindow,
    vtkRenderer,
    vtkTextActor,
    vtkWindowToImageFilter,
)
import vtkmodules.vtkRenderingFreeType  # noqa: F401  (text)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the OpenGL back end)

# exp(-5 d^2 / 3.5^2) = 0.3 at d = 1.72 A: a lone atom gets about a carbon's vdW radius.
LEVEL = 0.3

# CPK-like colours by atomic number (H white, C grey, N blue, O red, S yellow).
CPK = {1: (0.95, 0.95, 0.95), 6: (0.55, 0.55, 0.55), 7: (0.2, 0.35, 0.95),
       8: (0.9, 0.15, 0.1), 9: (0.5, 0.9, 0.3), 16: (0.95, 0.85, 0.2), 17: (0.2, 0.85, 0.2)}


def sigma_surface(molecule, spacing):
    """Gaussians of 3.5 A footprint at the atoms, summed, contoured at LEVEL."""
    points = vtkPoints()
    for i in range(molecule.GetNumberOfAtoms()):
        points.InsertNextPoint(molecule.GetAtom(i).GetPosition())
    cloud = vtkPolyData()
    cloud.SetPoints(points)
    b = list(points.GetBounds())
    for a in range(3):
        b[2 * a] -= 4.0
        b[2 * a + 1] += 4.0
    splat = vtkGaussianSplatter()
    splat.SetInputData(cloud)
    splat.SetModelBounds(b)
    splat.SetSampleDimensions([int(math.ceil((b[2 * a + 1] - b[2 * a]) / spacing)) + 1
                               for a in range(3)])
    splat.SetRadius(3.5 / max(b[1] - b[0], b[3] - b[2], b[5] - b[4]))
    splat.SetExponentFactor(-5.0)
    splat.ScalarWarpingOff()
    splat.NormalWarpingOff()
    splat.CappingOff()
    splat.SetAccumulationModeToSum()  # Blinn: the sum of the Gaussians
    contour = vtkFlyingEdges3D()
    contour.SetInputConnection(splat.GetOutputPort())
    contour.SetValue(0, LEVEL)
    contour.ComputeNormalsOn()
    contour.Update()
    return contour.GetOutput()


def pi_surface(molecule, mode, spacing):
    f = vtkPiMoleculeSurface()
    f.SetInputData(molecule)
    f.SetMode(mode)
    f.SetSpacing(spacing)
    f.Update()
    return f.GetOutput()


def panel(window, mesh, viewport, title, camera=None):
    renderer = vtkRenderer()
    renderer.SetViewport(*viewport)
    renderer.SetBackground(1, 1, 1)
    mapper = vtkPolyDataMapper()
    mapper.SetInputData(mesh)
    actor = vtkActor()
    actor.SetMapper(mapper)
    if mesh.GetPointData().GetArray('AtomicNumber') is not None:
        lut = vtkLookupTable()
        lut.SetNumberOfTableValues(18)
        lut.SetTableRange(0, 17)
        for z in range(18):
            lut.SetTableValue(z, *CPK.get(z, (0.8, 0.5, 0.8)), 1.0)
        mapper.SetLookupTable(lut)
        mapper.SetScalarModeToUsePointFieldData()
        mapper.SelectColorArray('AtomicNumber')
        mapper.SetScalarRange(0, 17)
        mapper.ScalarVisibilityOn()
    else:
        mapper.ScalarVisibilityOff()
        actor.GetProperty().SetColor(0.55, 0.7, 0.9)
    actor.GetProperty().SetSpecular(0.3)
    actor.GetProperty().SetSpecularPower(30)
    renderer.AddActor(actor)
    text = vtkTextActor()
    text.SetInput(title)
    text.GetTextProperty().SetColor(0, 0, 0)
    text.GetTextProperty().SetFontSize(18)
    text.SetPosition(10, 10)
    renderer.AddViewProp(text)
    window.AddRenderer(renderer)
    if camera is None:
        renderer.ResetCamera()
        renderer.GetActiveCamera().Zoom(1.3)
    else:
        renderer.SetActiveCamera(camera)
    return renderer.GetActiveCamera()


def figure(path, panels, size, zoom=1.0):
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(*size)
    camera = None
    n = len(panels)
    for k, (mesh, title) in enumerate(panels):
        camera = panel(window, mesh, (k / n, 0, (k + 1) / n, 1), title, camera)
        if k == 0:
            camera.Zoom(zoom)
    window.Render()
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    grab.Update()
    writer = vtkPNGWriter()
    writer.SetFileName(path)
    writer.SetInputConnection(grab.GetOutputPort())
    writer.Write()
    print('wrote', path)


def main(out):
    os.makedirs(out, exist_ok=True)
    cml = vtkCMLMoleculeReader()
    cml.SetFileName('/usr/share/chemical-structures/drugs/diazepam.cml')
    cml.Update()
    drug = cml.GetOutput()
    figure(os.path.join(out, 'molecule_diazepam.png'),
           [(sigma_surface(drug, 0.1), 'Sigma: Gaussian splats'),
            (pi_surface(drug, 0, 0.1), 'Pi, Global (r = 1)')], (900, 450))
    reader = vtkPiMoleculeReader()
    reader.SetFileName('/usr/share/freesasa/test-data/1ubq.pdb')
    reader.Update()
    protein = reader.GetOutput()
    figure(os.path.join(out, 'molecule_1ubq.png'),
           [(sigma_surface(protein, 0.4), 'Sigma: Gaussian splats'),
            (pi_surface(protein, 0, 0.4), 'Pi, Global (r = 1)'),
            (pi_surface(protein, 1, 0.4), 'Pi, Local (2 A)')], (1200, 420))
    # Close up: Global hugs the spheres (every far atom multiplies the product), Local
    # keeps a visible fillet where neighbouring atoms meet.
    figure(os.path.join(out, 'molecule_1ubq_closeup.png'),
           [(pi_surface(protein, 0, 0.25), 'Pi, Global (r = 1)'),
            (pi_surface(protein, 1, 0.25), 'Pi, Local (2 A)')], (1000, 500), zoom=3.5)


if __name__ == '__main__':
    main(sys.argv[1] if len(sys.argv) > 1 else 'out/gallery')
