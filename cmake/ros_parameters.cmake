# The nodes' one reader of their parameters (src/ros/parameter_reader.cpp): each parameter read
# with its type checked, so that a value of the wrong type (YAML 1.1's 1e6 is a string) is an error
# naming it, not a silent default; and a parameter set but never read (misspelt) is warned of.
# Every node's ROS library links it; its rostest (with the nodes' loaders) is in package_checks.cmake.
acc_add_ros_library(acc_ros_parameters SOURCES src/ros/parameter_reader.cpp)
