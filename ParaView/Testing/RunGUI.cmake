# The plugin in ParaView's GUI (see CMakeLists.txt): a pool (and its view and image) from
# StrataExamples, then `paraview --script=TestGUI.py` on a private Xvfb, then what the script
# wrote. MODE load: the script runs and the GUI exits (--exit). MODE refine: the GUI's event
# loop runs until the script, having watched the paged view refine by itself, leaves; refine-cs
# the same with the GUI the client of a pvserver. MODE resize: the main window resized by X
# requests between settled renders (TestGUI.py says what is measured).
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env --unset=DISPLAY
    "${EXAMPLES}" paged_volume "${WORK}/cxx.png" --data "${DATA}" --work "${WORK}" --keep-pools
    --camera "${WORK}/paged_volume.json"
  RESULT_VARIABLE result)
if (NOT result EQUAL 0)
  message(FATAL_ERROR "StrataExamples paged_volume failed (${result})")
endif ()
# A home of its own: the user's ParaView settings neither change the test nor are changed by
# it, and no welcome dialog (modal: it holds a client-server session's script back) shows.
file(WRITE "${WORK}/home/.config/ParaView/ParaView5.11.0.ini"
  "[General]\nGeneralSettings.ShowWelcomeDialog=0\n")
# refine-cs: the same against a pvserver (run-client-server), the GUI its client.
set(exit_after_script --exit)
set(launch "${PARAVIEW}")
if (MODE MATCHES "^refine" OR MODE STREQUAL "resize")
  set(exit_after_script)
endif ()
if (MODE STREQUAL "refine-cs")
  set(launch "${CLIENT_SERVER}" 1 "${MPIEXEC}" "${PVSERVER}" "${TIMEOUT}" "${PARAVIEW}")
endif ()
execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env "STRATA_PLUGIN=${PLUGIN}" "STRATA_POOL=${WORK}/tooth.spp"
    "STRATA_GUI_RESULT=${WORK}/result.txt" "STRATA_GUI_MODE=${MODE}" "STRATA_GUI_SCRIPT=${SCRIPT}"
    "HOME=${WORK}/home" "${WITH_XVFB}" ${launch} "--script=${SCRIPT}" ${exit_after_script}
  TIMEOUT 240
  RESULT_VARIABLE result)
file(READ "${WORK}/result.txt" found)
message(STATUS "The GUI's script found:\n${found}")
if (NOT result EQUAL 0)
  message(FATAL_ERROR "paraview exited with ${result}")
endif ()
if (MODE STREQUAL "resize")
  set(expected_lines "the volume kept its size through the resizes: 1")
elseif (MODE MATCHES "^refine")
  set(expected_lines "settled without interaction: 1" "renders after the first: ")
  if (MODE STREQUAL "refine")
    list(APPEND expected_lines "paging converged: 1")
  endif ()
else ()
  set(expected_lines "Strata Volume" "Strata Horizons" "volumes in scene: 1" "paged: 1")
endif ()
foreach (expected IN LISTS expected_lines)
  string(FIND "${found}" "${expected}" at)
  if (at EQUAL -1)
    message(FATAL_ERROR "the GUI's script did not find \"${expected}\"")
  endif ()
endforeach ()
if (MODE MATCHES "^refine")
  # The settled image against the C++ one (paged_volume's tolerance in TestPlugin: 0).
  string(REGEX MATCH "renders after the first: ([0-9]+)" unused "${found}")
  if (CMAKE_MATCH_1 LESS 2)
    message(FATAL_ERROR "the view did not render by itself (${CMAKE_MATCH_1} renders)")
  endif ()
  string(REGEX MATCH "against the C\\+\\+ image: max (-?[0-9]+)" unused "${found}")
  if (CMAKE_MATCH_1 STREQUAL "" OR CMAKE_MATCH_1 LESS 0 OR CMAKE_MATCH_1 GREATER TOLERANCE)
    message(FATAL_ERROR "the refined GUI image differs from the C++ one by ${CMAKE_MATCH_1} "
      "(at most ${TOLERANCE} of 255)")
  endif ()
endif ()
