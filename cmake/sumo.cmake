# SUMO export and replay: the identified ACC as a SUMO 1.15 vType (carFollowModel ACC), SUMO's
# ACC law replicated in the package to explain every difference, and replays of real leaders in
# headless SUMO over TraCI (python3 with Debian's sumo-tools). The library is always built, as the
# calibrate, diagnose and campaign tools write vTypes; the replay tool needs the run reader.
find_package(tinyxml2 CONFIG REQUIRED)  # reads and writes SUMO's XML
acc_add_library(acc_sumo
  SOURCES
    src/sumo/sumo_acc_law.cpp
    src/sumo/sumo_vtype.cpp
    src/sumo/sumo_acc_simulation.cpp
    src/sumo/sumo_replay.cpp
    src/sumo/sumo_replay_report.cpp
  LINK acc_evidence acc_run_io acc_model nlohmann_json::nlohmann_json tinyxml2::tinyxml2)

# The TraCI driver beside the executables (devel and install space), where sumo_replay finds it.
configure_file(scripts/sumo_traci_replay.py
  ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION}/sumo_traci_replay.py COPYONLY)
install(PROGRAMS scripts/sumo_traci_replay.py DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

if(TARGET acc_calibration_ros AND TARGET acc_campaign)
  # rosrun acc_identification sumo_replay RUN --vtype FILE [--id ID...|--platoon] --json OUT
  acc_add_tool(sumo_replay LINK acc_campaign acc_sumo acc_calibration_ros acc_run_io)
endif()

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_sumo
    test/unit/gtest_main.cpp
    test/unit/test_sumo_vtype.cpp
    test/unit/test_sumo_replay.cpp)
  target_compile_definitions(test_sumo PRIVATE
    ACC_CASALE_DIR="${ACC_DATA_CASALE_DIR}"
    ACC_SUMO_DRIVER="${PROJECT_SOURCE_DIR}/scripts/sumo_traci_replay.py")
  target_link_libraries(test_sumo acc_sumo acc_calibration acc_run_io)
endif()
