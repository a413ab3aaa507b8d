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

# Debian 13's VTK CMake packages name the Python extension modules `vtkmodules/vtkX.so`
# while the package ships `vtkmodules/vtkX.cpython-313-x86_64-linux-gnu.so`. The
# generated targets file checks every file it names and stops at the first missing one,
# before any code of ours could fix the targets. So the affected targets files are copied
# into the build tree with the real file names, and find_package reads the copies.
function (pisurfaces_fix_python_module_names package_dir out_var)
  file(GLOB targets_files "${package_dir}/*targets-*.cmake" "${package_dir}/*-targets-*.cmake")
  list(REMOVE_DUPLICATES targets_files)
  set(patched FALSE)
  foreach (targets_file IN LISTS targets_files)
    file(READ "${targets_file}" text)
    string(REGEX MATCHALL "[^\"]*/vtkmodules/vtk[A-Za-z0-9]+\\.so" named "${text}")
    if (NOT named)
      continue ()
    endif ()
    list(REMOVE_DUPLICATES named)
    foreach (path IN LISTS named)
      string(REPLACE "\${_IMPORT_PREFIX}" "${pisurfaces_import_prefix}" real_path "${path}")
      if (EXISTS "${real_path}")
        continue ()
      endif ()
      get_filename_component(dir "${real_path}" DIRECTORY)
      get_filename_component(stem "${real_path}" NAME_WE)
      file(GLOB candidates "${dir}/${stem}.cpython-*.so")
      if (candidates)
        list(GET candidates 0 candidate)
        get_filename_component(candidate_name "${candidate}" NAME)
        get_filename_component(path_dir "${path}" DIRECTORY)
        string(REPLACE "${path}\"" "${path_dir}/${candidate_name}\"" text "${text}")
        set(patched TRUE)
      endif ()
    endforeach ()
    set(pisurfaces_patched_${targets_file} "${text}" PARENT_SCOPE)
  endforeach ()
  set(${out_var} ${patched} PARENT_SCOPE)
endfunction ()

# Copies the CMake package in package_dir to the build tree (one level of sub-folders,
# e.g. ParaView's vtk/), with the targets files fixed, and returns the copy's path. The
# copies compute _IMPORT_PREFIX from their own location, so it is pinned to the real one.
function (pisurfaces_overlay_package package_dir import_prefix out_var)
  set(pisurfaces_import_prefix "${import_prefix}")
  set(any FALSE)
  set(overlay "${CMAKE_BINARY_DIR}/cmake-overlay/${package_dir}")
  file(GLOB_RECURSE files RELATIVE "${package_dir}" "${package_dir}/*.cmake")
  foreach (dir IN ITEMS "" vtk)
    if (NOT IS_DIRECTORY "${package_dir}/${dir}")
      continue ()
    endif ()
    pisurfaces_fix_python_module_names("${package_dir}/${dir}" patched)
    if (patched)
      set(any TRUE)
    endif ()
    file(GLOB targets_files "${package_dir}/${dir}/*targets-*.cmake" "${package_dir}/${dir}/*-targets-*.cmake")
    foreach (targets_file IN LISTS targets_files)
      if (DEFINED pisurfaces_patched_${targets_file})
        set(pisurfaces_overlay_text_${targets_file} "${pisurfaces_patched_${targets_file}}")
      endif ()
    endforeach ()
  endforeach ()
  if (NOT any)
    set(${out_var} "${package_dir}" PARENT_SCOPE)
    return ()
  endif ()
  file(REMOVE_RECURSE "${overlay}")
  foreach (file IN LISTS files)
    set(source "${package_dir}/${file}")
    if (DEFINED pisurfaces_overlay_text_${source})
      set(text "${pisurfaces_overlay_text_${source}}")
    else ()
      file(READ "${source}" text)
    endif ()
    # The prefix computed from the file's own place would point into the build tree.
    string(REGEX REPLACE "get_filename_component\\(_IMPORT_PREFIX [^\n]*\n" "" text "${text}")
    string(REPLACE "set(_IMPORT_PREFIX \"\")" "set(_IMPORT_PREFIX \"\")" text "${text}")
    string(REGEX REPLACE "\nif\\(_IMPORT_PREFIX STREQUAL \"/\"\\)\n  set\\(_IMPORT_PREFIX \"\"\\)\nendif\\(\\)"
      "\nset(_IMPORT_PREFIX \"${import_prefix}\")" text "${text}")
    file(WRITE "${overlay}/${file}" "${text}")
  endforeach ()
  message(STATUS "PiSurfaces: Debian's VTK Python module file names fixed in ${overlay}")
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
file(WRITE "${CMAKE_BINARY_DIR}/pisurfaces-stack.txt" "${pisurfaces_stack}\n")

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
