"""The README's VTK Python program (plain `import vtk`, no ParaView), with checks."""
import vtk
from pisurfaces import vtkPiSurface, vtkPiPrimitive, vtkPiFlyingEdges

a, b = vtkPiPrimitive(), vtkPiPrimitive()         # two unit spheres
a.SetCenter(0.9, 0, 0); b.SetCenter(-0.9, 0, 0)
surface = vtkPiSurface(); surface.AddFactor(a); surface.AddFactor(b)
surface.SetBlending(0.25)                          # F = f_a f_b - r
mesher = vtkPiFlyingEdges(); mesher.SetPiSurface(surface); mesher.SetResolution(64)
area = vtk.vtkMassProperties(); area.SetInputConnection(mesher.GetOutputPort())
area.Update()
print("%d triangles, area %.3f" % (mesher.GetOutput().GetNumberOfPolys(), area.GetSurfaceArea()))

# The blend is one closed surface a bit smaller than the two unit spheres (2 * 4 pi).
triangles = mesher.GetOutput().GetNumberOfPolys()
assert triangles > 5000, triangles
assert 15.0 < area.GetSurfaceArea() < 8 * 3.141593, area.GetSurfaceArea()
print("VTK", vtk.vtkVersion.GetVTKVersion())
