# The Python API (python/acc_identification, docs/PYTHON.md): pandas in, the tools' JSON out, by
# the same library calls as the command-line tools. Its compiled part is a pybind11 module
# (Debian's pybind11-dev), placed in the package's Python folder of the devel space beside the
# generated messages (catkin_python_setup in CMakeLists.txt makes the two one package).
if(TARGET acc_calibration_ros AND TARGET acc_campaign AND TARGET acc_conversion)
  # Python3 first, in this scope: pybind11 then builds the module with its python3_add_library.
  find_package(Python3 COMPONENTS Interpreter Development.Module REQUIRED)
  find_package(pybind11 CONFIG REQUIRED)
  pybind11_add_module(acc_identification_python_core src/python/python_module.cpp)
  target_link_libraries(acc_identification_python_core PRIVATE acc_campaign acc_diagnosis acc_calibration_ros
                        acc_calibration acc_conversion)
  set_target_properties(acc_identification_python_core PROPERTIES
    OUTPUT_NAME _core
    LIBRARY_OUTPUT_DIRECTORY ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_PYTHON_DESTINATION})
  install(TARGETS acc_identification_python_core LIBRARY DESTINATION ${CATKIN_PACKAGE_PYTHON_DESTINATION})

  if(CATKIN_ENABLE_TESTING)
    # pytest holds every function to its command-line tool's JSON on the bundled data.
    set(_acc_python_results ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME})
    catkin_run_tests_target("python" "api" "python-api.xml"
      COMMAND "/usr/bin/env ACC_DATA_CASALE_DIR=${ACC_DATA_CASALE_DIR} ACC_DATA_TOYOTA_DIR=${ACC_DATA_ZALAZONE_TOYOTA_RAV4_S_DIR} ACC_DATA_ZALAZONE_DIR=${ACC_DATA_ZALAZONE_DYNAMIC_DIR} /usr/bin/python3 -m pytest -q -p no:cacheprovider --junitxml=${_acc_python_results}/python-api.xml ${PROJECT_SOURCE_DIR}/test/python/api"
      WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
      DEPENDENCIES acc_identification_python_core calibrate diagnose campaign openacc_to_nmea nmea_to_csv)
  endif()
else()
  message(STATUS "python: the calibration, campaign and conversion components are needed: no Python API")
endif()
