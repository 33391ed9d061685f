# Relative state (issue 8): the two vehicles' fixes paired by GNSS epoch, the bumper-to-bumper
# gap (geodesic, WGS84), the jump bound and the gap-versus-Doppler consistency; the OpenACC to
# NMEA converter; relative_state_node. Needs the gnss component (NMEA writer and log reader).
add_library(acc_relative_state
  src/relative_state/epoch_pairing.cpp
  src/relative_state/vehicle_geometry.cpp
  src/relative_state/gap_doppler_consistency.cpp
  src/relative_state/relative_state_estimator.cpp)
target_include_directories(acc_relative_state PUBLIC include ${GeographicLib_INCLUDE_DIRS})
target_link_libraries(acc_relative_state PUBLIC ${GeographicLib_LIBRARIES})

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_relative_state
    test/unit/gtest_main.cpp
    test/unit/test_pairing.cpp
    test/unit/test_relative_state_geometry.cpp
    test/unit/test_relative_state_estimator.cpp)
  target_link_libraries(test_relative_state acc_relative_state)
endif()
