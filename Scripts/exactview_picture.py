"""The tutorial's picture of the exact view beside the mesh, at the same zoom, on the
cup's handle (a torus of minor radius 0.1): Pi Surface Model Reader at Resolution 64
drawn as Surface (left) and as Pi Exact Surface (right).

Usage: pvpython Scripts/exactview_picture.py MODELS_DIR OUTPUT.png"""
import os
import sys

from paraview.simple import (GetActiveViewOrCreate, PiSurfaceModelReader, Render,
                             SaveScreenshot, Show)
from vtkmodules.vtkFiltersCore import vtkImageAppend
from vtkmodules.vtkIOImage import vtkPNGReader, vtkPNGWriter

models, output = sys.argv[1], sys.argv[2]
cup = PiSurfaceModelReader(FileName=os.path.join(models, "cup_a1.0.pisurf"), Resolution=64)
view = GetActiveViewOrCreate("RenderView")
view.OrientationAxesVisibility = 0
view.Background = [0.32, 0.34, 0.43]
display = Show(cup, view)
display.ColorArrayName = ["POINTS", ""]
display.DiffuseColor = [0.85, 0.75, 0.55]
display.Specular = 0.3
Render(view)  # the first render resets the camera; the zoom comes after it
view.CameraPosition = [3.4, -2.4, 0.2]
view.CameraFocalPoint = [1.9, 0.0, -0.7]
view.CameraViewUp = [0, 0, 1]
view.CameraViewAngle = 30
parts = []
for representation in ("Surface", "Pi Exact Surface"):
    display.SetRepresentationType(representation)
    Render(view)
    path = output + ".%d.png" % len(parts)
    SaveScreenshot(path, view, ImageResolution=[400, 400])
    parts.append(path)
append = vtkImageAppend()
for path in parts:
    reader = vtkPNGReader()
    reader.SetFileName(path)
    append.AddInputConnection(reader.GetOutputPort())
writer = vtkPNGWriter()
writer.SetFileName(output)
writer.SetInputConnection(append.GetOutputPort())
writer.Write()
for path in parts:
    os.remove(path)
os._exit(0)
