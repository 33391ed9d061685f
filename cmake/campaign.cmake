# Whole campaigns (OpenACC platoons): every follower grouped by (vehicle, distance setting) and
# identified with the paper's protocol in parallel, and each run's platoon predicted from its
# real first car with models fitted without that run. ROS-free library, the campaign tool, its
# figure script, tests and a benchmark.
# The groups and model fits run on std::threads (model/parallel_tasks.h).
acc_add_library(acc_campaign
  SOURCES
    src/campaign/campaign_inputs.cpp
    src/campaign/group_identification.cpp
    src/campaign/platoon_check.cpp
    src/campaign/platoon_diagnosis.cpp
    src/campaign/link_evidence.cpp
    src/campaign/shape_transfer.cpp
    src/campaign/gap_summary.cpp
    src/campaign/link_ratio_chain.cpp
    src/campaign/campaign.cpp
    src/campaign/campaign_output.cpp
    src/campaign/campaign_sumo_export.cpp
    src/campaign/campaign_sumo_platoon.cpp
  LINK acc_diagnosis acc_calibration acc_sumo acc_evidence acc_run_io acc_model nlohmann_json::nlohmann_json)

# rosrun acc_identification campaign [options] FILE_OR_DIR... --json FILE --report DIR
acc_add_tool(campaign LINK acc_campaign)
# campaign finds its figure script next to itself, as diagnose does: copied into the devel
# space's bin folder at configure time (again whenever it changes), installed beside the executable.
configure_file(scripts/plot_campaign.py
  ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION}/plot_campaign.py COPYONLY)
install(PROGRAMS scripts/plot_campaign.py DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

acc_add_benchmark(bench_campaign LINK acc_campaign)
if(TARGET bench_campaign)
  target_compile_definitions(bench_campaign PRIVATE ACC_ZALAZONE_DYNAMIC_DIR="${ACC_DATA_ZALAZONE_DYNAMIC_DIR}")
endif()

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_campaign
    test/unit/gtest_main.cpp
    test/unit/test_campaign_grouping.cpp
    test/unit/test_campaign_platoon.cpp
    test/unit/test_campaign_zalazone.cpp
    test/unit/test_campaign_sumo.cpp)
  target_compile_definitions(test_campaign PRIVATE ACC_ZALAZONE_DYNAMIC_DIR="${ACC_DATA_ZALAZONE_DYNAMIC_DIR}")
  target_link_libraries(test_campaign acc_campaign acc_validation)
endif()
