# Checks of the package as a whole rather than of one component: its declared dependencies
# against rosdep.yaml, the Makefile's apt list and what dpkg says each Debian package provides
# (test/python/test_dependencies.py); what make refuses before it installs anything
# (test/python/test_makefile.py); the launch files and tools as a newcomer types them
# (test/python/test_launch_sources.py); and every `bash tested` command of README.md and docs/*.md
# run as written on the bundled data (test/python/test_doc_commands.py); and the house rules of
# the code (test/python/test_code_shape.py: short functions, thin mains, headers mirroring
# sources, no production file named like a test); and every node's parameters (a rostest). Debian's python3 on
# purpose: a python3 from another installation earlier on PATH lacks ROS's modules.
if(CATKIN_ENABLE_TESTING)
  set(_acc_results ${CATKIN_TEST_RESULTS_DIR}/${PROJECT_NAME})
  catkin_run_tests_target("python" "dependencies" "python-dependencies.xml"
    COMMAND "/usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/python/test_dependencies.py --junit ${_acc_results}/python-dependencies.xml"
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  catkin_run_tests_target("python" "makefile" "python-makefile.xml"
    COMMAND "/usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/python/test_makefile.py --junit ${_acc_results}/python-makefile.xml"
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  catkin_run_tests_target("python" "code_shape" "python-code_shape.xml"
    COMMAND "/usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/python/test_code_shape.py --junit ${_acc_results}/python-code_shape.xml"
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR})
  # Both run the package's nodes and tools: built first.
  set(_acc_user_targets gps_driver_node relative_state_node identifier_node openacc_to_nmea nmea_to_csv platoon
      calibrate diagnose stability_report campaign synthesize nmea_to_bag sumo_replay)
  set(_acc_user_dependencies)
  foreach(_target ${_acc_user_targets})
    if(TARGET ${_target})
      list(APPEND _acc_user_dependencies ${_target})
    endif()
  endforeach()
  catkin_run_tests_target("python" "launch_sources" "python-launch_sources.xml"
    COMMAND "/usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/python/test_launch_sources.py --junit ${_acc_results}/python-launch_sources.xml"
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    DEPENDENCIES ${_acc_user_dependencies})
  catkin_run_tests_target("python" "doc_commands" "python-doc_commands.xml"
    COMMAND "/usr/bin/python3 ${PROJECT_SOURCE_DIR}/test/python/test_doc_commands.py --devel ${CATKIN_DEVEL_PREFIX} --junit ${_acc_results}/python-doc_commands.xml"
    WORKING_DIRECTORY ${PROJECT_SOURCE_DIR}
    DEPENDENCIES ${_acc_user_dependencies})
endif()

# Every node's parameters read with their types checked, and the shipped config files read whole
# (test/rostest/node_parameters_check.cpp): needs the three nodes' ROS libraries.
if(CATKIN_ENABLE_TESTING AND TARGET acc_identifier_ros AND TARGET acc_relative_state_ros)
  add_rostest_gtest(test_node_parameters_rostest test/rostest/node_parameters.test
    test/rostest/node_parameters_check.cpp)
  target_link_libraries(test_node_parameters_rostest acc_identifier_ros acc_relative_state_ros)
endif()
