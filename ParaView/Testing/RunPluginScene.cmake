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
# With RANKS (more than 1), pvbatch runs under MPI: each rank draws its box of the scene and
# IceT blends them, against the same one-process C++ image.
set(launch "${PVBATCH}")
if (RANKS GREATER 1)
  set(launch "${CMAKE_COMMAND}" -E env OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
    OMPI_MCA_rmaps_base_oversubscribe=1 "${MPIEXEC}" -np ${RANKS} --bind-to none "${PVBATCH}")
endif ()
execute_process(
  COMMAND "${WITH_XVFB}" ${launch} "${SCRIPT}" --plugin "${PLUGIN}" --scene "${SCENE}"
    --work "${WORK}" --data "${DATA}" --tolerance "${TOLERANCE}"
  RESULT_VARIABLE result)
if (NOT result EQUAL 0)
  message(FATAL_ERROR "pvbatch ${SCENE} failed (${result})")
endif ()
