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
