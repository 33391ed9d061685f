# The model core: the ACC law, simulation of one follower and of a platoon, string stability, and
# the small thread pool the campaign and the diagnosis run their independent fits on.
find_package(Threads REQUIRED)
acc_add_library(acc_model
  SOURCES
    src/model/acc_model.cpp
    src/model/car_following_run.cpp
    src/model/pooled_moments.cpp
    src/model/follower_simulation.cpp
    src/model/platoon_simulation.cpp
    src/model/string_stability.cpp
    src/model/paper_settings.cpp
    src/model/halton_sequence.cpp
    src/model/block_bootstrap.cpp
    src/model/sample_statistics.cpp
    src/model/number_text.cpp
    src/model/plain_text.cpp
    src/model/normal_source.cpp
    src/model/follower_effects.cpp
    src/model/batch_means.cpp
    src/model/start_gap_covariance.cpp
    src/model/parallel_tasks.cpp
  LINK Eigen3::Eigen Boost::headers m Threads::Threads)

acc_add_tool(stability_report LINK acc_model)

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_model
    test/unit/gtest_main.cpp
    test/unit/test_acc_model.cpp
    test/unit/test_string_stability.cpp
    test/unit/test_follower_simulation.cpp
    test/unit/test_platoon_simulation.cpp
    test/unit/test_normal_source.cpp
    test/unit/test_number_text.cpp
    test/unit/test_sample_statistics.cpp)
  target_link_libraries(test_model acc_model)
endif()
