# Checks of the package as a whole rather than of one component: its declared dependencies
# against rosdep.yaml, the Makefile's apt list and what dpkg says each Debian package provides
# (test/python/test_dependencies.py). Debian's python3 on purpose: a python3 from another
# installation earlier on PATH lacks ROS's modules.
if(CATKIN_ENABLE_TESTING)
  set(_acc_results ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME}/python-dependencies.xml)
  catkin_run_tests_target("python" "dependencies" "python-dependencies.xml"
    COMMAND "/usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/python/test_dependencies.py --junit ${_acc_results}"
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
endif()
