"""The Pi Exact Surface representation in pvpython.

1. Images against baselines (Testing/Baselines/ExactView.*.png): the cup in solid
   colour (perspective), the dented cube coloured by Factor with a Cone source
   through it (parallel projection: the cone shows where it is in front), ubiquitin
   (1ubq) from Molecular Pi Surface in Local mode (its atoms and settings, no
   PiSurfaceModel; perspective).
   Interactive renders, with or without LOD: one depth per 4 x 4 block; still renders:
   every pixel. Opacity 0.35 with depth peeling and a sphere in the bowl shown after the
   cup: the opaque cup blended over the picture without it, pixel by pixel.
2. Depth: the view's Z buffer at every pixel against the depth of vtkPiRayCaster's
   CAMERA-mode first hit for the same camera and size (perspective and parallel): the
   same pixels hit, and each hit's point, unprojected from the Z buffer, within
   1e-6 of the model size of the caster's hit (or one step of the depth buffer there,
   if that is larger).
3. A Sphere source shown as Pi Exact Surface: one warning naming the source, nothing
   drawn, no crash; renders after that warn no more.
4. A model the caster refuses (a coefficient overflows): the caster's error once over
   three renders, nothing drawn; the same source with a valid model draws.
"""
import os
import sys

from paraview.simple import (ColorBy, Cone, GetActiveViewOrCreate, GetColorTransferFunction,
                             MolecularPiSurface, PiMoleculeReader, PiSurfaceModelReader, Render,
                             ProgrammableSource, SaveScreenshot, Show, Sphere)
from pisurfaces import vtkPiRayCaster, vtkPiSurfaceModelReader
from vtkmodules.vtkCommonCore import (vtkFloatArray, vtkOutputWindow, vtkStringOutputWindow,
                                      vtkUnsignedCharArray)
from vtkmodules.vtkCommonMath import vtkMatrix4x4
from vtkmodules.vtkTestingRendering import vtkTesting

from pitesting import check

models = os.environ["PISURF_MODELS_DIR"]
temp = os.environ["PISURF_TEMP_DIR"]
baselines = os.environ["PISURF_BASELINES_DIR"]
W, H = 400, 300


def compare(view, name):
    image = os.path.join(temp, "ExactView.%s.png" % name)
    baseline = os.path.join(baselines, "ExactView.%s.png" % name)
    SaveScreenshot(image, view, ImageResolution=[W, H])
    if not os.path.exists(baseline):
        check(False, "no baseline yet: look at %s and copy it to %s" % (image, baseline))
        return
    testing = vtkTesting()
    for argument in ("-V", baseline, "-T", temp):
        testing.AddArgument(argument)
    check(testing.RegressionTest(image, 0.05) == vtkTesting.PASSED,
          "%s differs from %s" % (image, baseline))


def new_view():
    view = GetActiveViewOrCreate("RenderView")
    view.OrientationAxesVisibility = 0
    view.Background = [0.32, 0.34, 0.43]
    view.ViewSize = [W, H]
    return view


def set_camera(view, position, focal, up, parallel, scale=1.0, angle=30.0):
    view.CameraPosition = position
    view.CameraFocalPoint = focal
    view.CameraViewUp = up
    view.CameraParallelProjection = parallel
    view.CameraParallelScale = scale
    view.CameraViewAngle = angle


def z_buffer(view):
    """The view window's size and its Z buffer (as last rendered)."""
    window = view.GetRenderWindow()
    w, h = window.GetSize()
    z = vtkFloatArray()
    window.GetZbufferData(0, 0, w - 1, h - 1, z)
    return w, h, z


def drawn_pixels(view):
    """How many pixels of a new render of the view have a depth nearer than the far plane."""
    Render(view)
    w, h, z = z_buffer(view)
    # len, not sum: running a Programmable Source's script rebinds sum in this
    # interpreter to the numpy_interface algorithm.
    return len([n for n in range(w * h) if z.GetValue(n) < 1.0])


def depth_check(view, path, what):
    """Z buffer of the rendered view against the caster's first hits."""
    Render(view)
    w, h, z = z_buffer(view)
    check(z.GetNumberOfTuples() == w * h, "%s: Z buffer of %d values" % (what, z.GetNumberOfTuples()))
    renderer = view.GetRenderer()
    camera = renderer.GetActiveCamera()
    aspect = w / float(h)
    matrix = vtkMatrix4x4()
    matrix.DeepCopy(camera.GetCompositeProjectionTransformMatrix(aspect, -1, 1))
    inverse = vtkMatrix4x4()
    vtkMatrix4x4.Invert(matrix, inverse)

    reader = vtkPiSurfaceModelReader()
    reader.SetFileName(path)
    reader.SetResolution(8)
    caster = vtkPiRayCaster()
    caster.SetInputConnection(reader.GetOutputPort())
    caster.SetViewMode(vtkPiRayCaster.CAMERA)
    caster.SetResolution(w, h)
    caster.SetCameraPosition(camera.GetPosition())
    caster.SetCameraFocalPoint(camera.GetFocalPoint())
    caster.SetCameraViewUp(camera.GetViewUp())
    caster.SetViewAngle(camera.GetViewAngle())
    caster.SetParallelProjection(bool(camera.GetParallelProjection()))
    caster.SetParallelScale(camera.GetParallelScale())
    caster.Update()
    hits = caster.GetOutput()
    pixels = hits.GetPointData().GetArray("PixelIndex")
    b = reader.GetOutput().GetBounds()
    size = max(b[1] - b[0], b[3] - b[2], b[5] - b[4])

    def unproject(i, j, depth):
        ndc = [2.0 * (i + 0.5) / w - 1.0, 2.0 * (j + 0.5) / h - 1.0, 2.0 * depth - 1.0, 1.0]
        p = inverse.MultiplyPoint(ndc)
        return [p[0] / p[3], p[1] / p[3], p[2] / p[3]]

    hit_pixels = set()
    worst = 0.0
    bad = 0
    for k in range(hits.GetNumberOfPoints()):
        i, j = int(pixels.GetComponent(k, 0)), int(pixels.GetComponent(k, 1))
        hit_pixels.add((i, j))
        depth = z.GetValue(j * w + i)
        if depth >= 1.0:
            bad += 1
            continue
        p = unproject(i, j, depth)
        q = hits.GetPoint(k)
        error = sum((p[c] - q[c]) ** 2 for c in range(3)) ** 0.5
        # One step of a 24-bit depth buffer there, in world units.
        step = unproject(i, j, min(depth + 2.0 ** -24, 1.0))
        quantum = sum((step[c] - p[c]) ** 2 for c in range(3)) ** 0.5
        worst = max(worst, error / size)
        if error > max(1e-6 * size, quantum):
            bad += 1
    drawn = sum(1 for n in range(w * h) if z.GetValue(n) < 1.0)
    print("%s: %d hits, %d pixels drawn, %d bad, worst error %.3g of the size"
          % (what, len(hit_pixels), drawn, bad, worst))
    check(len(hit_pixels) > 1000, "%s: only %d hits" % (what, len(hit_pixels)))
    check(bad == 0, "%s: %d pixels whose depth is not the hit's" % (what, bad))
    check(drawn == len(hit_pixels), "%s: %d pixels drawn, %d hit" % (what, drawn, len(hit_pixels)))


view = new_view()

# 1a. The cup, solid colour, perspective.
cup_path = os.path.join(models, "cup_a1.0.pisurf")
cup = PiSurfaceModelReader(FileName=cup_path, Resolution=32)
cup_display = Show(cup, view)
cup_display.SetRepresentationType("Pi Exact Surface")
cup_display.ColorArrayName = ["POINTS", ""]
cup_display.DiffuseColor = [0.85, 0.75, 0.55]
cup_display.Specular = 0.3
set_camera(view, [6, -8, 4], [0.7, 0, -1.2], [0, 0, 1], 0)
view.ResetCamera(False)
Render(view)
compare(view, "cup")
check(cup_display.Representation == "Pi Exact Surface", "the representation type is set")

# Interactive renders cast one ray per n x n pixels: every 4 x 4 block of the Z buffer
# holds one depth, at ParaView's default LOD Threshold (the 8 points the display gets
# are far below it) and with level of detail; still renders cast every pixel again.
def uniform_blocks(view, n):
    w, h, z = z_buffer(view)
    uniform = mixed = 0
    for bj in range(h // n):
        for bi in range(w // n):
            values = {z.GetValue((n * bj + dj) * w + n * bi + di)
                      for dj in range(n) for di in range(n)}
            if len(values) == 1 and min(values) < 1.0:
                uniform += 1
            elif len(values) > 1:
                mixed += 1
    return uniform, mixed


cup_display.InteractiveReduction = 4
for threshold in (view.LODThreshold, 0.0):
    view.LODThreshold = threshold
    view.InteractiveRender()
    uniform, mixed = uniform_blocks(view, 4)
    print("LOD Threshold %g, interactive render, 4 x 4: %d uniform blocks on the cup, %d mixed"
          % (threshold, uniform, mixed))
    check(uniform > 500 and mixed == 0, "an interactive render casts one ray per 4 x 4 pixels")
    Render(view)
    uniform, mixed = uniform_blocks(view, 4)
    print("still render: %d uniform blocks on the cup, %d mixed" % (uniform, mixed))
    check(mixed > 500, "a still render casts every pixel")
cup_display.InteractiveReduction = 1
view.InteractiveRender()
uniform, mixed = uniform_blocks(view, 4)
check(mixed > 500, "InteractiveReduction 1: interactive renders cast every pixel")
cup_display.InteractiveReduction = 2
view.LODThreshold = 20.0


# Opacity 0.35 (the GUI's look for Pi Surface), depth peeling on (ParaView's default),
# with an opaque Sphere source shown after the cup, in its bowl: every pixel the cup
# covers is the opaque cup's colour blended over the picture without the cup.
def rgb(view):
    window = view.GetRenderWindow()
    w, h = window.GetSize()
    pixels = vtkUnsignedCharArray()
    window.GetRGBACharPixelData(0, 0, w - 1, h - 1, 0, pixels)
    return [pixels.GetTuple4(n)[:3] for n in range(w * h)]


inside = Sphere(Center=[0, 0, -1.0], Radius=1.2, ThetaResolution=32, PhiResolution=32)
inside_display = Show(inside, view)
inside_display.DiffuseColor = [0.2, 0.4, 0.9]
view.DepthPeeling = 1
view.UseFXAA = 0  # FXAA blends edges by their luminance, which the opacity changes
Render(view)
opaque = rgb(view)
cup_display.Visibility = 0
Render(view)
behind = rgb(view)
cup_display.Visibility = 1
cup_display.Opacity = 0.35
Render(view)
translucent = rgb(view)
cup_display.Opacity = 1.0
inside_display.Visibility = 0


def departure(n):
    return max(abs(translucent[n][c] - (0.35 * opaque[n][c] + 0.65 * behind[n][c]))
               for c in range(3))


covered = [n for n in range(len(opaque)) if opaque[n] != behind[n]]
over_sphere = [n for n in covered if behind[n] != behind[0]]
departing = [n for n in covered if departure(n) > 2.0]
print("opacity 0.35: %d pixels covered (%d of them over the sphere), %d depart from the "
      "blend by more than 2 / 255 (largest %.1f)"
      % (len(covered), len(over_sphere), len(departing), max(map(departure, covered))))
check(len(covered) > 1000 and len(over_sphere) > 1000 and not departing,
      "opacity 0.35 blends the surface over what lies behind it")

# 2. Depth of the cup, perspective and parallel.
depth_check(view, cup_path, "cup perspective")
set_camera(view, [5, -7, 3], [0.7, 0, -1.2], [0, 0, 1], 1, 2.2)
depth_check(view, cup_path, "cup parallel")
cup_display.Visibility = 0

# 1b. The dented cube by Factor, a cone through it, parallel projection.
cube_path = os.path.join(models, "rounded_cube_sphere_2.pisurf")
cube = PiSurfaceModelReader(FileName=cube_path, Resolution=32)
cube_display = Show(cube, view)
cube_display.SetRepresentationType("Pi Exact Surface")
ColorBy(cube_display, ("POINTS", "Factor"))
lut = GetColorTransferFunction("Factor")
lut.ApplyPreset("Cool to Warm", True)
lut.RescaleTransferFunction(0.0, 1.0)
cone = Cone(Center=[1.2, 0.0, 0.0], Height=1.6, Radius=0.35, Resolution=48)
cone_display = Show(cone, view)
cone_display.DiffuseColor = [0.9, 0.9, 0.2]
cone_display.ColorArrayName = ["POINTS", ""]
set_camera(view, [7, -5, 4], [0.2, 0, 0], [0, 0, 1], 1, 1.9)
Render(view)
compare(view, "cube_cone")
cone_display.Visibility = 0
depth_check(view, cube_path, "dented cube parallel")
cube_display.Visibility = 0

# 1c. Ubiquitin (1ubq), Molecular Pi Surface in Local mode (its atoms and settings, no
# PiSurfaceModel): the exact view casts the molecule's own field.
molecule = MolecularPiSurface(Input=PiMoleculeReader(
    FileName="/usr/share/freesasa/test-data/1ubq.pdb"), Mode="Local", Spacing=2.0)
molecule_display = Show(molecule, view)
molecule_display.SetRepresentationType("Pi Exact Surface")
molecule_display.DiffuseColor = [0.85, 0.75, 0.55]
molecule_display.ColorArrayName = ["POINTS", ""]
set_camera(view, [33, -55, 66], [33, 29, 21], [0, 0, 1], 0, angle=30)
Render(view)
compare(view, "1ubq")
molecule_display.Visibility = 0

# 3. No model: one warning naming the source, nothing drawn.
messages = vtkStringOutputWindow()
previous = vtkOutputWindow.GetInstance()
vtkOutputWindow.SetInstance(messages)
sphere = Sphere()
sphere_display = Show(sphere, view)
sphere_display.SetRepresentationType("Pi Exact Surface")
Render(view)
view.CameraPosition = [0, 0, 5]
Render(view)
vtkOutputWindow.SetInstance(previous)
text = messages.GetOutput()
print("messages of the model-less input:\n" + text)
check(text.count("PiSurfaceModel") == 1, "one warning about the missing model")
check("vtkSphereSource" in text, "the warning names the source")
w, h, z = z_buffer(view)
check(all(z.GetValue(n) >= 1.0 for n in range(w * h)), "nothing drawn for the sphere")

sphere_display.Visibility = 0

# 4. A model the caster refuses (a coefficient that overflows): the caster's error,
#    once over renders from three cameras, nothing drawn; the model made valid draws.
cup_text = open(os.path.join(models, "cup_a1.0.pisurf")).read()
check("-0.1\"" in cup_text, "the cup's model has the term replaced below")
carrier = ProgrammableSource(OutputDataSetType="vtkPolyData")


def carry(text):
    """The carrier outputs the box's corners with `text` as its PiSurfaceModel."""
    carrier.Script = "\n".join([
        "from vtkmodules.vtkCommonCore import vtkPoints, vtkStringArray",
        "model = vtkStringArray()",
        "model.SetName('PiSurfaceModel')",
        "model.InsertNextValue(%r)" % text,
        "output = self.GetOutput()",
        "output.GetFieldData().AddArray(model)",
        "corners = vtkPoints()",
        "corners.InsertNextPoint(-2.2, -2.1, -2.55)",
        "corners.InsertNextPoint(3.4, 2.1, 0.25)",
        "output.SetPoints(corners)"])


carry(cup_text.replace("-0.1\"", "-1e300*1e300\""))
carrier_display = Show(carrier, view)
carrier_display.SetRepresentationType("Pi Exact Surface")
messages = vtkStringOutputWindow()
vtkOutputWindow.SetInstance(messages)
for position in ([6, -8, 4], [8, -6, 4], [6, -8, 6]):
    set_camera(view, position, [0.7, 0, -1.2], [0, 0, 1], 0)
    Render(view)
vtkOutputWindow.SetInstance(previous)
text = messages.GetOutput()
print("messages of the refused model:\n" + text)
check(text.count("Invalid PiSurfaceModel") == 1, "one error for the refused model")
check("coefficient overflow" in text and "bowl base ellipsoid" in text,
      "the error says what is wrong and where")
check(drawn_pixels(view) == 0, "nothing drawn for the refused model")
carry(cup_text)
drawn = drawn_pixels(view)
print("pixels covered once the model is valid: %d" % drawn)
check(drawn > W * H // 20, "the valid model draws")

# os._exit: pvpython 5.11 tearing its offscreen X window down at sys.exit fails
# (GLXBadContext) whichever representation was shown.
import pitesting  # noqa: E402

print("%d failures" % pitesting.failures)
sys.stdout.flush()
sys.stderr.flush()
os._exit(1 if pitesting.failures else 0)
