# The nodes' and tools' one reader of their parameters (src/parameters/): each parameter read with
# its type checked, so that a value of the wrong type (YAML 1.1's 1e6 is a string) is an error
# naming it, not a silent default, and a parameter set but never read (misspelt) is warned of.
# Its sources: the ROS parameter server (acc_ros_parameters, cmake/ros_parameters.cmake) or a YAML
# file of the same keys, typed as rosparam types it (yaml-cpp, PyYAML's YAML 1.1 resolver), for the
# tools that read a node's config file (nmea_to_csv --params).
find_package(yaml-cpp REQUIRED)
acc_add_library(acc_parameters
  SOURCES
    src/parameters/parameter_source.cpp
    src/parameters/parameter_reader.cpp
    src/parameters/yaml_parameter_source.cpp
  LINK yaml-cpp)

if(CATKIN_ENABLE_TESTING)
  catkin_add_gtest(test_parameters
    test/unit/gtest_main.cpp
    test/unit/test_yaml_parameters.cpp)
  target_link_libraries(test_parameters acc_parameters)
endif()
