# What the measured speeds say of string stability without any fitted model (always built, like
# the model core): perturbations of a leader and the dips they cause, the follower/leader dip
# ratio, the wild cluster bootstrap-t that tests model comparisons with few perturbations and,
# inverted, gives every interval over perturbations (a ratio's, a share's, a median's), and
# Welch's empirical frequency response of a link. The
# calibrate tool states it beside the model's verdict; the campaign per car and link.
acc_add_library(acc_evidence
  SOURCES
    src/evidence/perturbation.cpp
    src/evidence/wild_cluster_bootstrap.cpp
    src/evidence/wild_cluster_interval.cpp
    src/evidence/clustered_ratio.cpp
    src/evidence/clustered_median.cpp
    src/evidence/dip_shape_transfer.cpp
    src/evidence/empirical_response.cpp
    src/evidence/pair_dip_evidence.cpp
    src/evidence/perturbation_windows.cpp
    src/evidence/evidence_json.cpp
  LINK acc_model Eigen3::Eigen nlohmann_json::nlohmann_json)

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_evidence
    test/unit/gtest_main.cpp
    test/unit/test_clustered_ratio.cpp
    test/unit/test_clustered_median.cpp
    test/unit/test_empirical_response.cpp
    test/unit/test_pair_dip_evidence.cpp
    test/unit/test_perturbation_boundaries.cpp
    test/unit/test_perturbation_windows.cpp
    test/unit/test_wild_cluster_bootstrap.cpp
    test/unit/test_wild_cluster_interval.cpp)
  target_link_libraries(test_evidence acc_evidence)
endif()
