# Helpers that give every stage library, test suite and benchmark the same shape.

set(SIMTREE_WARNING_FLAGS -Wall -Wextra -Wpedantic -Wshadow=local -Wno-unused-parameter)
if(SIMTREE_WERROR)
  list(APPEND SIMTREE_WARNING_FLAGS -Werror)
endif()
# In a unity build every source is an included file, where GCC takes a class holding a file-local
# type for a header's mistake; in a source of its own that is the usual pimpl.
if(CMAKE_UNITY_BUILD AND CMAKE_CXX_COMPILER_ID STREQUAL "GNU")
  list(APPEND SIMTREE_WARNING_FLAGS -Wno-subobject-linkage)
endif()

# The one-definition-rule check: every object also carries GCC's LTO form (fat objects, so the
# ordinary links are unchanged), and simtree_add_odr_check links libraries whole with -flto -Wodr:
# two different types with one fully qualified name fail that link.
if(SIMTREE_ODR_CHECK)
  add_compile_options(-flto=auto -ffat-lto-objects)
endif()

if(SIMTREE_SANITIZE)
  # GCC 12's -Wmaybe-uninitialized fires falsely in sanitized code (std::regex's automaton, for
  # one); the sanitizers themselves catch what that warning guesses at.
  add_compile_options(-fsanitize=address,undefined -fno-omit-frame-pointer
                      -fno-sanitize-recover=undefined -Wno-maybe-uninitialized)
  add_link_options(-fsanitize=address,undefined)
endif()

# simtree_add_module(<name> SOURCES ... [PUBLIC_DEPS ...] [PRIVATE_DEPS ...])
# Builds the static library simtree_<name> (alias simtree::<name>) from src/simtree/<name>/.
function(simtree_add_module name)
  cmake_parse_arguments(ARG "" "" "SOURCES;PUBLIC_DEPS;PRIVATE_DEPS" ${ARGN})
  add_library(simtree_${name} STATIC ${ARG_SOURCES})
  add_library(simtree::${name} ALIAS simtree_${name})
  target_include_directories(simtree_${name} PUBLIC ${PROJECT_SOURCE_DIR}/src)
  target_link_libraries(simtree_${name} PUBLIC ${ARG_PUBLIC_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
  target_compile_options(simtree_${name} PRIVATE ${SIMTREE_WARNING_FLAGS})
  set_target_properties(simtree_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
endfunction()

# simtree_add_test_suite(<name> SOURCES ... DEPS ... [LABELS fast|slow ...] [TIMEOUT seconds]
#                        [ENVIRONMENT VAR=value ...] [USES_CLI])
# One GoogleTest executable per suite; each test case becomes a CTest test carrying LABELS.
# Tests find the shared data through SIMTREE_SHARED_DATA_DIR and write under SIMTREE_TEST_TMP_DIR.
# USES_CLI: the tests run the simtree CLI, which is built first. A slow suite is not built at all
# with SIMTREE_SLOW_TESTS off (the sanitizer build, which runs the fast suite only).
function(simtree_add_test_suite name)
  cmake_parse_arguments(ARG "USES_CLI" "TIMEOUT" "SOURCES;DEPS;LABELS;ENVIRONMENT" ${ARGN})
  if(NOT ARG_LABELS)
    set(ARG_LABELS fast)
  endif()
  if("slow" IN_LIST ARG_LABELS AND NOT SIMTREE_SLOW_TESTS)
    return()
  endif()
  if(NOT ARG_TIMEOUT)
    set(ARG_TIMEOUT 300)
  endif()
  add_executable(simtree_${name}_tests ${ARG_SOURCES})
  target_link_libraries(simtree_${name}_tests PRIVATE ${ARG_DEPS} GTest::gtest GTest::gmock
                        GTest::gtest_main)
  target_include_directories(simtree_${name}_tests PRIVATE ${PROJECT_SOURCE_DIR}/tests)
  # GoogleTest and GoogleMock headers are slow to parse; parse them once per suite.
  target_precompile_headers(simtree_${name}_tests PRIVATE <gtest/gtest.h> <gmock/gmock.h>)
  target_compile_options(simtree_${name}_tests PRIVATE ${SIMTREE_WARNING_FLAGS})
  target_compile_definitions(simtree_${name}_tests PRIVATE
    SIMTREE_SHARED_DATA_DIR="${SIMTREE_SHARED_DIR}/data"
    SIMTREE_TEST_TMP_DIR="${CMAKE_BINARY_DIR}/test_tmp/${name}"
    SIMTREE_CLI_PATH="$<TARGET_FILE_DIR:simtree_${name}_tests>/simtree"
    SIMTREE_SOURCE_DIR="${PROJECT_SOURCE_DIR}")
  gtest_discover_tests(simtree_${name}_tests
    DISCOVERY_MODE PRE_TEST
    WORKING_DIRECTORY ${CMAKE_BINARY_DIR}
    PROPERTIES LABELS "${ARG_LABELS}" TIMEOUT ${ARG_TIMEOUT} ENVIRONMENT "${ARG_ENVIRONMENT}")
  if(ARG_USES_CLI)
    add_dependencies(simtree_${name}_tests simtree)
  endif()
endfunction()

# simtree_add_benchmark(<name> SOURCES ... DEPS ...): a Google Benchmark executable in bin/.
function(simtree_add_benchmark name)
  cmake_parse_arguments(ARG "" "" "SOURCES;DEPS" ${ARGN})
  add_executable(bench_${name} ${ARG_SOURCES})
  target_link_libraries(bench_${name} PRIVATE ${ARG_DEPS} benchmark::benchmark)
  target_compile_options(bench_${name} PRIVATE ${SIMTREE_WARNING_FLAGS})
  target_compile_definitions(bench_${name} PRIVATE
    SIMTREE_SHARED_DATA_DIR="${SIMTREE_SHARED_DIR}/data")
endfunction()

# simtree_add_odr_check(<target> LIBRARIES ...): a program that links every object of LIBRARIES
# through the link-time optimiser with -Wodr as an error, so a type defined twice differently
# under one name (a one-definition-rule violation) fails the build. The program does nothing.
function(simtree_add_odr_check target)
  cmake_parse_arguments(ARG "" "" "LIBRARIES" ${ARGN})
  set(main ${CMAKE_CURRENT_BINARY_DIR}/${target}_main.cc)
  file(WRITE ${main} "int main() { return 0; }\n")
  add_executable(${target} ${main})
  # Every object of every library, whole (the libraries also stay ordinary dependencies, for what
  # they link to; their objects are in already, so nothing is pulled twice).
  set(whole)
  foreach(library IN LISTS ARG_LIBRARIES)
    list(APPEND whole "$<TARGET_FILE:${library}>")
  endforeach()
  target_link_libraries(${target} PRIVATE -Wl,--whole-archive ${whole} -Wl,--no-whole-archive
                        ${ARG_LIBRARIES})
  # -O0 at the link: the check needs the type merging of the whole program, not its optimisation.
  target_link_options(${target} PRIVATE -flto=auto -O0 -Wodr -Werror=odr)
endfunction()
