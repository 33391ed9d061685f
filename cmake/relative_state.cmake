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
install(TARGETS acc_relative_state
  ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
  LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_relative_state
    test/unit/gtest_main.cpp
    test/unit/test_pairing.cpp
    test/unit/test_relative_state_geometry.cpp
    test/unit/test_relative_state_estimator.cpp)
  target_link_libraries(test_relative_state acc_relative_state)
endif()

# The OpenACC converter writes NMEA with the gnss component's writer and its tests read the logs
# back with the gnss component's reader: both need acc_gnss.
if(TARGET acc_gnss)
  add_library(acc_conversion
    src/conversion/openacc_trajectories.cpp
    src/conversion/openacc_to_nmea.cpp)
  target_include_directories(acc_conversion PUBLIC include ${GeographicLib_INCLUDE_DIRS})
  target_link_libraries(acc_conversion PUBLIC acc_gnss ${GeographicLib_LIBRARIES})

  add_executable(openacc_to_nmea src/tools/openacc_to_nmea_main.cpp)
  target_link_libraries(openacc_to_nmea acc_conversion acc_cli)
  install(TARGETS acc_conversion openacc_to_nmea
    ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
    LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
    RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

  if(CATKIN_ENABLE_TESTING)
    # The real data (JRC OpenACC, Casale) lives beside the repository, not in it.
    get_filename_component(_acc_repository "${PROJECT_SOURCE_DIR}/CMakeLists.txt" REALPATH)
    get_filename_component(_acc_repository "${_acc_repository}" DIRECTORY)
    set(ACC_OPENACC_DATA_DIR "${_acc_repository}/../shared/data/openacc_casale"
        CACHE PATH "Folder of the OpenACC Casale runs part3..part6.csv for the real-data test")
    catkin_add_gtest(test_openacc
      test/unit/gtest_main.cpp
      test/unit/test_openacc_conversion.cpp
      test/unit/test_openacc_real_data.cpp)
    target_link_libraries(test_openacc acc_conversion acc_relative_state)
    target_compile_definitions(test_openacc PRIVATE
      ACC_RELSTATE_TEST_DATA="${PROJECT_SOURCE_DIR}/test/data/relative_state"
      ACC_OPENACC_DATA_DIR="${ACC_OPENACC_DATA_DIR}")
  endif()
endif()
