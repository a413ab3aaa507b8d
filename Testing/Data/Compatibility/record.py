"""Records this folder's state file, trace and meshes with the plugin of the day.

    PV_PLUGIN_PATH=<build>/lib/paraview-plugins/PiSurfaces PYTHONPATH=<build>/lib/python \
        pvpython Testing/Data/Compatibility/record.py

Run once, with the plugin as it was before the XML was split by feature (main at
f433cb1), to write pipeline.pvsm (saved by SaveState), trace.py (recorded by
paraview.smtrace) and meshes.json (the points, cells, bounds and SHA-1 of the points
of every output). Python.TestPiStateCompatibility loads the first two with the plugin
of today and compares. The same pipeline is built by the test (keep them in step).
"""
import json
import os
import sys

from paraview import servermanager, smtrace
from paraview.simple import LoadPlugin, ResetSession, SaveState  # noqa: F401

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "Python"))
from TestPiStateCompatibility import build_state_pipeline, build_trace_pipeline, meshes  # noqa: E402

build_state_pipeline()
SaveState(os.path.join(HERE, "pipeline.pvsm"))
recorded = {"state": meshes()}
ResetSession()
smtrace.start_trace()
build_trace_pipeline()
trace = smtrace.stop_trace()
with open(os.path.join(HERE, "trace.py"), "w", encoding="utf-8") as f:
    f.write(trace)
recorded["trace"] = meshes()
with open(os.path.join(HERE, "meshes.json"), "w", encoding="utf-8") as f:
    json.dump(recorded, f, indent=1, sort_keys=True)
    f.write("\n")
print("recorded", sorted(recorded["state"]), sorted(recorded["trace"]))
