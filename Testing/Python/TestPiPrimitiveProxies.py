"""Pi Primitive, Pi Product and the .pisurf writer from pvpython: XML defaults
are the C++ defaults; every primitive type meshes; bad values are errors with empty
output; a product of primitives is the Pi Surface of the same model; the writer round
trips through the model reader; a .pvsm state and a Python trace replay to the same
meshes."""
import json
import math
import os

from pitesting import check, finish

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager, smtrace
from vtkmodules.vtkCommonCore import VTK_STRING
from vtkmodules.util.misc import calldata_type
from vtkmodules.vtkFiltersCore import vtkFeatureEdges, vtkMassProperties, vtkTriangleFilter

models = os.environ["PISURF_MODELS_DIR"]
temp = os.environ["PISURF_TEMP_DIR"]


def area(mesh):
    if mesh.GetNumberOfCells() == 0:
        return 0.0
    mass = vtkMassProperties()
    mass.SetInputData(mesh)
    mass.Update()
    return mass.GetSurfaceArea()


def open_edges(mesh):
    edges = vtkFeatureEdges()
    edges.SetInputData(mesh)
    edges.BoundaryEdgesOn()
    edges.NonManifoldEdgesOn()
    edges.FeatureEdgesOff()
    edges.ManifoldEdgesOff()
    edges.Update()
    return edges.GetOutput().GetNumberOfCells()


def same_mesh(a, b, what):
    """Same numbers of points and cells, areas within 1e-9 relative."""
    ok = (a.GetNumberOfPoints() == b.GetNumberOfPoints() and
          a.GetNumberOfCells() == b.GetNumberOfCells() and a.GetNumberOfCells() > 0)
    aa, ab = area(a), area(b)
    ok = ok and abs(aa - ab) <= 1e-9 * max(aa, ab)
    check(ok, "%s: %d/%d points, %d/%d cells, area %.15g/%.15g" % (
        what, a.GetNumberOfPoints(), b.GetNumberOfPoints(), a.GetNumberOfCells(),
        b.GetNumberOfCells(), aa, ab))


class Errors:
    """Collects the vtkErrorMacro messages of a proxy's VTK object."""

    def __init__(self, proxy):
        self.messages = []

        @calldata_type(VTK_STRING)
        def collect(caller, event, message):
            self.messages.append(message)

        self.callback = collect
        proxy.GetClientSideObject().AddObserver("ErrorEvent", collect)

    def take(self):
        m, self.messages = self.messages, []
        return m


def model_of(mesh):
    array = mesh.GetFieldData().GetAbstractArray("PiSurfaceModel")
    return json.loads(array.GetValue(0)) if array is not None else None


# --- Defaults: XML = C++ -------------------------------------------------------------
from pisurfaces import vtkPiPrimitiveSource, vtkPiProduct
primitive = PiPrimitive()
cxx = vtkPiPrimitiveSource()
check(primitive.Type == "Sphere" and cxx.GetType() == 0, "Type default")
for name in ("Center", "Radii", "Normal", "Axis", "RotationAxis", "Orientation", "Bounds"):
    check(list(primitive.GetPropertyValue(name)) == list(getattr(cxx, "Get" + name)()),
          name + " default")
for name in ("Radius", "MajorRadius", "MinorRadius", "Exponent", "Angle", "RotationAngle",
             "Scale", "Resolution"):
    check(primitive.GetPropertyValue(name) == getattr(cxx, "Get" + name)(), name + " default")
check(primitive.Expression == cxx.GetExpression(), "Expression default")
check(primitive.Negate == int(cxx.GetNegate()), "Negate default")
product_defaults = PiProduct(Input=[primitive])
cxx_product = vtkPiProduct()
for name in ("Blending", "Resolution", "OuterEnvelope", "ProjectVertices", "GeneratePrimitives",
             "AutomaticResolution", "ComputeGradientMagnitude"):
    check(product_defaults.GetPropertyValue(name) == getattr(cxx_product, "Get" + name)(),
          "PiProduct %s default" % name)
check(list(product_defaults.Bounds) == list(cxx_product.GetBounds()), "PiProduct Bounds default")
check(product_defaults.Method == "Flying Edges" and cxx_product.GetMethod() == 0, "Method default")
Delete(product_defaults)
del product_defaults

# --- Every type meshes --------------------------------------------------------------------
settings = {
    "Sphere": dict(Radius=0.8),
    "Ellipsoid": dict(Radii=[1, 0.6, 0.4]),
    "Superellipsoid": dict(Radii=[1, 0.8, 0.6], Exponent=6),
    "Torus": dict(MajorRadius=1, MinorRadius=0.3, Axis=[0, 1, 0]),
    "Plane": dict(Normal=[1, 1, 0]),
    "Cylinder": dict(Radius=0.5, Axis=[1, 0, 0]),
    "Cone": dict(Angle=25),
    "Hyperboloid1": dict(Radii=[0.5, 0.5, 1]),
    "Hyperboloid2": dict(Radii=[0.5, 0.5, 0.5]),
    "Paraboloid": dict(Radii=[0.5, 0.7, 1]),
    "HyperbolicParaboloid": dict(Radii=[1, 1, 1]),
    "Polynomial": dict(Expression="x^4+y^4+z^4-x*y-1"),
}
bounded = ("Sphere", "Ellipsoid", "Superellipsoid", "Torus")
for type_, values in settings.items():
    source = PiPrimitive(Type=type_, Center=[0.5, -0.25, 1], Resolution=40, **values)
    errors = Errors(source)
    mesh = servermanager.Fetch(source)
    check(not errors.take(), type_ + ": no error")
    check(mesh.GetNumberOfCells() > 200, "%s meshes: %d cells" % (type_, mesh.GetNumberOfCells()))
    check(mesh.GetPointData().GetArray("Factor") is not None and
          mesh.GetPointData().GetArray("Normals") is not None, type_ + ": Factor and Normals")
    model = model_of(mesh)
    check(model is not None and len(model["primitives"]) == 1 and model["blending"] == 0 and
          model["primitives"][0]["center"] == [0.5, -0.25, 1], type_ + ": PiSurfaceModel")
    if type_ in bounded:
        check(open_edges(mesh) == 0, type_ + ": closed")
    else:
        check("bounds" in model, type_ + ": unbounded, so the model has bounds")
        b = mesh.GetBounds()
        check(b[0] >= model["bounds"][0] - 1e-9 and b[1] <= model["bounds"][1] + 1e-9,
              type_ + ": clipped to its box")
    Delete(source)

# Negate flips the normals, Scale keeps the surface.
plain = servermanager.Fetch(PiPrimitive(Type="Torus", Resolution=32))
flipped = servermanager.Fetch(PiPrimitive(Type="Torus", Resolution=32, Negate=1, Scale=3))
same_mesh(plain, flipped, "Negate and Scale keep the surface")
check(plain.GetPointData().GetArray("Normals").GetTuple3(0)[0] ==
      -flipped.GetPointData().GetArray("Normals").GetTuple3(0)[0], "Negate flips the normals")

# --- Orientation: Euler angles (the box widget's Rotation) turn the primitive further ------
from pisurfaces import vtkPiSurface


def factor_at(source, point):
    """The primitive's own f at a point, from the model its output carries."""
    surface = vtkPiSurface()
    check(surface.SetModelJSON(json.dumps(model_of(servermanager.Fetch(source)))),
          "the model loads")
    return surface.EvaluateFunction(point)


# An ellipsoid turned 90 degrees about z by Orientation is the one turned by
# RotationAxis/RotationAngle: its long semi-axis (2) now lies along y.
turned = PiPrimitive(Type="Ellipsoid", Radii=[2, 1, 0.5], Orientation=[0, 0, 90], Resolution=40)
rotated = PiPrimitive(Type="Ellipsoid", Radii=[2, 1, 0.5], RotationAxis=[0, 0, 1],
                      RotationAngle=90, Resolution=40)
same_mesh(servermanager.Fetch(turned), servermanager.Fetch(rotated),
          "Orientation 0 0 90 = a rotation of 90 degrees about z")
check(abs(factor_at(turned, [0, 2, 0])) < 1e-12 and abs(factor_at(turned, [2, 0, 0]) - 3) < 1e-12,
      "turned ellipsoid: (0, 2, 0) on it, (2, 0, 0) outside (f = 3): %g, %g"
      % (factor_at(turned, [0, 2, 0]), factor_at(turned, [2, 0, 0])))
# The Euler order is vtkProp3D's, R = Rz Rx Ry: x 90 then z 90 takes the local w axis
# (the long one, 2) to Rz(90) Rx(90) (0, 0, 1) = Rz(90) (0, -1, 0) = (1, 0, 0).
euler = PiPrimitive(Type="Ellipsoid", Radii=[0.5, 1, 2], Orientation=[90, 0, 90], Resolution=24)
check(abs(factor_at(euler, [2, 0, 0])) < 1e-12, "Euler order Rz Rx Ry: w ends along x (f = %g)"
      % factor_at(euler, [2, 0, 0]))
# After an Axis: a cylinder along x turned 90 degrees about z runs along y.
cylinder = PiPrimitive(Type="Cylinder", Radius=0.5, Axis=[1, 0, 0], Orientation=[0, 0, 90],
                       Resolution=24)
check(abs(factor_at(cylinder, [0.5, 7, 0])) < 1e-12 and
      abs(factor_at(cylinder, [0, 0.3, 0]) + 0.25) < 1e-12,
      "cylinder: Axis x, then Orientation z 90, runs along y")
for proxy in (turned, rotated, euler, cylinder):
    Delete(proxy)

# --- Bad values: an error naming the parameter, empty output ------------------------------
bad = PiPrimitive(Type="Sphere")
errors = Errors(bad)
for values, word in ((dict(Type="Sphere", Radius=-1), "radius"),
                     (dict(Type="Superellipsoid", Exponent=3), "exponent"),
                     (dict(Type="Polynomial", Expression="x^2+*y"), "expression"),
                     (dict(Type="Polynomial", Expression=""), "expression"),
                     (dict(Type="Torus", MinorRadius=0), "minor"),
                     (dict(Type="Cone", Angle=95), "angle"),
                     (dict(Type="Ellipsoid", Orientation=[0, float("nan"), 0]), "orientation"),
                     (dict(Type="Sphere", Radius=1, Bounds=[1, 0, 0, 1, 0, 1]), "bounds")):
    bad.Type = "Sphere"
    bad.Radius = 1
    bad.Bounds = [0] * 6
    bad.Orientation = [0, 0, 0]
    for k, v in values.items():
        bad.SetPropertyWithName(k, v)
    bad.UpdatePipeline()
    messages = errors.take()
    check(bad.GetDataInformation().GetNumberOfCells() == 0, "%s: empty output" % values)
    check(len(messages) == 1 and word in messages[0].lower(),
          "%s: one error naming %s: %s" % (values, word, messages))
# It recovers once the value is valid.
bad.Type = "Sphere"
bad.Radius = 1
bad.Bounds = [0] * 6
bad.UpdatePipeline()
check(bad.GetDataInformation().GetNumberOfCells() > 0 and not errors.take(), "recovers")

# --- A refused value keeps the last valid surface -----------------------------------------
# Pi Primitive: a torus, then a negative minor radius: the error is reported and the
# torus stays (same mesh, same model); a valid value re-meshes.
keep = PiPrimitive(Type="Torus", MinorRadius=0.3, Resolution=24)
kept_errors = Errors(keep)
before = servermanager.Fetch(keep)
check(before.GetNumberOfCells() > 200 and not kept_errors.take(), "a valid torus")
keep.MinorRadius = -0.1
after = servermanager.Fetch(keep)
messages = kept_errors.take()
check(len(messages) >= 1 and "minor" in messages[0].lower(),
      "a negative minor radius is refused with an error: %s" % messages)
same_mesh(before, after, "the last valid torus stays")
check(model_of(after) == model_of(before), "and its model (minor radius 0.3) stays")
keep.MinorRadius = 0.2
fixed = servermanager.Fetch(keep)
check(not kept_errors.take() and model_of(fixed)["primitives"][0]["minor_radius"] == 0.2,
      "a valid value re-meshes: %s" % model_of(fixed)["primitives"][0])

# Pi Product: an input refused upstream leaves the product as it was; so does an empty
# product, which is an error of its own.
other = PiPrimitive(Center=[1.2, 0, 0], Radius=0.5)
product = PiProduct(Input=[keep, other], Blending=0.05, Resolution=32)
product_errors = Errors(product)
good = servermanager.Fetch(product)
check(good.GetNumberOfCells() > 500 and not product_errors.take(), "a valid product")
other.Radius = -1
same_mesh(good, servermanager.Fetch(product), "a refused input radius leaves the product")
other.Radius = 0.5
product.Input = []
unchanged = servermanager.Fetch(product)
messages = product_errors.take()
check(any("input" in m.lower() for m in messages), "an empty product is an error: %s" % messages)
same_mesh(good, unchanged, "an empty product keeps the last valid surface")
product.Input = [keep, other]
check(servermanager.Fetch(product).GetNumberOfCells() > 500, "the product recovers")

# Pi Surface: a malformed Model keeps the last valid surface.
surface = PiSurface(Resolution=32)
surface_errors = Errors(surface)
valid_surface = servermanager.Fetch(surface)
surface.Model = '{"pisurf": 1, "blending": '
same_mesh(valid_surface, servermanager.Fetch(surface), "a malformed Model keeps the surface")
check(any("invalid json" in m.lower() for m in surface_errors.take()),
      "the malformed Model is reported")
for proxy in (product, other, keep, surface):
    Delete(proxy)

# --- Pi Product of primitives = Pi Surface of the same model -------------------------------
a = PiPrimitive(registrationName="right", Center=[0.9, 0, 0])
b = PiPrimitive(registrationName="left", Center=[-0.9, 0, 0])
two = PiProduct(registrationName="two_spheres", Input=[a, b], Blending=0.25, Resolution=64)
reference = PiSurface(Resolution=64)  # its default model is the same two spheres
two_mesh = servermanager.Fetch(two)
same_mesh(two_mesh, servermanager.Fetch(reference), "two spheres: product = Pi Surface")
check(len(model_of(two_mesh)["primitives"]) == 2 and model_of(two_mesh)["blending"] == 0.25,
      "the product carries the combined model")

# Editing an input re-executes the product.
a.Center = [1.1, 0, 0]
moved = servermanager.Fetch(two)
check(moved.GetBounds()[1] > two_mesh.GetBounds()[1] + 0.1, "moving an input moves the product")
reference.Model = json.dumps({"pisurf": 1, "blending": 0.25, "primitives": [
    {"type": "sphere", "center": [1.1, 0, 0], "radius": 1},
    {"type": "sphere", "center": [-0.9, 0, 0], "radius": 1}]})
same_mesh(moved, servermanager.Fetch(reference), "after the move: product = Pi Surface")

# The cup, from three polynomial primitives placed by Center, against its model file.
cup = json.load(open(os.path.join(models, "cup_a1.0.pisurf")))
handle_expr = "(x^2+z^2+y^2+0.5-0.01)^2-2*(x^2+z^2)"
base_expr = "1/8*x^2+1/8*y^2+(z+2)^2-0.1"
bowl_expr = "((z+1)^2+10*x^2+10*y^2+19)^2-800*(x^2+y^2)"


def build_cup():
    handle = PiPrimitive(registrationName="handle", Type="Polynomial", Expression=handle_expr,
                         Center=[2.2, 0, -1])
    base = PiPrimitive(registrationName="base", Type="Polynomial", Expression=base_expr)
    bowl = PiPrimitive(registrationName="bowl", Type="Polynomial", Expression=bowl_expr)
    return PiProduct(registrationName="cup", Input=[handle, base, bowl], Blending=10,
                     Resolution=64, Bounds=cup["bounds"])


cup_product = build_cup()
cup_model = {"pisurf": 1, "blending": 10, "bounds": cup["bounds"], "primitives": [
    {"type": "polynomial", "expression": handle_expr, "center": [2.2, 0, -1]},
    {"type": "polynomial", "expression": base_expr},
    {"type": "polynomial", "expression": bowl_expr}]}
cup_mesh = servermanager.Fetch(cup_product)
same_mesh(cup_mesh, servermanager.Fetch(PiSurface(Model=json.dumps(cup_model), Resolution=64)),
          "cup: product = Pi Surface")
# Live edits re-mesh incrementally (the unchanged factors' row restrictions are kept):
# moving the handle away and back gives exactly the fresh mesh, bit for bit.
handle = FindSource("handle")
handle.Center = [2.5, 0, -1]
cup_product.UpdatePipeline()
handle.Center = [2.2, 0, -1]
again = servermanager.Fetch(cup_product)
same_points = (again.GetNumberOfPoints() == cup_mesh.GetNumberOfPoints() and all(
    again.GetPoint(i) == cup_mesh.GetPoint(i) for i in range(cup_mesh.GetNumberOfPoints())))
check(same_points, "cup: after a move and back, the same points bit for bit")
# The model file's form (handle written about the origin with the parameter a) is the
# same surface up to rounding.
from_file = servermanager.Fetch(PiSurfaceModelReader(
    FileName=os.path.join(models, "cup_a1.0.pisurf"), Resolution=64))
check(abs(area(from_file) - area(cup_mesh)) <= 1e-6 * area(cup_mesh),
      "cup: product area %.9g vs the model file's %.9g" % (area(cup_mesh), area(from_file)))

# A product of products, and of a model reader: all factors multiplied, one r.
nested = PiProduct(Input=[two, PiSurfaceModelReader(
    FileName=os.path.join(models, "two_spheres_d1.1.pisurf"))], Blending=0.5, Resolution=48)
nested_model = model_of(servermanager.Fetch(nested))
check(len(nested_model["primitives"]) == 4 and nested_model["blending"] == 0.5,
      "product of a product and a reader: 4 primitives, r = 0.5")
# Parameters that clash are renamed: two copies of the cup file with a = 1 and 1.5.
clash = PiProduct(Input=[
    PiSurfaceModelReader(FileName=os.path.join(models, "cup_a1.0.pisurf"), Resolution=16),
    PiSurfaceModelReader(FileName=os.path.join(models, "cup_a1.5.pisurf"), Resolution=16)],
    Blending=10, Resolution=16)
clash_model = model_of(servermanager.Fetch(clash))
check(clash_model is not None and clash_model["parameters"] == {"a": 1, "a_2": 1.5} and
      "a_2" in clash_model["primitives"][3]["expression"],
      "clashing parameters renamed: %s" % (clash_model and clash_model.get("parameters")))

# Errors: an input without a model, an invalid input.
no_model = PiProduct(Input=[a, Sphere()])
errors = Errors(no_model)
no_model.UpdatePipeline()
messages = errors.take()
check(no_model.GetDataInformation().GetNumberOfCells() == 0, "input without a model: empty")
check(any("PiSurfaceModel" in m and "Input 2" in m for m in messages),
      "input without a model: error names it: %s" % messages)
broken = PiPrimitive(Radius=-2)
broken_product = PiProduct(Input=[a, broken])
errors = Errors(broken_product)
broken_product.UpdatePipeline()
check(broken_product.GetDataInformation().GetNumberOfCells() == 0 and
      any("Input 2" in m for m in errors.take()), "invalid input primitive: product reports it")

# --- The writer: File > Save Data as .pisurf, read back to the same mesh ------------------
path = os.path.join(temp, "issue7_cup.pisurf")
if os.path.exists(path):
    os.remove(path)
SaveData(path, proxy=cup_product)
check(os.path.exists(path), "SaveData wrote " + path)
back = PiSurfaceModelReader(FileName=path, Resolution=64)
same_mesh(servermanager.Fetch(back), cup_mesh, "writer round trip (cup product)")
path2 = os.path.join(temp, "issue7_torus.pisurf")
torus = PiPrimitive(Type="Torus", MajorRadius=1.2, MinorRadius=0.4, Center=[1, 2, 3])
SaveData(path2, proxy=torus)
torus_back = PiSurfaceModelReader(FileName=path2, Resolution=64, GeneratePrimitives=0)
torus_back.UpdatePipeline()
check(abs(area(servermanager.Fetch(torus_back)) - 4 * math.pi ** 2 * 1.2 * 0.4) < 0.02 * 19,
      "written torus reads back as a torus")

# --- State: save, reset, load: same properties, same meshes --------------------------------
state = os.path.join(temp, "issue7_state.pvsm")
handle = FindSource("handle")
handle.Center = [2.0, 0, -1]  # a moved handle must survive the round trip
before = servermanager.Fetch(cup_product)
SaveState(state)
ResetSession()
LoadState(state)
check(FindSource("handle") is not None and list(FindSource("handle").Center) == [2.0, 0, -1],
      "state: the handle's Center")
check(FindSource("handle").Type == "Polynomial" and FindSource("handle").Expression == handle_expr,
      "state: Type and Expression")
restored = FindSource("cup")
check(restored is not None and restored.Blending == 10 and list(restored.Bounds) == cup["bounds"]
      and len(restored.Input) == 3, "state: the product's properties and inputs")
same_mesh(servermanager.Fetch(restored), before, "state round trip: same mesh")

# --- Trace: build the cup from primitives under smtrace, replay in a fresh session ---------
ResetSession()
smtrace.start_trace()
traced_cup = build_cup()
Show(traced_cup)
trace = smtrace.stop_trace()
expected = servermanager.Fetch(traced_cup)
check("PiProduct(" in trace and "PiPrimitive(" in trace, "the trace records the proxies")
ResetSession()
namespace = {}
exec("from paraview.simple import *\n" + trace, namespace)
replayed = FindSource("cup")
check(replayed is not None, "the trace recreates the product")
if replayed is not None:
    same_mesh(servermanager.Fetch(replayed), expected, "trace replay: same mesh")

finish()
