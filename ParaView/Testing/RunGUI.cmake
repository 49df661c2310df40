# The plugin in ParaView's GUI (see CMakeLists.txt): a pool from StrataExamples, then
# `paraview --script=TestGUI.py --exit` on a private Xvfb, then what the script wrote.
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env --unset=DISPLAY
    "${EXAMPLES}" paged_volume "${WORK}/cxx.png" --data "${DATA}" --work "${WORK}" --keep-pools
  RESULT_VARIABLE result)
if (NOT result EQUAL 0)
  message(FATAL_ERROR "StrataExamples paged_volume failed (${result})")
endif ()
execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env "STRATA_PLUGIN=${PLUGIN}" "STRATA_POOL=${WORK}/tooth.spp"
    "STRATA_GUI_RESULT=${WORK}/result.txt"
    "${WITH_XVFB}" "${PARAVIEW}" "--script=${SCRIPT}" --exit
  RESULT_VARIABLE result)
file(READ "${WORK}/result.txt" found)
message(STATUS "The GUI's script found:\n${found}")
if (NOT result EQUAL 0)
  message(FATAL_ERROR "paraview exited with ${result}")
endif ()
foreach (expected IN ITEMS "Strata Volume" "Strata Horizons" "volumes in scene: 1" "paged: 1")
  string(FIND "${found}" "${expected}" at)
  if (at EQUAL -1)
    message(FATAL_ERROR "the GUI's script did not find \"${expected}\"")
  endif ()
endforeach ()
