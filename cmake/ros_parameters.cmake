# The nodes' parameters on the ROS parameter server as acc_parameters' ParameterReader reads them
# (src/ros/ros_parameter_source.cpp). Every node's ROS library links it; its rostest (with the
# nodes' loaders) is in package_checks.cmake.
acc_add_ros_library(acc_ros_parameters SOURCES src/ros/ros_parameter_source.cpp LINK acc_parameters)
