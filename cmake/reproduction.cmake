# Reproduction of the paper's analyses and figures (issue 7): the numbers behind each figure and
# the lead profiles A-I of Section III as a ROS-free library, and the `platoon` command-line tool.
acc_add_library(acc_reproduction
  SOURCES
    src/reproduction/lead_profiles.cpp
    src/reproduction/lambda2_map.cpp
    src/reproduction/frequency_response.cpp
    src/reproduction/lead_inputs.cpp
    src/reproduction/platoon_metrics.cpp
    src/reproduction/platoon_responses.cpp
    src/reproduction/run_comparison.cpp
    src/reproduction/equilibrium_regression.cpp
    src/reproduction/parameter_file.cpp
    src/reproduction/figure_options.cpp
    src/reproduction/figure_csv.cpp
    src/reproduction/figure_summary.cpp
    src/reproduction/simulated_figures.cpp
    src/reproduction/measured_figures.cpp
    src/reproduction/paper_figures.cpp
  LINK acc_model acc_run_io)
target_link_libraries(acc_reproduction PRIVATE nlohmann_json::nlohmann_json)

acc_add_tool(platoon LINK acc_reproduction acc_run_io nlohmann_json::nlohmann_json)
install(PROGRAMS scripts/plot_figures.py scripts/reproduce_figures.sh scripts/bundled_data.sh
  DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_reproduction
    test/unit/gtest_main.cpp
    test/unit/test_lead_profiles.cpp
    test/unit/test_reproduction_lambda2_map.cpp
    test/unit/test_reproduction_frequency_response.cpp
    test/unit/test_reproduction_platoon.cpp
    test/unit/test_reproduction_runs.cpp
    test/unit/test_reproduction_equilibrium.cpp
    test/unit/test_reproduction_figure_options.cpp)
  target_link_libraries(test_reproduction acc_reproduction)
endif()
