# Strata::ModuleArrows: the modules' arrows point one way, Rendering -> Core and IO -> Core,
# never Rendering -> IO. Checked three ways, so that no route back in passes unseen:
# - Rendering/vtk.module (-DSOURCE=<tree>) names Strata::IO in no DEPENDS or PRIVATE_DEPENDS
#   (TEST_DEPENDS may: the tests read files);
# - no file under Rendering/ includes a header of IO/;
# - the rendering library (-DRENDERING=...) loads no libStrataIO (ldd).
# The same checks on known-bad inputs must fail, or the check is blind.
cmake_policy(SET CMP0057 NEW) # IN_LIST in if()
foreach (v SOURCE RENDERING)
  if (NOT DEFINED ${v})
    message(FATAL_ERROR "CheckModuleArrows.cmake needs -D${v}=...")
  endif ()
endforeach ()

include("${CMAKE_CURRENT_LIST_DIR}/../cmake/StrataModuleDepends.cmake")

# Files of `files` that include a header of `headers` (file names).
function (including files headers out)
  set(found)
  foreach (file IN LISTS files)
    file(STRINGS "${file}" includes REGEX "^[ \t]*#[ \t]*include[ \t]*\"")
    foreach (line IN LISTS includes)
      string(REGEX REPLACE ".*\"([^\"]+)\".*" "\\1" name "${line}")
      if (name IN_LIST headers)
        list(APPEND found "${file}: ${name}")
      endif ()
    endforeach ()
  endforeach ()
  set(${out} "${found}" PARENT_SCOPE)
endfunction ()

# Blind-spot guards: a module file that depends on IO, privately, must be caught.
strata_module_link_dependencies("NAME\n  Strata::X\nDEPENDS\n  Strata::Core\nPRIVATE_DEPENDS\n  Strata::IO\nTEST_DEPENDS\n  Strata::IO\n" bad)
strata_module_link_dependencies("NAME\n  Strata::X\nDEPENDS\n  Strata::Core\nTEST_DEPENDS\n  Strata::IO\n" good)
if (NOT "Strata::IO" IN_LIST bad OR "Strata::IO" IN_LIST good)
  message(FATAL_ERROR "the vtk.module parser is blind: ${bad} / ${good}")
endif ()

file(READ "${SOURCE}/Rendering/vtk.module" module)
strata_module_link_dependencies("${module}" rendering_depends)
message("Rendering links: ${rendering_depends}")
if ("Strata::IO" IN_LIST rendering_depends)
  message(FATAL_ERROR "Rendering/vtk.module depends on Strata::IO: the arrow must go through Core")
endif ()

file(GLOB io_headers RELATIVE "${SOURCE}/IO" "${SOURCE}/IO/*.h")
file(GLOB_RECURSE rendering_files "${SOURCE}/Rendering/*.h" "${SOURCE}/Rendering/*.cxx")
list(LENGTH io_headers nh)
list(LENGTH rendering_files nr)
if (nh EQUAL 0 OR nr EQUAL 0)
  message(FATAL_ERROR "no IO headers (${nh}) or Rendering files (${nr}) found: the check is blind")
endif ()
including("${rendering_files}" "${io_headers}" wrong)
if (wrong)
  message(FATAL_ERROR "Rendering includes IO headers:\n${wrong}")
endif ()
# The include scan finds an IO include where there is one.
including("${SOURCE}/IO/vtkPagePoolReader.cxx" "${io_headers}" self)
if (NOT self)
  message(FATAL_ERROR "the include scan is blind (it sees no IO header in an IO source)")
endif ()

execute_process(COMMAND ldd "${RENDERING}" RESULT_VARIABLE rc OUTPUT_VARIABLE loads ERROR_VARIABLE err)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "ldd ${RENDERING} failed (${rc}): ${err}")
endif ()
if (loads MATCHES "libStrataIO")
  message(FATAL_ERROR "the rendering library loads libStrataIO")
endif ()
if (NOT loads MATCHES "libStrataCore")
  message(FATAL_ERROR "the rendering library loads no libStrataCore: the ldd check is blind")
endif ()
message("${nr} Rendering files include none of ${nh} IO headers; rendering loads no libStrataIO")
message("module arrows: ok")
