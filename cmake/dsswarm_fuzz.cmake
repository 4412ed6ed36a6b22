# libFuzzer targets (clang only), declared in fuzz/CMakeLists.txt, which is
# configured when DSSWARM_FUZZ is ON; scripts/fuzz.sh builds and runs them.
#
# dsswarm_fuzz_target(NAME SOURCES a.cpp ... LIBS lib ...)
# An executable CMAKE_BINARY_DIR/fuzz/NAME (seeds in fuzz/corpus/NAME, optional
# dictionary fuzz/dict/NAME.dict). Its sources define LLVMFuzzerTestOneInput and
# dsswarm::fuzz::write_seeds (fuzz/fuzz_support.hpp). This project's libraries
# among LIBS get coverage instrumentation, so the fuzzer sees their branches.
# A target whose libraries are not part of this build (ROS packages missing,
# say) is skipped with a message.
function(dsswarm_fuzz_target name)
  cmake_parse_arguments(F "" "" "SOURCES;LIBS" ${ARGN})
  foreach(lib ${F_LIBS})
    if(lib MATCHES "^dsswarm_" AND NOT TARGET ${lib})
      message(STATUS "dsswarm: fuzz target ${name} skipped (${lib} is not built)")
      return()
    endif()
  endforeach()
  add_executable(fuzz_${name} ${F_SOURCES})
  target_link_libraries(fuzz_${name} PRIVATE dsswarm_fuzz_support ${F_LIBS})
  target_compile_options(fuzz_${name} PRIVATE -fsanitize=fuzzer)
  target_link_options(fuzz_${name} PRIVATE -fsanitize=fuzzer)
  set_target_properties(fuzz_${name} PROPERTIES OUTPUT_NAME ${name}
                        RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/fuzz)
  if(NOT TARGET fuzz_targets)
    add_custom_target(fuzz_targets)  # builds them all
  endif()
  add_dependencies(fuzz_targets fuzz_${name})
  foreach(lib ${F_LIBS})
    if(lib MATCHES "^dsswarm_")
      dsswarm_fuzz_instrument(${lib})
    endif()
  endforeach()
endfunction()

# Coverage instrumentation for one of our libraries (once per library). The
# unit tests link the same libraries: the ASan runtime supplies the coverage
# callbacks there.
function(dsswarm_fuzz_instrument lib)
  get_target_property(done ${lib} DSSWARM_FUZZ_INSTRUMENTED)
  if(NOT done)
    target_compile_options(${lib} PRIVATE -fsanitize=fuzzer-no-link)
    set_target_properties(${lib} PROPERTIES DSSWARM_FUZZ_INSTRUMENTED ON)
  endif()
endfunction()
