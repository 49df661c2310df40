# strata_module_link_dependencies(<vtk.module text> <out>): the module names a vtk.module lists
# under DEPENDS and PRIVATE_DEPENDS (not TEST_DEPENDS), for the module-arrow checks (the root
# CMakeLists.txt at configure time, Testing/CheckModuleArrows.cmake as a test).
function (strata_module_link_dependencies text out)
  string(REGEX REPLACE "\n" ";" lines "${text}")
  set(section "")
  set(names)
  foreach (line IN LISTS lines)
    if (line MATCHES "^([A-Z_]+)$")
      set(section "${CMAKE_MATCH_1}")
    elseif (line MATCHES "^[ \t]+([^ \t]+)")
      set(name "${CMAKE_MATCH_1}")
      if (section STREQUAL "DEPENDS" OR section STREQUAL "PRIVATE_DEPENDS")
        list(APPEND names "${name}")
      endif ()
    endif ()
  endforeach ()
  set(${out} "${names}" PARENT_SCOPE)
endfunction ()
