# Sim-to-real gap diagnosis (issue 6): where the calibrated model's held-out residual lies, which
# missing physical effect explains it, and what adding that effect buys. ROS-free library, the
# diagnose tool and unit tests; the suites that check the diagnosis on data with known effects
# are the validation library beside it.
acc_add_library(acc_diagnosis
  SOURCES
    src/diagnosis/augmented_calibration.cpp
    src/diagnosis/augmented_standard_errors.cpp
    src/diagnosis/residual_breakdown.cpp
    src/diagnosis/effect_selection.cpp
    src/diagnosis/perturbation_window_criterion.cpp
    src/diagnosis/augmented_stability.cpp
    src/diagnosis/augmented_stability_verdict.cpp
    src/diagnosis/diagnosis.cpp
    src/diagnosis/determined_effects.cpp
    src/diagnosis/augmented_fit_json.cpp
    src/diagnosis/final_model_bootstrap.cpp
    src/diagnosis/diagnosis_output.cpp
    src/diagnosis/diagnosis_text.cpp
    src/diagnosis/calibration_second_opinion.cpp
  # acc_calibration: the model-adequacy checks of the base and the final model (model_adequacy.h).
  LINK acc_calibration acc_evidence acc_sumo acc_model ${ACC_NLOPT_TARGET} nlohmann_json::nlohmann_json)

# The diagnosis's own checks, a library of their own (cmake/validation.cmake).
include(cmake/validation.cmake)

# The tool reads runs (CSV or bags) as the calibrate tool does (calibration component).
if(TARGET acc_calibration_ros)
  acc_add_tool(diagnose LINK acc_validation acc_diagnosis acc_calibration_ros acc_run_io acc_sumo)
  # --withheld-suite semi-real injects effects into the bundled real runs (cmake/data.cmake).
  target_compile_definitions(diagnose PRIVATE ACC_CASALE_DIR="${ACC_DATA_CASALE_DIR}"
    ACC_ZALAZONE_TOYOTA_DIR="${ACC_DATA_ZALAZONE_TOYOTA_RAV4_S_DIR}")
  # diagnose finds its figure script next to itself: copied into the devel space's bin folder at
  # configure time (again whenever it changes), installed beside the executable.
  configure_file(scripts/plot_diagnosis.py
    ${CATKIN_DEVEL_PREFIX}/${CATKIN_PACKAGE_BIN_DESTINATION}/plot_diagnosis.py COPYONLY)
  install(PROGRAMS scripts/plot_diagnosis.py DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
else()
  message(STATUS "diagnosis: acc_calibration_ros not built (add calibration to ACC_COMPONENTS): no diagnose tool")
endif()

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_diagnosis
    test/unit/gtest_main.cpp
    test/unit/test_diagnosis_simulation.cpp
    test/unit/test_diagnosis_selection.cpp
    test/unit/test_diagnosis_withheld.cpp
    test/unit/test_diagnosis_output.cpp
    test/unit/test_diagnosis_stability.cpp
    test/unit/test_diagnosis_forward.cpp
    test/unit/test_diagnosis_perturbation_windows.cpp
    test/unit/test_diagnosis_injected.cpp
    test/unit/test_diagnosis_combined.cpp
    test/unit/test_diagnosis_determined.cpp
    test/unit/test_diagnosis_adequacy.cpp
    test/unit/test_diagnosis_bootstrap.cpp)
  # The semi-real test reads a bundled real run (acc_run_io, cmake/data.cmake).
  target_link_libraries(test_diagnosis acc_validation acc_diagnosis acc_run_io)
  target_compile_definitions(test_diagnosis PRIVATE ACC_CASALE_DIR="${ACC_DATA_CASALE_DIR}"
    ACC_ZALAZONE_TOYOTA_DIR="${ACC_DATA_ZALAZONE_TOYOTA_RAV4_S_DIR}")
endif()

# One whole diagnose of the bundled 25-minute Casale part6 run (cmake/data.cmake).
acc_add_benchmark(bench_diagnosis LINK acc_diagnosis acc_validation acc_run_io)
if(TARGET bench_diagnosis)
  target_compile_definitions(bench_diagnosis PRIVATE ACC_CASALE_DIR="${ACC_DATA_CASALE_DIR}")
endif()
