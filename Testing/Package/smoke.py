"""The installed package, from pvpython without any path: the plugin by name, the cup
meshes, a molecule reads, the `pisurfaces` Python package imports."""
import sys

from paraview.simple import *  # noqa: F401,F403
from paraview import servermanager

LoadDistributedPlugin("PiSurfaces", ns=globals())
models = sys.argv[1]
cup = PiSurfaceModelReader(FileName=models + "/cup_a1.0.pisurf")
cup.UpdatePipeline()
cells = cup.GetDataInformation(0).GetNumberOfCells()
print("cup: %d triangles" % cells)
assert cells > 1000, cells

molecule = PiMoleculeReader(FileName="/usr/share/freesasa/test-data/1ubq.pdb")
atoms = servermanager.Fetch(molecule).GetNumberOfAtoms()
print("1ubq: %d atoms" % atoms)
assert atoms > 600, atoms

from pisurfaces import vtkPiSurface, vtkPiFlyingEdges  # noqa: E402
import pisurfaces  # noqa: E402
print("pisurfaces from", pisurfaces.__file__)
assert pisurfaces.__file__.startswith("/usr/lib/python3/dist-packages/")
print("smoke test passed")
