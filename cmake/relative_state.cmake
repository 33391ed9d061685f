# Relative state (issue 8): the two vehicles' fixes paired by GNSS epoch, the bumper-to-bumper
# gap (geodesic, WGS84), the jump bound and the gap-versus-Doppler consistency; the OpenACC to
# NMEA converter; relative_state_node. Needs the gnss component (NMEA writer and log reader).
# The sources are one list: the relative-state fuzzer (scripts/test_hooks/fuzz_relative_state.sh)
# builds the same files with clang's libFuzzer from cmake/relative_state_sources.cmake.
include(${CMAKE_CURRENT_LIST_DIR}/relative_state_sources.cmake)
acc_add_library(acc_relative_state
  SOURCES
    ${ACC_RELATIVE_STATE_SOURCES}
    src/relative_state/relative_state_parameters.cpp
  LINK acc_parameters ${GeographicLib_LIBRARIES})
target_include_directories(acc_relative_state PUBLIC ${GeographicLib_INCLUDE_DIRS})

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_relative_state
    test/unit/gtest_main.cpp
    test/unit/test_clock_reset_rule.cpp
    test/unit/test_pairing.cpp
    test/unit/test_relative_state_geometry.cpp
    test/unit/test_relative_state_parameters.cpp
    test/unit/test_relative_state_estimator.cpp)
  target_link_libraries(test_relative_state acc_relative_state acc_model)
endif()

# The OpenACC converter writes NMEA with the gnss component's writer and its tests read the logs
# back with the gnss component's reader: both need acc_gnss.
if(TARGET acc_gnss)
  # The OpenACC files themselves are read by acc_run_io's one reader (io/openacc_file.h).
  acc_add_library(acc_conversion
    SOURCES
      src/conversion/openacc_to_nmea.cpp
      src/conversion/nmea_logs_to_csv.cpp
    LINK acc_gnss acc_relative_state acc_run_io ${GeographicLib_LIBRARIES} nlohmann_json::nlohmann_json)
  target_include_directories(acc_conversion PUBLIC ${GeographicLib_INCLUDE_DIRS})
  acc_add_tool(openacc_to_nmea LINK acc_conversion)
  acc_add_tool(nmea_to_csv LINK acc_conversion)

  if(CATKIN_ENABLE_TESTING)
    # The real data: the Casale runs shipped in data/openacc, unpacked by cmake/data.cmake.
    catkin_add_gtest(test_openacc
      test/unit/gtest_main.cpp
      test/unit/test_openacc_conversion.cpp
      test/unit/test_openacc_real_data.cpp
      test/unit/test_nmea_logs_to_csv.cpp)
    target_link_libraries(test_openacc acc_conversion acc_relative_state)
    target_compile_definitions(test_openacc PRIVATE
      ACC_RELSTATE_TEST_DATA="${PROJECT_SOURCE_DIR}/test/data/relative_state"
      ACC_OPENACC_TEST_DATA="${PROJECT_SOURCE_DIR}/test/data/openacc"
      ACC_OPENACC_DATA_DIR="${ACC_DATA_CASALE_DIR}"
      ACC_CONFIG_DIR="${PROJECT_SOURCE_DIR}/config")
  endif()
endif()

# The ROS wrapper and its ten-line main. It reuses the gnss component's message conversion
# (fromMessage in acc_gnss_ros), so it needs that component's ROS library.
if(TARGET acc_gnss_ros AND TARGET acc_conversion)
  acc_add_ros_library(acc_relative_state_ros SOURCES src/ros/relative_state_ros.cpp
    LINK acc_relative_state acc_gnss_ros acc_ros_parameters)
  acc_add_node(relative_state_node WRAPPER acc_relative_state_ros)

  if(CATKIN_ENABLE_TESTING)
    # Recorded fixes with a late, bursty, broken leader stream and a looping restart.
    add_rostest_gtest(test_relative_state_fixes test/rostest/relative_state_fixes.test
      test/rostest/relative_state_fixes_check.cpp)
    target_link_libraries(test_relative_state_fixes acc_relative_state_ros acc_conversion ${catkin_LIBRARIES})
    add_dependencies(test_relative_state_fixes relative_state_node)
    add_rostest(test/rostest/relative_state_fixes.test ARGS use_sim_time:=true
      DEPENDENCIES test_relative_state_fixes relative_state_node)

    # Every Casale run through openacc_to_nmea, the two drivers and the node.
    add_executable(test_relative_state_drivers EXCLUDE_FROM_ALL test/rostest/relative_state_drivers_check.cpp)
    target_link_libraries(test_relative_state_drivers acc_relative_state_ros acc_conversion ${GTEST_LIBRARIES}
      ${catkin_LIBRARIES})
    target_include_directories(test_relative_state_drivers PRIVATE ${GTEST_INCLUDE_DIRS})
    add_dependencies(tests test_relative_state_drivers)
    set(_acc_nmea_dir ${CMAKE_CURRENT_BINARY_DIR}/openacc_nmea)
    foreach(run part3 part4 part5 part6)
      set(_acc_csv ${ACC_DATA_CASALE_DIR}/${run}.csv)
      add_custom_command(
        OUTPUT ${_acc_nmea_dir}/${run}_leader.nmea ${_acc_nmea_dir}/${run}_follower.nmea
        COMMAND ${CMAKE_COMMAND} -E make_directory ${_acc_nmea_dir}
        COMMAND openacc_to_nmea ${_acc_csv} ${_acc_nmea_dir}/${run}_leader.nmea ${_acc_nmea_dir}/${run}_follower.nmea
        DEPENDS openacc_to_nmea ${_acc_csv}
        COMMENT "openacc_to_nmea ${run}")
      add_custom_target(relative_state_nmea_${run}
        DEPENDS ${_acc_nmea_dir}/${run}_leader.nmea ${_acc_nmea_dir}/${run}_follower.nmea)
      add_dependencies(tests relative_state_nmea_${run})
      # rostest names the target after the launch file and its ARGS: absolute paths in ARGS would
      # put the checkout's path into a file name (past 255 bytes in a deep checkout). So each run
      # gets a small launch file in the build tree that passes the paths on; its name, relative
      # to the build folder, is all the target name holds.
      set(_acc_launch ${PROJECT_BINARY_DIR}/rostest/relative_state_drivers_${run}.test)
      file(CONFIGURE OUTPUT ${_acc_launch} @ONLY CONTENT [=[
<!-- Made by cmake/relative_state.cmake: run @run@ of the bundled Casale data. -->
<launch>
  <include file="$(find acc_identification)/test/rostest/relative_state_drivers.test">
    <arg name="run" value="@run@"/>
    <arg name="nmea_dir" value="@_acc_nmea_dir@"/>
    <arg name="csv" value="@_acc_csv@"/>
  </include>
</launch>
]=])
      add_rostest(${_acc_launch}
        DEPENDENCIES relative_state_node gps_driver_node test_relative_state_drivers relative_state_nmea_${run})
    endforeach()

    # Issue 26: part3 replayed at 20x as a user replays a drive, the leader's stream a second late
    # (its log without its first 10 epochs of GGA + RMC), recorded by rosbag record.
    add_executable(test_relative_state_record EXCLUDE_FROM_ALL test/rostest/relative_state_record_check.cpp)
    target_link_libraries(test_relative_state_record acc_relative_state_ros ${GTEST_LIBRARIES} ${catkin_LIBRARIES})
    target_include_directories(test_relative_state_record PRIVATE ${GTEST_INCLUDE_DIRS})
    add_dependencies(tests test_relative_state_record)
    set(_acc_late_leader ${_acc_nmea_dir}/part3_leader_from_1s.nmea)
    # (tail, not CMake's file(READ), which would turn the sentences' CR LF into LF.)
    add_custom_command(
      OUTPUT ${_acc_late_leader}
      COMMAND sh -c "tail -n +21 '${_acc_nmea_dir}/part3_leader.nmea' > '${_acc_late_leader}'"
      DEPENDS ${_acc_nmea_dir}/part3_leader.nmea
      COMMENT "part3's leader log from its second second"
      VERBATIM)
    add_custom_target(relative_state_late_leader_part3 DEPENDS ${_acc_late_leader})
    add_dependencies(relative_state_late_leader_part3 relative_state_nmea_part3)
    add_dependencies(tests relative_state_late_leader_part3)
    set(_acc_launch ${PROJECT_BINARY_DIR}/rostest/relative_state_record_part3.test)
    file(CONFIGURE OUTPUT ${_acc_launch} @ONLY CONTENT [=[
<!-- Made by cmake/relative_state.cmake: run part3, the leader's log a second late. -->
<launch>
  <include file="$(find acc_identification)/test/rostest/relative_state_record.test">
    <arg name="run" value="part3"/>
    <arg name="leader_log" value="@_acc_late_leader@"/>
    <arg name="follower_log" value="@_acc_nmea_dir@/part3_follower.nmea"/>
    <arg name="bag" value="@PROJECT_BINARY_DIR@/rostest/relative_state_record_part3.bag"/>
  </include>
</launch>
]=])
    add_rostest(${_acc_launch}
      DEPENDENCIES relative_state_node gps_driver_node test_relative_state_record relative_state_late_leader_part3)
  endif()
endif()
