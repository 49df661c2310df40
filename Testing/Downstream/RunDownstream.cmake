# Installs Strata from STRATA_BUILD into WORK/install, converts a horizon grid (DATA's Reek .gri)
# into a page pool and a volume (DATA's bucky.raw) into a hybrid file with the INSTALLED
# strata-convert and strata-hybrid, then configures, builds and runs the downstream consumer in
# this folder against that install tree alone; the consumer renders the flat horizon and reads
# the pool back.
foreach (v STRATA_BUILD WORK SOURCE DATA)
  if (NOT DEFINED ${v})
    message(FATAL_ERROR "RunDownstream.cmake needs -D${v}=...")
  endif ()
endforeach ()
file(REMOVE_RECURSE "${WORK}")
function (step what)
  execute_process(COMMAND ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if (NOT rc EQUAL 0)
    message(FATAL_ERROR "${what} failed (${rc}):\n${out}\n${err}")
  endif ()
  message(STATUS "${what}: ok")
  set(step_output "${out}" PARENT_SCOPE)
endfunction ()
step("install" "${CMAKE_COMMAND}" --install "${STRATA_BUILD}" --prefix "${WORK}/install")
set(bin "${WORK}/install/bin")
foreach (tool strata-convert strata-hybrid)
  if (NOT EXISTS "${bin}/${tool}")
    message(FATAL_ERROR "cmake --install put no ${tool} in ${bin}")
  endif ()
endforeach ()
# Run with no build-tree library path: the installed tools must find the installed libraries.
step("installed strata-convert" "${CMAKE_COMMAND}" -E env --unset=LD_LIBRARY_PATH
  "${bin}/strata-convert" "${DATA}/horizons/reek_01_topreek_rota.gri" "${WORK}/reek.spp"
  --page-size 64)
step("installed strata-hybrid" "${CMAKE_COMMAND}" -E env --unset=LD_LIBRARY_PATH
  "${bin}/strata-hybrid" "${DATA}/volumes/bucky.raw" "${WORK}/bucky.shv" --raw 32 32 32 uint8
  --factor 4)
foreach (out reek.spp bucky.shv)
  if (NOT EXISTS "${WORK}/${out}")
    message(FATAL_ERROR "the installed tools wrote no ${WORK}/${out}")
  endif ()
endforeach ()
step("configure" "${CMAKE_COMMAND}" -S "${SOURCE}" -B "${WORK}/build" -G Ninja
  -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${WORK}/install")
step("build" "${CMAKE_COMMAND}" --build "${WORK}/build")
# Under scripts/asan the consumer (built here by the system compiler, not instrumented) loads the
# instrumented libraries: the sanitizer runtime they need must be loaded before anything else
# (STRATA_DOWNSTREAM_PRELOAD names it), or static constructors run before it is initialised.
set(preload)
if (DEFINED ENV{STRATA_DOWNSTREAM_PRELOAD})
  set(preload "LD_PRELOAD=$ENV{STRATA_DOWNSTREAM_PRELOAD}")
endif ()
step("run" "${CMAKE_COMMAND}" -E env STRATA_OFFSCREEN=1 ${preload}
  "${WORK}/build/StrataDownstream" "${WORK}/reek.spp")
message("${step_output}")
# A project written against the single module of earlier releases (Strata::Strata, now the
# umbrella of the three) configures, builds and renders the same.
step("configure (Strata::Strata)" "${CMAKE_COMMAND}" -S "${SOURCE}" -B "${WORK}/build-umbrella"
  -G Ninja -DCMAKE_BUILD_TYPE=Release "-DCMAKE_PREFIX_PATH=${WORK}/install"
  -DSTRATA_DOWNSTREAM_UMBRELLA=ON)
step("build (Strata::Strata)" "${CMAKE_COMMAND}" --build "${WORK}/build-umbrella")
step("run (Strata::Strata)" "${CMAKE_COMMAND}" -E env STRATA_OFFSCREEN=1 ${preload}
  "${WORK}/build-umbrella/StrataDownstream" "${WORK}/reek.spp")
string(REGEX MATCH "window [A-Za-z]+" window "${step_output}")
message("downstream: Strata::Strata umbrella: ${window}: ok")
