# Shared compile options for every Deltapath target.
add_library(dp_options INTERFACE)
target_compile_options(dp_options INTERFACE -Wall -Wextra -Wpedantic -Wshadow -Wdouble-promotion
  # GCC 12 false positives in libstdc++ string code (GCC bug 105651):
  $<$<CXX_COMPILER_ID:GNU>:-Wno-restrict>)
if(DP_WERROR)
  target_compile_options(dp_options INTERFACE -Werror)
endif()
target_include_directories(dp_options INTERFACE ${PROJECT_SOURCE_DIR})

# dp_add_library(name SOURCES ... DEPS ...): one static library per layer folder.
function(dp_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(${name} STATIC ${ARG_SOURCES})
  target_link_libraries(${name} PUBLIC dp_options ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  dp_sanitize_target(${name})
endfunction()

# dp_add_test(name SOURCES ... [OWN_UNIT ...] DEPS ... LABELS unit stat ...): one Catch2
# executable; one ctest entry per label, running the test cases tagged [label]. OWN_UNIT
# lists sources kept out of the unity batches (their file-local helpers share names with
# another file's of the same test).
function(dp_add_test name)
  cmake_parse_arguments(ARG "" "" "SOURCES;OWN_UNIT;DEPS;LABELS" ${ARGN})
  add_executable(${name} ${ARG_SOURCES})
  if(ARG_OWN_UNIT)
    set_source_files_properties(${ARG_OWN_UNIT} TARGET_DIRECTORY ${name} PROPERTIES SKIP_UNITY_BUILD_INCLUSION ON)
  endif()
  target_link_libraries(${name} PRIVATE dp_test_main ${ARG_DEPS})
  target_compile_definitions(${name} PRIVATE DP_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  dp_sanitize_target(${name})
  foreach(label ${ARG_LABELS})
    add_test(NAME ${name}_${label} COMMAND ${name} "[${label}]" --warn NoTests --warn NoAssertions)
    set_tests_properties(${name}_${label} PROPERTIES LABELS ${label}
                         WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  endforeach()
endfunction()
