# Installs Strata from STRATA_BUILD into WORK and runs TestInstalled.py against that install tree
# alone (PYTHONPATH = its Python folder; the build tree is not on the path).
foreach (v STRATA_BUILD WORK PYTHON DESTINATION SCRIPT)
  if (NOT DEFINED ${v})
    message(FATAL_ERROR "RunInstalled.cmake needs -D${v}=...")
  endif ()
endforeach ()
file(REMOVE_RECURSE "${WORK}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${STRATA_BUILD}" --prefix "${WORK}"
  RESULT_VARIABLE rc OUTPUT_QUIET)
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "install failed (${rc})")
endif ()
execute_process(COMMAND "${CMAKE_COMMAND}" -E env "PYTHONPATH=${WORK}/${DESTINATION}" STRATA_OFFSCREEN=1
  "${PYTHON}" "${SCRIPT}" "${WORK}" RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if (NOT rc EQUAL 0)
  message(FATAL_ERROR "TestInstalled.py failed (${rc})")
endif ()
