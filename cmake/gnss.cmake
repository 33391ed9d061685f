# The GNSS driver (issue 3): NMEA parsing and epoch assembly in the ROS-free library acc_gnss,
# byte sources (serial, UDP, TCP, file), the gps_driver_node wrapper, tests and a benchmark.
# The parser's sources are one list: the fuzzer (scripts/test_hooks/fuzz_nmea.sh) builds the
# same files with clang's libFuzzer from cmake/gnss_parser_sources.cmake.
include(${CMAKE_CURRENT_LIST_DIR}/gnss_parser_sources.cmake)
acc_add_library(acc_gnss
  SOURCES
    ${ACC_GNSS_PARSER_SOURCES}
    src/gnss/nmea_log.cpp
    src/gnss/nmea_log_timing.cpp
    src/gnss/source_uri.cpp
    src/gnss/file_source.cpp
    src/gnss/log_pacer.cpp
    src/gnss/reconnecting_source.cpp
    src/gnss/live_sources.cpp)

acc_add_ros_library(acc_gnss_ros SOURCES src/ros/gps_driver_ros.cpp LINK acc_gnss acc_ros_parameters)
acc_add_node(gps_driver_node WRAPPER acc_gnss_ros)

# Any receiver's NMEA log into a bag of raw sentences stamped with their receive times (rosbag
# API, no ROS master needed): what the drivers replay. The synthesize tool writes its bags with it.
acc_add_ros_library(acc_sentence_bag SOURCES src/ros/sentence_bag_writer.cpp LINK acc_gnss)
acc_add_tool(nmea_to_bag LINK acc_sentence_bag acc_run_io)

# Parser throughput (issue 3 target: 2 million GGA + RMC sentences per second on one core).
acc_add_benchmark(bench_nmea LINK acc_gnss)

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_gnss
    test/unit/gtest_main.cpp
    test/unit/test_nmea_parser.cpp
    test/unit/test_nmea_line_assembler.cpp
    test/unit/test_nmea_writer.cpp
    test/unit/test_gnss_epoch.cpp
    test/unit/test_gnss_sources.cpp
    test/unit/test_gnss_captures.cpp)
  target_link_libraries(test_gnss acc_gnss)
  target_compile_definitions(test_gnss PRIVATE ACC_GNSS_TEST_DATA="${PROJECT_SOURCE_DIR}/test/data/nmea"
    ACC_GNSS_CAPTURE_DATA="${PROJECT_SOURCE_DIR}/test/data/nmea_captures")

  catkin_add_gtest(test_gnss_ros test/unit/gtest_main.cpp test/unit/test_gnss_ros_conversion.cpp)
  target_link_libraries(test_gnss_ros acc_gnss_ros)

  # Checks what the node publishes when it replays test/data/nmea/drive_10s.nmea.
  add_rostest_gtest(test_gps_driver_file test/rostest/gps_driver_file.test
    test/rostest/gps_driver_file_check.cpp)
  target_link_libraries(test_gps_driver_file ${catkin_LIBRARIES})
  add_dependencies(test_gps_driver_file ${PROJECT_NAME}_generate_messages_cpp gps_driver_node)
  # A datagram larger than a small read buffer, read whole.
  add_rostest(test/rostest/gps_driver_udp.test DEPENDENCIES test_gps_driver_file gps_driver_node)
  # 10 Hz at rate 1 (hztest).
  add_rostest(test/rostest/gps_driver_rate.test DEPENDENCIES gps_driver_node)
endif()
