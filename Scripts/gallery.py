"""Renders the gallery of the paper's figures (Raposo and Gomes, Pi-surfaces) to PNG files
and an index.html: the primitives in colour under the translucent grey Pi-surface.

    pvbatch gallery.py MODELS_DIR OUT_DIR        (./run demo does this)
"""
import html
import json
import os
import sys

from pisurfaces import vtkPiSurfaceModelReader
from vtkmodules.vtkCommonCore import vtkLookupTable
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (
    vtkActor,
    vtkPolyDataMapper,
    vtkRenderWindow,
    vtkRenderer,
    vtkWindowToImageFilter,
)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the OpenGL back end)

# The figures, their views and styles: Testing/Data/gallery.json (shared with the
# C++ image tests, so the tests check exactly what the gallery shows).
COLOURS = [
    (0.85, 0.22, 0.18), (0.22, 0.42, 0.85), (0.25, 0.7, 0.3), (0.95, 0.6, 0.15),
    (0.6, 0.3, 0.75), (0.15, 0.7, 0.7), (0.9, 0.8, 0.2), (0.8, 0.4, 0.6),
]


def save_png(window, path):
    """Writes what the (rendered) window shows to the PNG file `path`."""
    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    writer = vtkPNGWriter()
    writer.SetInputConnection(grab.GetOutputPort())
    writer.SetFileName(path)
    writer.Write()


def render(model_path, png_path, direction, view_up, inside, size=(640, 480)):
    reader = vtkPiSurfaceModelReader()  # port 0: the Pi-surface, port 1: its primitives
    reader.SetFileName(model_path)
    reader.SetResolution(160)
    reader.Update()
    surface = reader.GetPiSurface()
    bounds = [0.0] * 6
    if not surface.GetModelBounds(bounds):
        raise RuntimeError("no bounds for " + model_path)

    renderer = vtkRenderer()
    renderer.SetBackground(1, 1, 1)
    renderer.SetUseDepthPeeling(True)
    colours = vtkLookupTable()
    n = surface.GetNumberOfFactors()
    colours.SetNumberOfTableValues(n)
    colours.SetTableRange(0, max(n - 1, 1))
    for i in range(n):
        colours.SetTableValue(i, *COLOURS[i % len(COLOURS)], 1.0)
    colours.Build()
    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(reader.GetOutputPort(1))
    mapper.SetScalarModeToUsePointFieldData()
    mapper.SelectColorArray("Factor")
    mapper.SetLookupTable(colours)
    mapper.UseLookupTableScalarRangeOn()
    # Primitives and Pi-surface often coincide: keep the primitives just behind.
    mapper.SetRelativeCoincidentTopologyPolygonOffsetParameters(2, 2)
    primitives = vtkActor()
    primitives.SetMapper(mapper)
    primitives.GetProperty().SetOpacity(0.35 if inside else 1.0)
    renderer.AddActor(primitives)

    mapper = vtkPolyDataMapper()
    mapper.SetInputConnection(reader.GetOutputPort())
    mapper.ScalarVisibilityOff()
    pi = vtkActor()
    pi.SetMapper(mapper)
    pi.GetProperty().SetColor(0.62, 0.62, 0.62)
    pi.GetProperty().SetOpacity(1.0 if inside else 0.42)
    pi.GetProperty().SetSpecular(0.3)
    renderer.AddActor(pi)

    window = vtkRenderWindow()
    window.SetOffScreenRendering(1)
    window.SetMultiSamples(0)
    window.SetSize(*size)
    window.AddRenderer(renderer)
    camera = renderer.GetActiveCamera()
    centre = [0.5 * (bounds[2 * k] + bounds[2 * k + 1]) for k in range(3)]
    camera.SetFocalPoint(centre)
    camera.SetPosition([centre[k] + direction[k] for k in range(3)])
    camera.SetViewUp(view_up)
    renderer.ResetCamera(reader.GetOutput().GetBounds())
    camera.Zoom(1.15)
    window.Render()
    save_png(window, png_path)
    return reader.GetOutput().GetNumberOfCells()


def main(models, out):
    os.makedirs(out, exist_ok=True)
    cards = []
    with open(os.path.join(os.path.dirname(models.rstrip("/")), "gallery.json")) as f:
        figures = json.load(f)["figures"]
    for figure in figures:
        name, title = figure["model"], figure["title"]
        path = os.path.join(models, name + ".pisurf")
        if not os.path.exists(path):
            print("missing model", path)
            continue
        png = name + ".png"
        triangles = render(path, os.path.join(out, png), figure["direction"], figure["view_up"],
                           figure["pi_surface_inside"])
        with open(path) as f:
            model = json.load(f)
        terms = []
        for p in model["primitives"]:
            if p["type"] == "polynomial":
                terms.append("(" + p["expression"] + ")")
            elif p["type"] == "sphere":
                c = p.get("center", [0, 0, 0])
                terms.append("((x-%g)^2+(y-%g)^2+(z-%g)^2-%g^2)" % (c[0], c[1], c[2], p["radius"]))
            else:
                terms.append(p["type"])
        equation = " · ".join(terms) + " − %g" % model["blending"]
        params = model.get("parameters")
        if params:
            equation += "   with " + ", ".join("%s = %g" % kv for kv in params.items())
        cards.append((png, title, equation, model.get("description", ""), triangles))
        print("%-28s %7d triangles -> %s" % (name, triangles, os.path.join(out, png)))

    with open(os.path.join(out, "index.html"), "w") as f:
        f.write("<!DOCTYPE html><html><head><meta charset='utf-8'><title>PiSurfaces gallery</title>"
                "<style>body{font-family:sans-serif;margin:2em}div.g{display:flex;flex-wrap:wrap;gap:1em}"
                "figure{width:420px;margin:0}img{width:420px}figcaption{font-size:0.85em}"
                "code{font-size:0.8em;word-break:break-all}</style></head><body>"
                "<h1>Π-surfaces: the paper's figures</h1><p>F(x,y,z) = Π f<sub>i</sub> − r. "
                "Primitives in colour, the Π-surface in translucent grey.</p><div class='g'>")
        for png, title, equation, description, triangles in cards:
            f.write("<figure><img src='%s' alt='%s'><figcaption><b>%s</b><br><code>F = %s</code>"
                    "<br>%s<br><i>%d triangles</i></figcaption></figure>"
                    % (png, html.escape(title), html.escape(title), html.escape(equation),
                       html.escape(description), triangles))
        f.write("</div><p><a href='molecules.html'>Molecules: Blinn's Σ-surface against the "
                "Π-surfaces</a> (written by molecule_gallery.py)</p></body></html>\n")
    return 0 if len(cards) == len(figures) else 1


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
