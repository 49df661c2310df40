# The parallel test (see CMakeLists.txt and TestParallel.py): the scene's data, its brick pool
# (the standalone build's strata-convert), pvbatch over MPI with 1, 2 and 4 ranks, the
# comparison with the 1-rank images.
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
foreach (ranks IN ITEMS 1 2 4)
  run("pvbatch with ${ranks} rank(s)" "${CMAKE_COMMAND}" -E env OMPI_ALLOW_RUN_AS_ROOT=1
    OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1
    "${WITH_XVFB}" "${MPIEXEC}" -np ${ranks} --bind-to none "${PVBATCH}" "${SCRIPT}"
    --plugin "${PLUGIN}" --work "${WORK}" --render)
endforeach ()
run("the comparison" "${WITH_XVFB}" "${PVBATCH}" "${SCRIPT}" --plugin "${PLUGIN}" --work "${WORK}"
  --compare 2 4 --tolerance "${TOLERANCE}")
