"""Renders the gallery of the paper's figures (Raposo and Gomes, Pi-surfaces) to PNG files
and an index.html: the primitives in colour under the translucent grey Pi-surface.

    pvbatch gallery.py MODELS_DIR OUT_DIR        (./run demo does this)
"""
import html
import json
import os
import sys

from pisurfaces import vtkPiFlyingEdges, vtkPiSurface, vtkPiSurfaceModelReader
from vtkmodules.vtkIOImage import vtkPNGWriter
from vtkmodules.vtkRenderingCore import (
    vtkActor,
    vtkPolyDataMapper,
    vtkRenderWindow,
    vtkRenderer,
    vtkWindowToImageFilter,
)
import vtkmodules.vtkRenderingOpenGL2  # noqa: F401  (the OpenGL back end)

# file, figure, view direction (from the focal point to the camera), view up.
# Where the Pi-surface lies inside its primitives (dents, concavities), it is drawn
# opaque and the primitives translucent instead (INSIDE).
INSIDE = {"depression", "concavity", "rounded_cube_sphere_1", "rounded_cube_sphere_2",
          "rounded_cube_sphere_3"}
FIGURES = [
    ("two_spheres_d0.8", "Fig. 1(a) two spheres, d = 0.8", (0.25, -1, 0.45), (0, 0, 1)),
    ("two_spheres_d0.9", "Fig. 1(b) two spheres, d = 0.9", (0.25, -1, 0.45), (0, 0, 1)),
    ("two_spheres_d1.0", "Fig. 1(c) two spheres, d = 1.0", (0.25, -1, 0.45), (0, 0, 1)),
    ("two_spheres_d1.1", "Fig. 1(d) two spheres, d = 1.1", (0.25, -1, 0.45), (0, 0, 1)),
    ("eggplant_r1", "Fig. 2(a) eggplant, r = 1", (0.25, -1, 0.45), (0, 0, 1)),
    ("eggplant_r0.25", "Fig. 2(b) eggplant, r = 0.25", (0.25, -1, 0.45), (0, 0, 1)),
    ("eggplant_r0.05", "Fig. 2(c) eggplant, r = 0.05", (0.25, -1, 0.45), (0, 0, 1)),
    ("crossed_cylinders_r1", "Fig. 3(a) crossed cylinders, r = 1", (1, -0.8, 0.9), (0, 0, 1)),
    ("crossed_cylinders_r0.001", "Fig. 3(b) crossed cylinders, r = 0.001", (1, -0.8, 0.9), (0, 0, 1)),
    ("protrusion", "Fig. 4(a) protrusion", (1, -1.2, 0.6), (0, 0, 1)),
    ("depression", "Fig. 4(b) depression", (1, -1.2, 0.6), (0, 0, 1)),
    ("concavity", "Fig. 4(c) concavity", (1, -1.2, 0.6), (0, 0, 1)),
    ("cup_a1.5", "Fig. 5(a) cup, handle at a = 1.5", (0.2, -1, 0.5), (0, 0, 1)),
    ("cup_a1.25", "Fig. 5(b) cup, handle at a = 1.25", (0.2, -1, 0.5), (0, 0, 1)),
    ("cup_a1.0", "Fig. 5(c) cup, handle at a = 1.0", (0.2, -1, 0.5), (0, 0, 1)),
    ("hammer", "Fig. 6(a) hammer", (0.3, -1, 0.6), (0, 0, 1)),
    ("sword", "Fig. 6(b) sword", (0.2, 0.3, 1), (0, 1, 0)),
    ("table", "Fig. 6(c) table", (1, -1.4, -0.9), (0, 0, -1)),
    ("rounded_cube_sphere_1", "Fig. 7 rounded cube, negative sphere far", (1.2, -1, 0.7), (0, 0, 1)),
    ("rounded_cube_sphere_2", "Fig. 7 rounded cube, negative sphere nearer", (1.2, -1, 0.7), (0, 0, 1)),
    ("rounded_cube_sphere_3", "Fig. 7 rounded cube, negative sphere at the face", (1.2, -1, 0.7), (0, 0, 1)),
    ("formic_acid", "Fig. 8(c) formic acid", (0.2, -0.4, 1), (0, 1, 0)),
    ("acetic_acid", "Fig. 9(c) acetic acid", (0.2, -0.4, 1), (0, 1, 0)),
]

COLOURS = [
    (0.85, 0.22, 0.18), (0.22, 0.42, 0.85), (0.25, 0.7, 0.3), (0.95, 0.6, 0.15),
    (0.6, 0.3, 0.75), (0.15, 0.7, 0.7), (0.9, 0.8, 0.2), (0.8, 0.4, 0.6),
]


def mesh(surface, bounds, resolution):
    mesher = vtkPiFlyingEdges()
    # A primitive may have no real points (the paper's concavity uses the "sphere"
    # -x^2-y^2-z^2-0.01): its empty mesh is expected, not worth a warning.
    mesher.GetExecutive()
    mesher.AddObserver("WarningEvent", lambda *args: None)
    mesher.SetPiSurface(surface)
    mesher.SetBounds(bounds)
    mesher.SetResolution(resolution)
    mesher.Update()
    return mesher.GetOutput()


def render(model_path, png_path, direction, view_up, inside, size=(640, 480)):
    reader = vtkPiSurfaceModelReader()
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
    for i in range(surface.GetNumberOfFactors()):
        alone = vtkPiSurface()  # the primitive itself: its factor alone with r = 0
        alone.AddFactor(surface.GetFactor(i))
        mapper = vtkPolyDataMapper()
        mapper.SetInputData(mesh(alone, bounds, 128))
        mapper.ScalarVisibilityOff()
        # Primitives and Pi-surface often coincide: keep the primitives just behind.
        mapper.SetRelativeCoincidentTopologyPolygonOffsetParameters(2, 2)
        actor = vtkActor()
        actor.SetMapper(mapper)
        actor.GetProperty().SetColor(COLOURS[i % len(COLOURS)])
        actor.GetProperty().SetOpacity(0.35 if inside else 1.0)
        renderer.AddActor(actor)

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

    grab = vtkWindowToImageFilter()
    grab.SetInput(window)
    writer = vtkPNGWriter()
    writer.SetInputConnection(grab.GetOutputPort())
    writer.SetFileName(png_path)
    writer.Write()
    return reader.GetOutput().GetNumberOfCells()


def main(models, out):
    os.makedirs(out, exist_ok=True)
    cards = []
    for name, title, direction, up in FIGURES:
        path = os.path.join(models, name + ".pisurf")
        if not os.path.exists(path):
            print("missing model", path)
            continue
        png = name + ".png"
        triangles = render(path, os.path.join(out, png), direction, up, name in INSIDE)
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
        f.write("</div></body></html>\n")
    return 0 if len(cards) == len(FIGURES) else 1


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print(__doc__)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2]))
