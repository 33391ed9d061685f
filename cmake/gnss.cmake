# The GNSS driver (issue 3): NMEA parsing and epoch assembly in the ROS-free library acc_gnss,
# byte sources (serial, UDP, TCP, file), the gps_driver_node wrapper, tests and a benchmark.
add_library(acc_gnss
  src/gnss/nmea_fields.cpp
  src/gnss/nmea_parser.cpp
  src/gnss/nmea_writer.cpp
  src/gnss/nmea_statistics.cpp
  src/gnss/utc_date.cpp
  src/gnss/gnss_epoch_assembler.cpp
  src/gnss/gnss_velocity.cpp
  src/gnss/nmea_decoder.cpp
  src/gnss/nmea_log.cpp
  src/gnss/source_uri.cpp
  src/gnss/file_source.cpp
  src/gnss/reconnecting_source.cpp
  src/gnss/live_sources.cpp)
target_include_directories(acc_gnss PUBLIC include)

install(TARGETS acc_gnss
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_gnss
    test/unit/gtest_main.cpp
    test/unit/test_nmea_parser.cpp
    test/unit/test_nmea_line_assembler.cpp
    test/unit/test_nmea_writer.cpp
    test/unit/test_gnss_epoch.cpp
    test/unit/test_gnss_sources.cpp)
  target_link_libraries(test_gnss acc_gnss)
  target_compile_definitions(test_gnss PRIVATE ACC_GNSS_TEST_DATA="${PROJECT_SOURCE_DIR}/test/data/nmea")
endif()

# The ROS wrapper and its ten-line main.
add_library(acc_gnss_ros src/ros/gps_driver_ros.cpp)
target_include_directories(acc_gnss_ros PUBLIC include ${catkin_INCLUDE_DIRS})
target_link_libraries(acc_gnss_ros acc_gnss ${catkin_LIBRARIES})
add_dependencies(acc_gnss_ros ${PROJECT_NAME}_generate_messages_cpp)
add_executable(gps_driver_node src/nodes/gps_driver_node.cpp)
target_link_libraries(gps_driver_node acc_gnss_ros)
install(TARGETS acc_gnss_ros gps_driver_node
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
install(FILES launch/gps_driver.launch DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/launch)
install(FILES config/gps_driver.yaml DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/config)

# Parser throughput (issue 3 target: 2 million GGA + RMC sentences per second on one core).
# A plain executable, run by `make bench`, not by `make test`.
find_package(benchmark QUIET)
if(benchmark_FOUND)
  add_executable(bench_nmea bench/bench_nmea.cpp)
  target_link_libraries(bench_nmea acc_gnss benchmark::benchmark)
endif()

if(CATKIN_ENABLE_TESTING)
  find_package(rostest REQUIRED)
  # Checks what the node publishes when it replays test/data/nmea/drive_10s.nmea.
  add_rostest_gtest(test_gps_driver_file test/rostest/gps_driver_file.test
    test/rostest/gps_driver_file_check.cpp)
  target_link_libraries(test_gps_driver_file ${catkin_LIBRARIES})
  add_dependencies(test_gps_driver_file ${PROJECT_NAME}_generate_messages_cpp gps_driver_node)
  catkin_add_gtest(test_gnss_ros test/unit/gtest_main.cpp test/unit/test_gnss_ros_conversion.cpp)
  target_link_libraries(test_gnss_ros acc_gnss_ros)
  # 10 Hz at rate 1 (hztest).
  add_rostest(test/rostest/gps_driver_rate.test DEPENDENCIES gps_driver_node)
endif()
