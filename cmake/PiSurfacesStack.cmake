# SPDX-License-Identifier: BSD-3-Clause
# Finds the stack PiSurfaces builds against, in one place: ParaView with its bundled VTK
# (PISURFACES_PARAVIEW=ON, the default: Debian 12's 5.11, Debian 13's 5.13) or plain VTK
# (OFF: Debian 13's VTK 9.3, our VTK modules and their Python wrapping only). Packaging
# quirks of Debian's CMake packages are handled here, and the version found is written
# to <build>/pisurfaces-stack.txt for ./run to print.

set(pisurfaces_vtk_components
  CommonCore CommonDataModel CommonExecutionModel CommonSystem CommonTransforms
  FiltersCore FiltersGeneral FiltersSources ImagingHybrid IOCore IOXML DomainsChemistry
  IOChemistry ParallelCore
  WrappingPythonCore Python
  TestingRendering RenderingOpenGL2 RenderingCore InteractionStyle InteractionWidgets
  RenderingFreeType)

# Debian 13's ParaView CMake package names its Python extension modules
# `.../dist-packages/{vtkmodules,paraview/modules}/vtkX.so` while the package ships
# `vtkX.cpython-313-x86_64-linux-gnu.so`. The generated targets files check every file
# they name and stop at the first missing one, inside find_package, before any code of
# ours could fix the targets' IMPORTED_LOCATION. So the package is copied into the build
# tree with the real file names, and find_package reads the copy. Returns package_dir
# itself when nothing needs fixing (Debian 12).
function (pisurfaces_overlay_package package_dir import_prefix out_var)
  file(GLOB_RECURSE files RELATIVE "${package_dir}" "${package_dir}/*.cmake")
  set(overlay "${CMAKE_BINARY_DIR}/cmake-overlay/${package_dir}")
  set(fixed 0)
  foreach (file IN LISTS files)
    file(READ "${package_dir}/${file}" text)
    if (file MATCHES "targets-[a-z]+\\.cmake$")
      string(REGEX MATCHALL "[^\"]*/dist-packages/[^\"]*/vtk[A-Za-z0-9_]+\\.so\"" named "${text}")
      list(REMOVE_DUPLICATES named)
      foreach (quoted IN LISTS named)
        string(REPLACE "\"" "" path "${quoted}")
        string(REPLACE "\${_IMPORT_PREFIX}" "${import_prefix}" real_path "${path}")
        if (EXISTS "${real_path}")
          continue ()
        endif ()
        get_filename_component(dir "${real_path}" DIRECTORY)
        get_filename_component(stem "${real_path}" NAME_WE)
        file(GLOB candidates "${dir}/${stem}.cpython-*.so")
        if (candidates)
          list(GET candidates 0 candidate)
          get_filename_component(name "${candidate}" NAME)
          get_filename_component(path_dir "${path}" DIRECTORY)
          string(REPLACE "${quoted}" "${path_dir}/${name}\"" text "${text}")
          math(EXPR fixed "${fixed} + 1")
        endif ()
      endforeach ()
    endif ()
    # The copy would compute the install prefix from its own place: pin the real one.
    get_filename_component(real_dir "${package_dir}/${file}" DIRECTORY)
    string(REPLACE "set(_vtk_module_import_prefix \"\${CMAKE_CURRENT_LIST_DIR}\")"
      "set(_vtk_module_import_prefix \"${real_dir}\")" text "${text}")
    string(REGEX REPLACE "get_filename_component\\(_IMPORT_PREFIX [^\n]*\n" "" text "${text}")
    string(REGEX REPLACE "if\\(_IMPORT_PREFIX STREQUAL \"/\"\\)\n  set\\(_IMPORT_PREFIX \"\"\\)\nendif\\(\\)"
      "set(_IMPORT_PREFIX \"${import_prefix}\")" text "${text}")
    set(text_${file} "${text}")
  endforeach ()
  if (fixed EQUAL 0)
    set(${out_var} "${package_dir}" PARENT_SCOPE)
    return ()
  endif ()
  file(REMOVE_RECURSE "${overlay}")
  foreach (file IN LISTS files)
    file(WRITE "${overlay}/${file}" "${text_${file}}")
  endforeach ()
  # The package's other files (templates, XSL, scripts) as links to the originals.
  file(GLOB_RECURSE others RELATIVE "${package_dir}" "${package_dir}/*")
  list(FILTER others EXCLUDE REGEX "\\.cmake$")
  foreach (file IN LISTS others)
    get_filename_component(dir "${overlay}/${file}" DIRECTORY)
    file(MAKE_DIRECTORY "${dir}")
    file(CREATE_LINK "${package_dir}/${file}" "${overlay}/${file}" SYMBOLIC)
  endforeach ()
  message(STATUS "PiSurfaces: ${fixed} Python module file names of Debian's ParaView fixed in ${overlay}")
  set(${out_var} "${overlay}" PARENT_SCOPE)
endfunction ()

option(PISURFACES_PARAVIEW
  "Build the ParaView plugin against ParaView (OFF: only the VTK modules, against plain VTK)"
  ON)

if (PISURFACES_PARAVIEW)
  # ParaView's VTK::mpi target refers to MPI::MPI_C: find MPI first.
  find_package(MPI COMPONENTS C)
  find_path(pisurfaces_paraview_config NAMES ParaViewConfig.cmake paraview-config.cmake
    PATH_SUFFIXES lib/cmake/paraview-5.13 lib/${CMAKE_LIBRARY_ARCHITECTURE}/cmake/paraview-5.13
    NO_CACHE)
  if (pisurfaces_paraview_config AND NOT ParaView_DIR)
    # Debian 13: /usr/lib/x86_64-linux-gnu/cmake/paraview-5.13 → prefix /usr.
    get_filename_component(prefix "${pisurfaces_paraview_config}/../../../.." ABSOLUTE)
    pisurfaces_overlay_package("${pisurfaces_paraview_config}" "${prefix}" ParaView_DIR)
    set(ParaView_DIR "${ParaView_DIR}" CACHE PATH "ParaView's CMake package" FORCE)
  endif ()
  find_package(ParaView REQUIRED COMPONENTS RemotingServerManager RemotingCore
    OPTIONAL_COMPONENTS pqApplicationComponents pqComponents pqCore)
  find_package(VTK REQUIRED COMPONENTS ${pisurfaces_vtk_components}
    PATHS "${ParaView_DIR}/vtk" NO_DEFAULT_PATH)
  set(pisurfaces_stack "ParaView ${ParaView_VERSION}")
  if (DEFINED ParaView_VERSION_PATCH AND NOT ParaView_VERSION MATCHES "\\.[0-9]+\\.")
    set(pisurfaces_stack "ParaView ${ParaView_VERSION}.${ParaView_VERSION_PATCH}")
  endif ()
else ()
  find_package(VTK REQUIRED COMPONENTS ${pisurfaces_vtk_components})
  set(pisurfaces_stack "VTK ${VTK_VERSION}")
endif ()
message(STATUS "PiSurfaces: building against ${pisurfaces_stack}")

# gemmi: header-only in Debian 12; Debian 13's 0.6 compiles part of itself into
# libgemmi_cpp.a, which the molecule reader must link. (Its CMake package cannot be used:
# it names the program /usr/bin/gemmi of another package and stops when it is missing.)
find_package(ZLIB REQUIRED)
find_library(PISURFACES_GEMMI_CPP NAMES gemmi_cpp)
if (PISURFACES_GEMMI_CPP)
  add_library(PiSurfaces::gemmi_cpp STATIC IMPORTED)
  set_target_properties(PiSurfaces::gemmi_cpp PROPERTIES
    IMPORTED_LOCATION "${PISURFACES_GEMMI_CPP}"
    INTERFACE_LINK_LIBRARIES ZLIB::ZLIB)
endif ()
file(WRITE "${CMAKE_BINARY_DIR}/pisurfaces-stack.txt" "${pisurfaces_stack}\n")

# The Qt that ParaView's client libraries use (5.11: Qt 5 only; 5.13 says which).
if (DEFINED PARAVIEW_QT_MAJOR_VERSION)
  set(PISURFACES_QT "Qt${PARAVIEW_QT_MAJOR_VERSION}")
else ()
  set(PISURFACES_QT Qt5)
endif ()

# The Qt editor links ParaView's pqComponents, whose imported link interface names
# third-party targets of libraries Debian ships inside ParaView's VTK (libxml2, HDF5,
# Boost, NetCDF). Their development packages are not needed to link against the shared
# libraries: stand-in interface targets satisfy CMake's check when a package is absent.
if (TARGET ParaView::pqComponents)
  find_package(LibXml2 QUIET)
  find_package(Boost QUIET)
  foreach (dependency IN ITEMS LibXml2::LibXml2 Boost::boost hdf5::hdf5 hdf5::hdf5_hl
                              NetCDF::NetCDF)
    if (NOT TARGET ${dependency})
      add_library(${dependency} INTERFACE IMPORTED)
    endif ()
  endforeach ()
endif ()
