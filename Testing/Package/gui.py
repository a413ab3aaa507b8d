"""Run by `paraview --plugins=PiSurfaces --script=gui.py`: the plugin is loaded and its
proxies exist. Writes PASSED or FAILED to the file named by PISURF_GUI_RESULT."""
import os

result = "FAILED"
try:
    from paraview.simple import *  # noqa: F401,F403
    from paraview import servermanager
    plm = servermanager.vtkSMProxyManager.GetProxyManager().GetPluginManager()
    info = plm.GetLocalInformation()
    loaded = [info.GetPluginName(i) for i in range(info.GetNumberOfPlugins())
              if info.GetPluginLoaded(i)]
    source = PiSurface()
    source.UpdatePipeline()
    if "PiSurfaces" in loaded and source.GetDataInformation(0).GetNumberOfCells() > 1000:
        result = "PASSED"
    result += " plugins: " + ", ".join(loaded)
except Exception as e:  # noqa: BLE001
    result = "FAILED %s" % e
with open(os.environ["PISURF_GUI_RESULT"], "w") as f:
    f.write(result + "\n")
os._exit(0)
