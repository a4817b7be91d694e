# ctest script: installs the Python component of the build into a temporary prefix and runs the
# pytest suite against that installed copy (not the build tree), with the Vulkan validation
# layer on. -DBUILD_DIR=... -DSOURCE_DIR=... -DWORK_DIR=... -DDATA_DIR=... -DPYTHON=...
# -DSITE=<lib/pythonX.Y/dist-packages>
file(REMOVE_RECURSE "${WORK_DIR}")
execute_process(COMMAND ${CMAKE_COMMAND} --install "${BUILD_DIR}" --component python
                        --prefix "${WORK_DIR}/prefix"
                RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "installing the Python component failed (${result})")
endif()
execute_process(
  COMMAND ${CMAKE_COMMAND} -E env "PYTHONPATH=${WORK_DIR}/prefix/${SITE}"
          "STRATA_DATA_DIR=${DATA_DIR}" "STRATA_PYTHON_PREFIX=${WORK_DIR}/prefix"
          STRATA_VALIDATION=1
          ${PYTHON} -m pytest -q -p no:cacheprovider "${SOURCE_DIR}/python/tests"
  WORKING_DIRECTORY "${WORK_DIR}"
  RESULT_VARIABLE result)
if(NOT result EQUAL 0)
  message(FATAL_ERROR "pytest failed (${result})")
endif()
