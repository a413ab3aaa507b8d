"""The picture of EdgeFlipRounds in the user guide: the cup's six axis views at 128 x 128
pixels triangulated without flips (left) and with the default one round (right), the
same close-up of the handle and the rim, shaded by |F|/|grad F| at the triangles'
centroids (how far each triangle leaves the surface).

    pvpython triangulation_flips_picture.py MODELS_DIR OUT.png
"""
import math
import sys

from gallery import save_png
from pisurfaces import vtkPiImageTriangulator
from triangulation_benchmark import distance, load_model, six_views
from vtkmodules.vtkCommonCore import vtkDoubleArray, vtkLookupTable
from vtkmodules.vtkRenderingAnnotation import vtkScalarBarActor
from vtkmodules.vtkRenderingCore import (vtkActor, vtkPolyDataMapper, vtkRenderWindow,
                                         vtkRenderer, vtkTextActor)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401
import vtkmodules.vtkRenderingFreeType  # noqa: F401


def main():
    models, out = sys.argv[1], sys.argv[2]
    surface, size = load_model(models, "cup_a1.0")
    caster = six_views(surface, 128)
    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetSize(1200, 600)
    lut = vtkLookupTable()
    lut.SetHueRange(0.66, 0.0)
    lut.SetTableRange(0, 4e-4)
    lut.Build()
    for k, rounds in enumerate((0, 1)):
        tri = vtkPiImageTriangulator()
        tri.SetInputConnection(caster.GetOutputPort())
        tri.SetEdgeFlipRounds(rounds)
        tri.Update()
        mesh = tri.GetOutput()
        error = vtkDoubleArray()
        error.SetName("CentroidError")
        total = 0.0
        for c in range(mesh.GetNumberOfCells()):
            ids = mesh.GetCell(c).GetPointIds()
            q = [sum(mesh.GetPoint(ids.GetId(v))[a] for v in range(3)) / 3 for a in range(3)]
            d = distance(surface, q) / size
            error.InsertNextValue(d)
            total += d * d
        mesh.GetCellData().SetScalars(error)
        mapper = vtkPolyDataMapper()
        mapper.SetInputData(mesh)
        mapper.SetLookupTable(lut)
        mapper.SetScalarModeToUseCellData()
        mapper.UseLookupTableScalarRangeOn()
        actor = vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().EdgeVisibilityOn()
        actor.GetProperty().SetEdgeColor(0.1, 0.1, 0.1)
        actor.GetProperty().SetLineWidth(1.0)
        renderer = vtkRenderer()
        renderer.SetViewport(0.5 * k, 0, 0.5 * (k + 1), 1)
        renderer.SetBackground(1, 1, 1)
        renderer.AddActor(actor)
        text = vtkTextActor()
        text.SetInput("EdgeFlipRounds %d: RMS centroid error %.2g of the model size"
                      % (rounds, math.sqrt(total / max(mesh.GetNumberOfCells(), 1))))
        text.GetTextProperty().SetColor(0, 0, 0)
        text.GetTextProperty().SetFontSize(17)
        text.GetTextProperty().SetBackgroundColor(1, 1, 1)
        text.GetTextProperty().SetBackgroundOpacity(0.85)
        text.SetPosition(12, 568)
        renderer.AddActor2D(text)
        camera = renderer.GetActiveCamera()
        camera.SetFocalPoint(1.55, -0.35, -0.55)
        camera.SetPosition(4.0, -3.2, 1.2)
        camera.SetViewUp(0, 0, 1)
        camera.SetViewAngle(30)
        if k == 1:
            bar = vtkScalarBarActor()
            bar.SetLookupTable(lut)
            bar.SetTitle("centroid's distance to F = 0, relative")
            bar.SetLabelFormat("%.0e")
            bar.DrawBackgroundOn()
            bar.GetBackgroundProperty().SetColor(1, 1, 1)
            bar.GetTitleTextProperty().ShadowOff()
            bar.GetLabelTextProperty().ShadowOff()
            bar.GetTitleTextProperty().ItalicOff()
            bar.GetLabelTextProperty().ItalicOff()
            bar.SetNumberOfLabels(3)
            bar.SetOrientationToHorizontal()
            bar.SetPosition(0.5, 0.02)
            bar.SetWidth(0.48)
            bar.SetHeight(0.12)
            bar.GetTitleTextProperty().SetColor(0, 0, 0)
            bar.GetLabelTextProperty().SetColor(0, 0, 0)
            renderer.AddActor2D(bar)
        renderer.ResetCameraClippingRange()
        window.AddRenderer(renderer)
    window.Render()
    save_png(window, out)


if __name__ == "__main__":
    main()
