# One plugin scene test (see CMakeLists.txt): the C++ reference, then pvbatch.
if (NOT EXISTS "${EXAMPLES}")
  message(FATAL_ERROR "${EXAMPLES} is missing: build the standalone tree first (scripts/test does)")
endif ()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
# The standalone build renders through its EGL window: no display for it.
execute_process(
  COMMAND "${CMAKE_COMMAND}" -E env --unset=DISPLAY
    "${EXAMPLES}" "${SCENE}" "${WORK}/cxx_${SCENE}.png" --data "${DATA}" --work "${WORK}"
    --camera "${WORK}/${SCENE}.json" --keep-pools
  RESULT_VARIABLE result)
if (NOT result EQUAL 0)
  message(FATAL_ERROR "StrataExamples ${SCENE} failed (${result})")
endif ()
execute_process(
  COMMAND "${WITH_XVFB}" "${PVBATCH}" "${SCRIPT}" --plugin "${PLUGIN}" --scene "${SCENE}"
    --work "${WORK}" --data "${DATA}" --tolerance "${TOLERANCE}"
  RESULT_VARIABLE result)
if (NOT result EQUAL 0)
  message(FATAL_ERROR "pvbatch ${SCENE} failed (${result})")
endif ()
