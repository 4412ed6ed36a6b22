# With DSSWARM_TESTS=system, whether any of the sources defines a real-data or
# multi-process test (a TEST/TEST_F/TEST_P whose name says so, as the ctest
# filters of scripts/test.sh match it); always true otherwise. The sources
# become configure dependencies, so a test added or renamed later is seen.
function(dsswarm_holds_system_tests out)
  if(NOT DSSWARM_TESTS STREQUAL "system")
    set(${out} TRUE PARENT_SCOPE)
    return()
  endif()
  set(found FALSE)
  foreach(src IN LISTS ARGN)
    cmake_path(ABSOLUTE_PATH src BASE_DIRECTORY ${CMAKE_CURRENT_SOURCE_DIR})
    set_property(DIRECTORY APPEND PROPERTY CMAKE_CONFIGURE_DEPENDS ${src})
    file(STRINGS ${src} hits REGEX "TEST(_F|_P)?\\([^)]*(RealData|MultiProcess)")
    if(hits)
      set(found TRUE)
    endif()
  endforeach()
  set(${out} ${found} PARENT_SCOPE)
endfunction()

# dsswarm_test(NAME SOURCES a_test.cpp ... LIBS lib ... [COST n] [SERIAL])
# A GoogleTest executable registered with ctest; each TEST becomes one ctest case.
# COST (ctest's property, for every case): executables holding cases that run
# for tens of seconds under the sanitizers give one, so that `ctest -j` starts
# them first instead of ending the run with one of them alone.
# SERIAL (ctest's RUN_SERIAL): cases that need the machine's cores to
# themselves, e.g. robot processes that must keep up with their real-time input.
function(dsswarm_test name)
  if(NOT DSSWARM_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(T "SERIAL" "COST" "SOURCES;LIBS" ${ARGN})
  dsswarm_holds_system_tests(wanted ${T_SOURCES})
  if(NOT wanted)
    return()
  endif()
  add_executable(${name} ${T_SOURCES})
  target_link_libraries(${name} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    DSSWARM_SHARED_DATA="${DSSWARM_SHARED_DATA}"
    DSSWARM_TEST_TMP="${CMAKE_BINARY_DIR}/test_tmp"
    DSSWARM_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  set(properties TIMEOUT 600)
  if(T_COST)
    list(APPEND properties COST ${T_COST})
  endif()
  if(T_SERIAL)
    list(APPEND properties RUN_SERIAL TRUE)
  endif()
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES ${properties})
endfunction()
