# The diagnosis's validation suites (ROS-free): synthetic runs with a withheld effect, every pair of
# effects withheld at once, and the bundled real runs with an effect injected; each run case by
# case with the confusion matrix or tables that diagnose --withheld-suite prints.
acc_add_library(acc_validation
  SOURCES
    src/validation/withheld_effect_suite.cpp
    src/validation/combined_effect_suite.cpp
    src/validation/injected_effect.cpp
    src/validation/suite_runs.cpp
  LINK acc_diagnosis acc_run_io acc_model nlohmann_json::nlohmann_json)
