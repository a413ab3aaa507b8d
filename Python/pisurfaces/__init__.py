"""PiSurfaces: products of implicit surfaces (Pi-surfaces) for VTK and ParaView.

    from pisurfaces import vtkPiSurface, vtkPiPrimitive
"""
# The wrapped modules need VTK's core wrappers loaded first.
import vtkmodules.vtkCommonCore  # noqa: F401
import vtkmodules.vtkCommonDataModel  # noqa: F401
import vtkmodules.vtkCommonExecutionModel  # noqa: F401
import vtkmodules.vtkRenderingCore  # noqa: F401

from .vtkPiSurfacesFilters import *  # noqa: F401,F403
from .vtkPiSurfacesReaders import *  # noqa: F401,F403
from .vtkPiSurfacesRendering import *  # noqa: F401,F403
