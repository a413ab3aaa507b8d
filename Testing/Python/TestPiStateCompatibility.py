"""A state file and a Python trace saved with an older plugin still load and give the
same meshes (pvpython).

    pvpython TestPiStateCompatibility.py <folder of the state, trace and meshes>

Testing/Data/Compatibility/ holds pipeline.pvsm (SaveState) and trace.py
(paraview.smtrace), both recorded by record.py there with the plugin as it was before
its XML was split by feature (Plugin/PiSurfaces.xml, with the base proxies PiMeshingBase
and PiMesherBase), and meshes.json, the meshes that plugin gave. The pipeline covers
every family of proxies whose properties moved or whose base changed: the cup as three
Pi Primitive sources and a Pi Product, a Pi Surface and a Pi Surface Model Reader with
the blending overridden (the properties PiMesherBase gave them) and the reader on the
ray-cast method, a Molecular Pi Surface of 1ubq (Pi Molecule Reader) and a Clip by a
Pi Surface Function. Coarse resolutions keep the files small.

The state's and the trace's paths to the checkout's models are rewritten to this
checkout (PISURF_MODELS_DIR); /usr/share paths stay. Each output (every port of every
source) after LoadState and after running the trace must equal, in points, cells,
bounds and SHA-1 of the points, both the same pipeline built now and the recorded
meshes.
"""
import hashlib
import json
import os
import re
import sys
import tempfile

from paraview import servermanager
from paraview.simple import (Clip, FindSource, GetSources, LoadState, MolecularPiSurface,
                             PiMoleculeReader, PiPrimitive, PiProduct, PiSurface,
                             PiSurfaceModelReader, ResetSession, Sphere)
from vtkmodules.util.numpy_support import vtk_to_numpy

from pitesting import check, finish

UBQ = "/usr/share/freesasa/test-data/1ubq.pdb"
MODELS = os.environ.get("PISURF_MODELS_DIR") or os.path.join(
    os.path.dirname(os.path.abspath(__file__)), "..", "Data", "Models")
CUP_BOUNDS = [-2.2, 3.4, -2.1, 2.1, -2.55, 0.25]
TWO_SPHERES = ('{"pisurf": 1, "blending": 0.25, "primitives": ['
               '{"type": "sphere", "center": [0.6, 0, 0], "radius": 1}, '
               '{"type": "sphere", "center": [-0.6, 0, 0], "radius": 1}]}')


def build_cup():
    handle = PiPrimitive(registrationName="handle", Type="Polynomial",
                         Expression="(x^2+z^2+y^2+0.5-0.01)^2-2*(x^2+z^2)", Center=[2.2, 0, -1])
    base = PiPrimitive(registrationName="base", Type="Polynomial",
                       Expression="1/8*x^2+1/8*y^2+(z+2)^2-0.1")
    bowl = PiPrimitive(registrationName="bowl", Type="Polynomial",
                       Expression="((z+1)^2+10*x^2+10*y^2+19)^2-800*(x^2+y^2)")
    return PiProduct(registrationName="cup", Input=[handle, base, bowl], Blending=10,
                     Resolution=24, Bounds=CUP_BOUNDS)


def build_molecule():
    ubq = PiMoleculeReader(registrationName="ubq", FileName=UBQ)
    return MolecularPiSurface(registrationName="molecule", Input=ubq, Spacing=1.5)


def build_state_pipeline():
    """The pipeline of pipeline.pvsm."""
    build_cup()
    PiSurface(registrationName="surface", Resolution=24, OverrideBlending=1, Blending=0.4)
    PiSurfaceModelReader(registrationName="reader",
                         FileName=os.path.join(MODELS, "two_spheres_d1.1.pisurf"),
                         Resolution=16, Method="Ray Cast Triangulation", OverrideBlending=1,
                         Blending=0.3, GeneratePrimitives=0)
    build_molecule()
    ball = Sphere(registrationName="ball", Radius=1.5, ThetaResolution=16, PhiResolution=16)
    clip = Clip(registrationName="clip", Input=ball, ClipType="Pi Surface Function")
    clip.ClipType.Model = TWO_SPHERES


def build_trace_pipeline():
    """The pipeline of trace.py (recorded by smtrace as a user would build it)."""
    build_cup()
    PiSurface(registrationName="surface", Resolution=20, Method="Ray Cast Triangulation",
              OverrideBlending=1, Blending=0.35)
    build_molecule()


def meshes():
    """{"source:port": description} of every data-set output of the session."""
    result = {}
    for (name, _), proxy in sorted(GetSources().items()):
        for port in range(proxy.GetNumberOfOutputPorts()):
            data = servermanager.Fetch(proxy, idx=port)
            if data is None or not data.IsA("vtkDataSet"):
                continue
            sha = hashlib.sha1()
            if data.IsA("vtkPointSet") and data.GetPoints() is not None:
                sha.update(vtk_to_numpy(data.GetPoints().GetData()).tobytes())
            result["%s:%d" % (name, port)] = {
                "points": data.GetNumberOfPoints(), "cells": data.GetNumberOfCells(),
                "bounds": [repr(b) for b in data.GetBounds()], "points_sha1": sha.hexdigest()}
    return result


def with_this_checkout(text):
    """Paths to the models of the checkout that recorded the files, to this one's."""
    return re.sub(r"[^\"'<>\s]*/Testing/Data/Models/",
                  lambda _: os.path.abspath(MODELS).replace("\\", "/") + "/", text)


def compare(what, got, expected):
    check(sorted(got) == sorted(expected), "%s: outputs %s, expected %s"
          % (what, sorted(got), sorted(expected)))
    for key in sorted(expected):
        if key in got:
            check(got[key] == expected[key], "%s: %s is %s, expected %s"
                  % (what, key, got[key], expected[key]))
    nonempty = [k for k in expected if expected[k]["cells"] > 0]
    check(len(nonempty) >= 4, "%s: %d non-empty outputs" % (what, len(nonempty)))


def main(folder):
    with open(os.path.join(folder, "meshes.json"), encoding="utf-8") as f:
        recorded = json.load(f)

    # The state file, with its model path pointing into this checkout.
    with open(os.path.join(folder, "pipeline.pvsm"), encoding="utf-8") as f:
        state = with_this_checkout(f.read())
    with tempfile.TemporaryDirectory() as scratch:
        path = os.path.join(scratch, "pipeline.pvsm")
        with open(path, "w", encoding="utf-8") as f:
            f.write(state)
        ResetSession()
        LoadState(path)
    check(FindSource("cup") is not None and len(FindSource("cup").Input) == 3,
          "state: the cup and its three inputs")
    reader = FindSource("reader")
    check(reader is not None and reader.OverrideBlending == 1 and reader.Blending == 0.3,
          "state: the reader's blending override (a property of the former PiMesherBase)")
    loaded = meshes()
    ResetSession()
    build_state_pipeline()
    fresh = meshes()
    compare("state vs fresh", loaded, fresh)
    compare("state vs recorded", loaded, recorded["state"])

    # The trace, run as a user runs a saved trace.
    with open(os.path.join(folder, "trace.py"), encoding="utf-8") as f:
        trace = with_this_checkout(f.read())
    ResetSession()
    exec(compile(trace, "trace.py", "exec"), {"__name__": "__main__"})
    traced = meshes()
    ResetSession()
    build_trace_pipeline()
    fresh = meshes()
    compare("trace vs fresh", traced, fresh)
    compare("trace vs recorded", traced, recorded["trace"])
    finish()


if __name__ == "__main__":
    if len(sys.argv) < 2:
        sys.exit(__doc__)
    main(sys.argv[1])
