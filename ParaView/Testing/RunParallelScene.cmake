# The parallel test (see CMakeLists.txt and TestParallel.py): the scene's data, its brick pool
# (the standalone build's strata-convert), pvbatch over MPI with 1, 2 and 4 ranks, a 2-rank
# pvserver with a pvpython client (1 and 2 ranks), the comparison with the 1-rank images.
if (NOT EXISTS "${CONVERT}")
  message(FATAL_ERROR "${CONVERT} is missing: build the standalone tree first (scripts/test does)")
endif ()
file(REMOVE_RECURSE "${WORK}")
file(MAKE_DIRECTORY "${WORK}")
function (run what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE result)
  if (NOT result EQUAL 0)
    message(FATAL_ERROR "${what} failed (${result})")
  endif ()
endfunction ()
run("making the data" "${WITH_XVFB}" "${PVBATCH}" "${SCRIPT}" --plugin "${PLUGIN}" --work "${WORK}"
  --make-data)
run("strata-convert" "${CMAKE_COMMAND}" -E env --unset=DISPLAY
  "${CONVERT}" "${WORK}/paged.vti" "${WORK}/paged.spp" --page-size 16)
# Four ranks on two cores: --oversubscribe; the tests may run as root in containers.
# Stock ParaView 5.11 under mpirun on these 2-core machines fails now and then at start-up,
# whatever the scene (seen with a plain Sphere in 2 of 8 runs of 4 ranks): a rank's first
# XOpenDisplay on the shared Xvfb fails ("bad X server connection"), or rank 0 enters IceT's
# context creation while the others wait in ParaView's RMI barrier and the run hangs before its
# first frame. Such a run (that message, or no exit within 120 s: timeout stops mpirun, which
# stops its ranks) is tried again, up to 4 times; any other failure fails the test at once.
# (The lost connections were Xvfb resetting when its last client left: with-xvfb now runs it
# with -noreset, and no retry has been needed since; the hang is ParaView's.)
foreach (ranks IN ITEMS 1 2 4)
  foreach (attempt RANGE 1 4)
    execute_process(COMMAND "${CMAKE_COMMAND}" -E env OMPI_ALLOW_RUN_AS_ROOT=1
      OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
      "${WITH_XVFB}" "${TIMEOUT}" --kill-after=10 120
      "${MPIEXEC}" -np ${ranks} --bind-to none "${PVBATCH}" "${SCRIPT}" --plugin "${PLUGIN}" --work "${WORK}" --render
      RESULT_VARIABLE result OUTPUT_VARIABLE output ERROR_VARIABLE output)
    message("${output}")
    if (result EQUAL 0 OR NOT (output MATCHES "bad X server connection" OR
                               result EQUAL 124))
      break ()
    endif ()
    message("pvbatch with ${ranks} rank(s), attempt ${attempt}: ${result}; trying again")
  endforeach ()
  if (NOT result EQUAL 0)
    message(FATAL_ERROR "pvbatch with ${ranks} rank(s) failed (${result})")
  endif ()
endforeach ()
# ParaView's client-server mode: a 1-rank and a 2-rank pvserver render the scene for a pvpython
# client (run-client-server), whose images must equal the 1-rank pvbatch ones as the pvbatch
# images of as many ranks do.
run("pvserver + pvpython" "${WITH_XVFB}" "${CLIENT_SERVER}" 2 "${MPIEXEC}" "${PVSERVER}"
  "${TIMEOUT}" "${PVPYTHON}" "${SCRIPT}" --plugin "${PLUGIN}" --work "${WORK}" --render
  --label _server)
run("pvserver (1 rank) + pvpython" "${WITH_XVFB}" "${CLIENT_SERVER}" 1 "${MPIEXEC}"
  "${PVSERVER}" "${TIMEOUT}" "${PVPYTHON}" "${SCRIPT}" --plugin "${PLUGIN}" --work "${WORK}"
  --render --label _server)
run("the comparison" "${WITH_XVFB}" "${PVBATCH}" "${SCRIPT}" --plugin "${PLUGIN}" --work "${WORK}"
  --compare 2 4)
run("the client-server comparison" "${WITH_XVFB}" "${PVBATCH}" "${SCRIPT}" --plugin "${PLUGIN}"
  --work "${WORK}" --compare 1 2 --label _server)
