"""Instructions (valgrind's callgrind) of the mesher and the ray caster on the cup,
the table and ten spheres: a measure of the code's work that, unlike time, does not
depend on what else the machine runs. Compare two builds with it:

    python3 Scripts/instruction_counts.py build/lib/python [other/build/lib/python]

Each workload runs in its own process on one thread; the count of the same process
doing nothing but the set-up is subtracted (for the triangulation, the set-up includes
its input: the six axis views cast at 128²; for the molecule, reading 1ubq).
PISURF_COUNT_KINDS chooses the workloads (default "mesh cast triangulate molecule":
the molecule kind meshes 1ubq at spacing 0.5 Å in Global and Local mode). Needs
valgrind.
"""
import os
import re
import subprocess
import sys

MODELS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Testing", "Data",
                      "Models")

WORKLOAD = r"""
import sys
from pisurfaces import (vtkPiSurface, vtkPiPrimitive, vtkPiFlyingEdges, vtkPiRayCaster,
                        vtkPiImageTriangulator, vtkPiMoleculeReader, vtkPiMoleculeSurface)
kind, model = sys.argv[1], sys.argv[2]
s = vtkPiSurface()
if model.startswith("1ubq"):
    reader = vtkPiMoleculeReader()
    reader.SetFileName("/usr/share/freesasa/test-data/1ubq.pdb")
    reader.Update()
elif model == "10_spheres":
    keep = []
    for i in range(10):
        p = vtkPiPrimitive()
        p.SetCenter(1.2 * (i % 5) - 2.4, 1.2 * (i // 5) - 0.6, 0.1 * i)
        p.SetRadius(0.8)
        s.AddFactor(p)
        keep.append(p)
    s.SetBlending(0.5)
else:
    assert s.LoadModel(sys.argv[3] + "/" + model + ".pisurf")


def six_views(resolution):
    c = vtkPiRayCaster()
    c.SetPiSurface(s)
    c.SetViewMode(vtkPiRayCaster.SIX_AXIS_VIEWS)
    c.SetResolution(resolution, resolution)
    return c


a = None
if kind == "mesh":
    a = vtkPiFlyingEdges()
    a.SetPiSurface(s)
    a.SetResolution(200)
elif kind == "cast":
    a = six_views(384)
elif kind.endswith("triangulate"):
    c = six_views(128)
    c.Update()
    if kind == "triangulate":
        a = vtkPiImageTriangulator()
        a.SetInputData(c.GetOutput())
elif kind == "molecule":
    a = vtkPiMoleculeSurface()
    a.SetInputConnection(reader.GetOutputPort())
    a.SetMode(1 if model == "1ubq_local" else 0)
    a.SetSpacing(0.5)
if a is not None:
    a.Update()
"""


def count(python_dir, kind, model):
    env = dict(os.environ, PYTHONPATH=python_dir, VTK_SMP_MAX_THREADS="1")
    out = subprocess.run(
        ["valgrind", "--tool=callgrind", "--callgrind-out-file=/dev/null", "/usr/bin/python3",
         "-c", WORKLOAD, kind, model, MODELS], env=env, capture_output=True, text=True,
        check=True).stderr
    match = re.search(r"Collected : (\d+)", out)
    if not match:
        raise RuntimeError("callgrind gave no count:\n" + out)
    return int(match.group(1))


def main():
    builds = sys.argv[1:]
    if not builds:
        sys.exit(__doc__)
    kinds = os.environ.get("PISURF_COUNT_KINDS", "mesh cast triangulate molecule").split()
    rows = [(kind, model) for kind in kinds
            for model in (("1ubq_global", "1ubq_local") if kind == "molecule"
                          else ("cup_a1.0", "table", "10_spheres"))]
    header = "| workload | " + " | ".join("build %d (M instr.)" % (i + 1)
                                         for i in range(len(builds)))
    print(header + (" | change |" if len(builds) == 2 else " |"))
    print("|---" * (len(builds) + 1 + (len(builds) == 2)) + "|")
    for kind, model in rows:
        counts = []
        for build in builds:
            idle = count(build, "none_triangulate" if kind == "triangulate" else "none", model)
            counts.append(count(build, kind, model) - idle)
        line = "| %s %s | " % (kind, model) + " | ".join("%.1f" % (c / 1e6) for c in counts)
        if len(builds) == 2:
            line += " | %+.2f %%" % (100.0 * (counts[1] - counts[0]) / counts[0])
        print(line + " |")


main()
