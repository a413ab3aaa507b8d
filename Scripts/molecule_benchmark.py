# SPDX-License-Identifier: BSD-3-Clause
"""Molecular Pi-surfaces against the Gaussian (Blinn) Sigma-surface a VTK user would build:
vtkGaussianSplatter / vtkCheckerboardSplatter + vtkFlyingEdges3D on the same grid.

Rows: 1ubq Global at 0.5 A; 1a0q (3301 atoms) Local at 0.25 A; synthetic clusters of
copies of ubiquitin (1ubq without waters, 602 atoms, copies on a 40 A lattice, each
rotated) Local at 0.5 A, from ~10^3 to ~10^5 atoms (Global too up to ~10^4); the largest
again with ProjectVertices off (linear vertices, as flying edges places them). Run with pvpython (the plugin's
Python package on PYTHONPATH); threads: both vtkSMPTools backends.

Then Pi Ray Cast downstream of the molecular surface: the molecule path (the field rebuilt
from PiMoleculeCenters/Radii/Settings, MoleculeField::CastRay) against the product path
(the same output without PiMoleculeSettings: the PiSurfaceModel product of every atom)
where the latter is affordable, and alone on the large cases."""
import math
import sys
import time

import numpy as np
from vtkmodules.vtkCommonCore import vtkPoints, vtkSMPTools, vtkDoubleArray
from vtkmodules.vtkCommonDataModel import vtkMolecule, vtkPolyData
from vtkmodules.vtkFiltersCore import vtkFlyingEdges3D
from vtkmodules.vtkImagingHybrid import vtkGaussianSplatter, vtkCheckerboardSplatter
from pisurfaces import vtkPiMoleculeReader, vtkPiMoleculeSurface, vtkPiRayCaster

DATA = '/usr/share/freesasa/test-data/'
# exp(-5 d^2 / 3.5^2) = 0.3 at d = 1.72 A: a lone atom gets about a carbon's vdW radius.
LEVEL = 0.3


def read(name):
    r = vtkPiMoleculeReader()
    r.SetFileName(DATA + name)
    r.Update()
    m = vtkMolecule()
    m.DeepCopy(r.GetOutput())
    return m


def cluster(base, copies):
    """`copies` rotated copies of `base` on a cubic lattice of 40 A."""
    n = base.GetNumberOfAtoms()
    xyz = np.array([base.GetAtom(i).GetPosition() for i in range(n)])
    xyz -= xyz.mean(axis=0)
    z = [base.GetAtom(i).GetAtomicNumber() for i in range(n)]
    side = math.ceil(copies ** (1 / 3))
    rng = np.random.default_rng(1)
    m = vtkMolecule()
    m.Initialize()
    for c in range(copies):
        q = rng.normal(size=4)
        q /= np.linalg.norm(q)
        a, b, cc, d = q
        R = np.array([[a*a+b*b-cc*cc-d*d, 2*(b*cc-a*d), 2*(b*d+a*cc)],
                      [2*(b*cc+a*d), a*a-b*b+cc*cc-d*d, 2*(cc*d-a*b)],
                      [2*(b*d-a*cc), 2*(cc*d+a*b), a*a-b*b-cc*cc+d*d]])
        shift = 40.0 * np.array([c % side, (c // side) % side, c // (side * side)])
        for p, e in zip(xyz @ R.T + shift, z):
            m.AppendAtom(e, *p)
    return m


def pi_surface(molecule, mode, spacing, project=True):
    f = vtkPiMoleculeSurface()
    f.SetInputData(molecule)
    f.SetMode(mode)
    f.SetSpacing(spacing)
    f.SetProjectVertices(project)
    t = time.perf_counter()
    f.Update()
    return time.perf_counter() - t, f.GetOutput()


def splat(molecule, spacing, kind):
    """The Sigma-surface pipeline on the grid the Pi filter used: one Gaussian per atom
    of radius ~ the atom's reach, contoured at the level that gives the vdW radius."""
    n = molecule.GetNumberOfAtoms()
    pts = vtkPoints()
    pts.SetNumberOfPoints(n)
    for i in range(n):
        pts.SetPoint(i, molecule.GetAtom(i).GetPosition())
    poly = vtkPolyData()
    poly.SetPoints(pts)
    b = list(pts.GetBounds())
    for a in range(3):
        b[2 * a] -= 4.0
        b[2 * a + 1] += 4.0
    dims = [int(math.ceil((b[2 * a + 1] - b[2 * a]) / spacing)) + 1 for a in range(3)]
    s = vtkGaussianSplatter() if kind == 'gaussian' else vtkCheckerboardSplatter()
    s.SetInputData(poly)
    s.SetModelBounds(b)
    s.SetSampleDimensions(dims)
    if kind == 'gaussian':
        # vtkGaussianSplatter's Radius is relative to the longest side of the bounds.
        longest = max(b[1] - b[0], b[3] - b[2], b[5] - b[4])
        s.SetRadius(3.5 / longest)
    else:
        # vtkCheckerboardSplatter's Radius is in world units; its Footprint (voxels on
        # each side of the splat's voxel) must cover that radius.
        s.SetRadius(3.5)
        s.SetFootprint(int(math.ceil(3.5 / spacing)))
    s.SetExponentFactor(-5.0)
    s.ScalarWarpingOff()
    s.NormalWarpingOff()
    s.CappingOff()
    s.SetAccumulationModeToSum()  # Blinn: the sum of the Gaussians
    fe = vtkFlyingEdges3D()
    fe.SetInputConnection(s.GetOutputPort())
    fe.SetValue(0, LEVEL)
    fe.ComputeNormalsOn()
    t = time.perf_counter()
    fe.Update()
    return time.perf_counter() - t, fe.GetOutput(), dims


def main():
    quick = '--quick' in sys.argv
    ubq = read('1ubq.pdb')
    rows = []
    backends = ['Sequential', 'STDThread']
    cases = [('1ubq', ubq, 0, 0.5, True), ('1a0q', read('1a0q.pdb'), 1, 0.25, True)]
    sizes = [2, 16] if quick else [2, 16, 166]
    for copies in sizes:
        m = largest = cluster(ubq, copies)
        cases.append(('%d x 1ubq' % copies, m, 1, 0.5, True))
        if copies <= 16:
            cases.append(('%d x 1ubq' % copies, m, 0, 0.5, True))  # Global scaling
    # The largest again with ProjectVertices off: linear vertices, as flying edges'.
    cases.append(('%d x 1ubq' % sizes[-1], largest, 1, 0.5, False))
    print('| molecule | atoms | mode | spacing | backend | Pi surface | triangles | Gaussian splatter + FE | Checkerboard splatter + FE | Pi vs Gaussian | Pi vs Checkerboard | Pi us/atom |')
    print('|---|---|---|---|---|---|---|---|---|---|---|---|')
    for name, m, mode, spacing, project in cases:
        for backend in backends:
            vtkSMPTools.SetBackend(backend)
            tp, out = pi_surface(m, mode, spacing, project)
            tg, _, dims = splat(m, spacing, 'gaussian')
            tc, _, _ = splat(m, spacing, 'checkerboard')
            n = m.GetNumberOfAtoms()
            print('| %s | %d | %s | %.2f | %s | %.2f s | %d | %.2f s | %.2f s | %.2fx | %.2fx | %.1f |' % (
                name, n, ('Global' if mode == 0 else 'Local') + ('' if project else ', linear vertices'),
                spacing, backend, tp,
                out.GetNumberOfCells(), tg, tc, tg / tp, tc / tp, 1e6 * tp / n))
            sys.stdout.flush()
    return ubq, largest  # for the ray-casting table


def cast(surface_output, view, n, molecule=True):
    data = surface_output
    if not molecule:
        data = vtkPolyData()
        data.ShallowCopy(surface_output)
        fd = type(surface_output.GetFieldData())()
        fd.DeepCopy(surface_output.GetFieldData())
        fd.RemoveArray('PiMoleculeSettings')
        data.SetFieldData(fd)
    c = vtkPiRayCaster()
    c.SetInputData(data)
    c.SetViewMode(view)
    c.SetResolution(n, n)
    t = time.perf_counter()
    c.Update()
    return time.perf_counter() - t, c.GetOutput().GetNumberOfPoints()


def rays(ubq, big):
    six, minus_z = vtkPiRayCaster.SIX_AXIS_VIEWS, vtkPiRayCaster.MINUS_Z
    cases = [('1ubq', ubq, 0, six, 64, True), ('1ubq', ubq, 0, six, 512, False),
             ('1ubq', ubq, 1, six, 512, False),
             ('%d x 1ubq' % (big.GetNumberOfAtoms() // ubq.GetNumberOfAtoms()), big, 1, minus_z, 512,
              False)]
    print()
    print('| molecule | atoms | mode | views | pixels | backend | molecule path | rays/s | product path | ratio | hits |')
    print('|---|---|---|---|---|---|---|---|---|---|---|')
    for name, m, mode, view, n, compare in cases:
        f = vtkPiMoleculeSurface()
        f.SetInputData(m)
        f.SetMode(mode)
        f.SetSpacing(0.5)
        f.Update()
        out = f.GetOutput()
        for backend in ['Sequential', 'STDThread']:
            vtkSMPTools.SetBackend(backend)
            tm, hits = cast(out, view, n)
            views = 6 if view == six else 1
            product, ratio = '-', '-'
            if compare:
                tp, hp = cast(out, view, n, molecule=False)
                product, ratio = '%.2f s (%d hits)' % (tp, hp), '%.1fx' % (tp / tm)
            print('| %s | %d | %s | %s | %d² | %s | %.2f s | %.2f M | %s | %s | %d |' % (
                name, m.GetNumberOfAtoms(), 'Global' if mode == 0 else 'Local',
                'six axis' if view == six else '-Z', n, backend, tm, views * n * n / tm / 1e6,
                product, ratio, hits))
            sys.stdout.flush()


if __name__ == '__main__':
    rays(*main())
