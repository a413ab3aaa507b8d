# SPDX-License-Identifier: BSD-3-Clause
"""The bad-input catalogue through the ParaView proxies, as a pvpython user types it:
bad models and expressions in the Model property, bad files in the readers, and bad
properties (zero, negative, huge, NaN, infinite) on every proxy. Each case must report an
error whose text names the problem, leave an empty output without NaN coordinates, and
not crash or hang (ctest's timeout)."""
import math
import os
import time

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager
from vtkmodules.vtkCommonCore import vtkLogger, vtkOutputWindow, vtkStringOutputWindow

from pitesting import check, finish

NAN = float('nan')
INF = float('inf')
TEMP = os.path.join(os.environ.get('PISURF_TEMP_DIR', '/tmp'), 'BadInputProxies')
os.makedirs(TEMP, exist_ok=True)

# While a case runs, every message VTK prints lands in a string window (and not on stderr).
# pvpython prints Python's own output through the output window too, so the original
# one is back for the checks.
original = vtkOutputWindow.GetInstance()
vtkLogger.SetStderrVerbosity(vtkLogger.VERBOSITY_OFF)

SPHERE = ('{"pisurf": 1, "blending": 0.1, "primitives": [{"type": "sphere", "radius": 1%s}]}')


def polynomial(expression):
    return ('{"pisurf": 1, "blending": 0, "bounds": [-1, 1, -1, 1, -1, 1], "primitives": '
            '[{"type": "polynomial", "expression": "%s"}]}' % expression)


def write(name, content, mode='w'):
    path = os.path.join(TEMP, name)
    with open(path, mode) as f:
        f.write(content)
    return path


def atom(serial, name, x, y, z, element, record='ATOM  ', residue='ALA'):
    return '%-6s%5d %-4s %3s A%4d    %8.3f%8.3f%8.3f  1.00  0.00          %2s\n' % (
        record, serial, name, residue, 1, x, y, z, element)


def empty_and_finite(data):
    """(True, '') if the output has no points (and so no NaN), else (False, why)."""
    if data is None:
        return True, ''
    if data.IsA('vtkMolecule'):
        n = data.GetNumberOfAtoms()
        return n == 0, '%d atoms' % n
    n = data.GetNumberOfPoints()
    if data.IsA('vtkPointSet') and n:
        for i in range(n):
            if not all(math.isfinite(c) for c in data.GetPoint(i)):
                return False, 'a non-finite coordinate'
    return n == 0, '%d points' % n


cases = 0


def expect(name, expected, make):
    """Runs one case: `make` builds and returns a proxy; its update must report `expected`
    and leave an empty, NaN-free output."""
    global cases
    cases += 1
    window = vtkStringOutputWindow()
    start = time.time()
    vtkOutputWindow.SetInstance(window)
    try:
        proxy = make()
        proxy.UpdatePipeline()
    finally:
        vtkOutputWindow.SetInstance(original)
    data = proxy.GetClientSideObject().GetOutputDataObject(0)
    ok, why = empty_and_finite(data)
    text = window.GetOutput()
    if isinstance(text, bytes):  # messages quoting binary garbage are not UTF-8
        text = text.decode('utf-8', 'replace')
    check(ok, '%s: output not empty (%s)' % (name, why))
    check(expected in text, "%s: no error containing '%s'; got: %s" % (name, expected, text[:400]))
    check(time.time() - start < 60, '%s: took %.0f s' % (name, time.time() - start))
    Delete(proxy)


# ---- Pi Surface: models and expressions typed in the Model property.
model_cases = [
    ('model.syntax', '{"pisurf": 1, "blending": ', 'invalid JSON at line 1'),
    ('model.empty', '', 'invalid JSON'),
    ('model.array', '[1, 2]', 'the top level must be a JSON object'),
    ('model.version', '{"pisurf": 3, "blending": 0, "primitives": []}', 'unsupported version'),
    ('model.unknown_key', SPHERE % ', "colour": 1', "unknown key 'colour'"),
    ('model.wrong_type', SPHERE % ', "center": "origin"', 'expected an array of 3 numbers'),
    ('model.negative_radius',
     '{"pisurf": 1, "blending": 0, "primitives": [{"type": "sphere", "radius": -2}]}',
     'primitives[0]'),
    ('model.overflow', SPHERE % ', "scale": 1e999', 'numbers must be finite'),
    ('model.nesting', '[' * 5000 + ']' * 5000, 'nested deeper than 32'),
    ('model.huge_array', SPHERE % (', "center": [%s]' % ','.join(['0'] * 200000)),
     'expected an array of 3 numbers'),
    ('model.too_many_primitives',
     '{"pisurf": 1, "blending": 0, "primitives": [%s]}'
     % ','.join(['{"type": "sphere", "radius": 1}'] * 100001),
     'more than 100000 primitives'),
    ('expression.syntax', polynomial('x^2 + '), 'unexpected end of expression'),
    ('expression.parenthesis', polynomial('(x + y'), "missing ')'"),
    ('expression.exponent_overflow', polynomial('10^999 * x'), 'coefficient overflow'),
    ('expression.degree', polynomial('x^1000000'), 'degree above'),
    ('expression.fraction_exponent', polynomial('x^0.5'), 'non-negative integer'),
    ('expression.division_by_zero', polynomial('x / (3 - 3)'), 'division by zero'),
    ('expression.division_by_variable', polynomial('1 / x'), 'division by a non-constant'),
    ('expression.unknown_name', polynomial('x^2 + t'), "unknown name 't'"),
    ('expression.function', polynomial('cos(x)'), "unknown name 'cos'"),
]
for name, model, expected in model_cases:
    expect(name, expected, lambda: PiSurface(Model=model, Resolution=16))

# ---- Pi Surface: mesher properties (zero, negative, huge, inverted, NaN).
setting_cases = [
    ('mesher.resolution_zero', dict(Resolution=0), 'Resolution must be at least 1'),
    ('mesher.resolution_negative', dict(Resolution=-3), 'Resolution must be at least 1'),
    ('mesher.resolution_huge', dict(Resolution=50000), 'the limit is 2048 MiB'),
    ('mesher.bounds_inverted', dict(Bounds=[1, -1, -1, 1, -1, 1]), 'x0 < x1'),
    ('mesher.bounds_nan', dict(Bounds=[NAN, 1, -1, 1, -1, 1]), 'bounds must be finite'),
    ('mesher.bounds_infinite', dict(Bounds=[-INF, INF, -1, 1, -1, 1]), 'bounds must be finite'),
    ('mesher.blending_nan', dict(OverrideBlending=1, Blending=NAN), 'Blending must be a finite'),
    ('mesher.blending_infinite', dict(OverrideBlending=1, Blending=INF),
     'Blending must be a finite'),
    ('mesher.ray_cast_resolution_zero', dict(Method='Ray Cast Triangulation', Resolution=0),
     'Resolution must be at least 1'),
]
for name, properties, expected in setting_cases:
    expect(name, expected, lambda: PiSurface(**properties))

# ---- Pi Surface Model Reader: bad files.
garbage = bytes((i * 7919 + 13) % 256 for i in range(4096))
reader_cases = [
    ('reader.missing', os.path.join(TEMP, 'missing.pisurf'), 'cannot open model file'),
    ('reader.directory', TEMP, 'is a directory'),
    ('reader.empty', write('empty.pisurf', ''), 'invalid JSON'),
    ('reader.garbage', write('garbage.pisurf', garbage, 'wb'), 'invalid JSON'),
    ('reader.schema', write('schema.pisurf', '{"pisurf": 1}'), "missing key 'blending'"),
]
for name, path, expected in reader_cases:
    expect(name, expected, lambda: PiSurfaceModelReader(FileName=path))

# ---- Pi Ray Cast: resolutions and cameras.
sphere = PiSurface(Model=SPHERE % '', Resolution=16)
ray_cases = [
    ('rays.resolution_zero', dict(Resolution=[0, 16]), 'Resolution must be at least 1 x 1'),
    ('rays.resolution_huge', dict(Resolution=[100000, 100000]), 'the limit is 2048 MiB'),
    ('rays.bounds_inverted', dict(Bounds=[0, 1, 1, 0, 0, 1]), 'x0 < x1'),
    ('rays.camera_at_focal_point', dict(ViewMode='Camera', CameraPosition=[0, 0, 0],
                                        CameraFocalPoint=[0, 0, 0]), 'equals CameraFocalPoint'),
    ('rays.view_up_parallel', dict(ViewMode='Camera', CameraPosition=[0, 0, 5],
                                   CameraFocalPoint=[0, 0, 0], CameraViewUp=[0, 0, 1]),
     'CameraViewUp is parallel'),
    ('rays.camera_nan', dict(ViewMode='Camera', CameraPosition=[NAN, 0, 5]), 'must be finite'),
    ('rays.view_angle_nan', dict(ViewMode='Camera', CameraPosition=[0, -5, 0],
                                 CameraViewUp=[0, 0, 1], ViewAngle=NAN), 'ViewAngle must be in'),
    ('rays.view_angle_180', dict(ViewMode='Camera', CameraPosition=[0, -5, 0],
                                 CameraViewUp=[0, 0, 1], ViewAngle=180), 'ViewAngle must be in'),
    ('rays.parallel_scale_zero', dict(ViewMode='Camera', CameraPosition=[0, -5, 0],
                                      CameraViewUp=[0, 0, 1], ParallelProjection=1,
                                      ParallelScale=0), 'ParallelScale must be positive'),
]
for name, properties, expected in ray_cases:
    expect(name, expected, lambda: PiRayCast(Input=sphere, **properties))
# An input without a model (a plain ParaView source).
expect('rays.input_without_model', 'carries no PiSurfaceModel',
       lambda: PiRayCast(Input=Sphere()))
# The triangulator on an input that is not a ray cast.
expect('triangulation.input_not_hits', 'has no pixel structure',
       lambda: ImageBasedTriangulation(Input=sphere))

# ---- Pi Molecule Reader: bad files.
small = (atom(1, ' N  ', 0, 0, 0, ' N') + atom(2, ' CA ', 1.46, 0, 0, ' C') + 'END\n')
molecule_cases = [
    ('molecule.missing', os.path.join(TEMP, 'missing.pdb'), 'Cannot open'),
    ('molecule.empty', write('empty.pdb', ''), 'No atoms'),
    ('molecule.garbage', write('garbage.cif', b'data_x\n' + garbage, 'wb'), 'Cannot read'),
    ('molecule.truncated', write('truncated.pdb', small[:40]), 'shorter than 54 characters'),
    ('molecule.wrong_columns',
     write('columns.pdb', small.replace('   0.000   0.000   0.000', ' 0.000   0.000   0.000   ')),
     'wrong columns'),
    ('molecule.only_waters',
     write('waters.pdb', atom(1, ' O  ', 0, 0, 0, ' O', 'HETATM', 'HOH')), 'No atoms left'),
]
for name, path, expected in molecule_cases:
    expect(name, expected, lambda: PiMoleculeReader(FileName=path))
expect('molecule.model_out_of_range', 'Model 7 requested',
       lambda: PiMoleculeReader(FileName=write('small.pdb', small), Model=7))

# ---- Molecular Pi Surface: bad properties on a good molecule.
water = PiMoleculeReader(FileName=write(
    'water.pdb', atom(1, ' O  ', 0, 0, 0, ' O', 'ATOM  ', 'WAT') + atom(2, ' H1 ', 0.96, 0, 0, ' H')
    + atom(3, ' H2 ', -0.24, 0.93, 0, ' H')))
surface_cases = [
    ('molsurface.blending_nan', dict(Blending=NAN), 'Blending must be a finite number >= 0'),
    ('molsurface.blending_negative', dict(Blending=-0.5), 'Blending must be a finite number >= 0'),
    ('molsurface.influence_zero', dict(Mode='Local', InfluenceRadius=0),
     'InfluenceRadius must be a finite number >= 0.001'),
    ('molsurface.influence_tiny', dict(Mode='Local', InfluenceRadius=1e-20),
     'InfluenceRadius must be a finite number >= 0.001'),
    ('molsurface.influence_nan', dict(Mode='Local', InfluenceRadius=NAN),
     'InfluenceRadius must be a finite number >= 0.001'),
    ('molsurface.spacing_negative', dict(Spacing=-1), 'Spacing must be 0 (automatic)'),
    ('molsurface.spacing_nan', dict(Spacing=NAN), 'Spacing must be 0 (automatic)'),
    ('molsurface.spacing_tiny', dict(Spacing=1e-6), 'the limit is 2048 MiB'),
]
for name, properties, expected in surface_cases:
    expect(name, expected, lambda: MolecularPiSurface(Input=water, **properties))

print('%d cases' % cases)
check(cases >= 40, 'at least 40 cases')
finish()
