# Configures and builds tests/odr/planted with the clash planted (VARIANT=clash) or not
# (VARIANT=no_clash); passes when the build fails with an ODR diagnostic exactly when planted.
file(REMOVE_RECURSE ${BINARY_DIR})
set(plant OFF)
if(VARIANT STREQUAL "clash")
  set(plant ON)
endif()
execute_process(
  COMMAND ${CMAKE_COMMAND} -S ${SOURCE_DIR} -B ${BINARY_DIR} -DSIMTREE_MODULE_DIR=${MODULE_DIR}
          -DPLANT_CLASH=${plant}
  RESULT_VARIABLE configure_result OUTPUT_VARIABLE out ERROR_VARIABLE out)
if(NOT configure_result EQUAL 0)
  message(FATAL_ERROR "configure failed:\n${out}")
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BINARY_DIR}
  RESULT_VARIABLE build_result OUTPUT_VARIABLE out ERROR_VARIABLE out)
string(FIND "${out}" "One Definition Rule" odr_at)
if(plant)
  if(build_result EQUAL 0 OR odr_at EQUAL -1)
    message(FATAL_ERROR "the planted clash was not caught (exit ${build_result}):\n${out}")
  endif()
  message(STATUS "planted clash caught:\n${out}")
elseif(NOT build_result EQUAL 0)
  message(FATAL_ERROR "the project without a clash failed:\n${out}")
endif()
