# dsswarm_test(NAME SOURCES a_test.cpp ... LIBS lib ...)
# A GoogleTest executable registered with ctest; each TEST becomes one ctest case.
function(dsswarm_test name)
  if(NOT DSSWARM_BUILD_TESTS)
    return()
  endif()
  cmake_parse_arguments(T "" "" "SOURCES;LIBS" ${ARGN})
  add_executable(${name} ${T_SOURCES})
  target_link_libraries(${name} PRIVATE ${T_LIBS} GTest::gtest GTest::gtest_main)
  target_compile_definitions(${name} PRIVATE
    DSSWARM_SHARED_DATA="${DSSWARM_SHARED_DATA}"
    DSSWARM_TEST_TMP="${CMAKE_BINARY_DIR}/test_tmp"
    DSSWARM_SOURCE_DIR="${CMAKE_SOURCE_DIR}")
  set_target_properties(${name} PROPERTIES RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/tests)
  gtest_discover_tests(${name} DISCOVERY_TIMEOUT 60 PROPERTIES TIMEOUT 600)
endfunction()
