# trace generated using paraview version 5.11.0
#import paraview
#paraview.compatibility.major = 5
#paraview.compatibility.minor = 11

#### import the simple module from the paraview
from paraview.simple import *
#### disable automatic camera reset on 'Show'
paraview.simple._DisableFirstRenderCameraReset()

# create a new 'Pi Primitive'
handle = PiPrimitive(registrationName='handle')
handle.Type = 'Polynomial'
handle.Center = [2.2, 0.0, -1.0]
handle.Expression = '(x^2+z^2+y^2+0.5-0.01)^2-2*(x^2+z^2)'

# create a new 'Pi Primitive'
base = PiPrimitive(registrationName='base')
base.Type = 'Polynomial'
base.Expression = '1/8*x^2+1/8*y^2+(z+2)^2-0.1'

# create a new 'Pi Primitive'
bowl = PiPrimitive(registrationName='bowl')
bowl.Type = 'Polynomial'
bowl.Expression = '((z+1)^2+10*x^2+10*y^2+19)^2-800*(x^2+y^2)'

# create a new 'Pi Product'
cup = PiProduct(registrationName='cup', Input=[handle, base, bowl])
cup.Resolution = 24
cup.Bounds = [-2.2, 3.4, -2.1, 2.1, -2.55, 0.25]
cup.Blending = 10.0

# create a new 'Pi Surface'
surface = PiSurface(registrationName='surface')
surface.Resolution = 20
surface.Method = 'Ray Cast Triangulation'
surface.OverrideBlending = 1
surface.Blending = 0.35

# create a new 'Pi Molecule Reader'
ubq = PiMoleculeReader(registrationName='ubq', FileName='/usr/share/freesasa/test-data/1ubq.pdb')

# create a new 'Molecular Pi Surface'
molecule = MolecularPiSurface(registrationName='molecule', Input=ubq)
molecule.RadiusArray = [None, '0 0 0 0 radius']
molecule.Spacing = 1.5

#================================================================
# addendum: following script captures some of the application
# state to faithfully reproduce the visualization during playback
#================================================================

#--------------------------------------------
# uncomment the following to render all views
# RenderAllViews()
# alternatively, if you want to write images, you can use SaveScreenshot(...).