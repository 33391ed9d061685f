# The few shapes every component's targets take, defined once so that each component file is a
# list of what it builds. Libraries are installed and exported (CMakeLists.txt lists them for
# catkin_package); executables land in the package's devel/install bin folder, where rosrun finds
# them.

# acc_add_library(NAME SOURCES file... [LINK target...])
# A ROS-free library of the science: the package's headers, nothing of ROS.
function(acc_add_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LINK" ${ARGN})
  add_library(${name} ${ARG_SOURCES})
  target_include_directories(${name} PUBLIC ${PROJECT_SOURCE_DIR}/include)
  target_link_libraries(${name} PUBLIC ${ARG_LINK})
  install(TARGETS ${name}
    ARCHIVE DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION}
    LIBRARY DESTINATION ${CATKIN_PACKAGE_LIB_DESTINATION})
endfunction()

# acc_add_ros_library(NAME SOURCES file... [LINK target...])
# A ROS wrapper library (src/ros/): roscpp, rosbag and the package's generated messages.
function(acc_add_ros_library name)
  cmake_parse_arguments(ARG "" "" "SOURCES;LINK" ${ARGN})
  acc_add_library(${name} SOURCES ${ARG_SOURCES} LINK ${ARG_LINK} ${catkin_LIBRARIES})
  target_include_directories(${name} PUBLIC ${catkin_INCLUDE_DIRS})
  add_dependencies(${name} ${PROJECT_NAME}_generate_messages_cpp)
endfunction()

# acc_add_node(NAME WRAPPER ros_library)
# A node: its ten-line main src/nodes/NAME.cpp on a ROS wrapper library, installed with its
# launch/NAME-without-_node.launch and config/NAME-without-_node.yaml when they exist.
function(acc_add_node name)
  cmake_parse_arguments(ARG "" "WRAPPER" "" ${ARGN})
  add_executable(${name} src/nodes/${name}.cpp)
  target_link_libraries(${name} ${ARG_WRAPPER})
  install(TARGETS ${name} RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
  string(REGEX REPLACE "_node$" "" base ${name})
  if(EXISTS ${PROJECT_SOURCE_DIR}/launch/${base}.launch)
    install(FILES launch/${base}.launch DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/launch)
  endif()
  if(EXISTS ${PROJECT_SOURCE_DIR}/config/${base}.yaml)
    install(FILES config/${base}.yaml DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/config)
  endif()
endfunction()

# acc_add_tool(NAME [LINK target...])
# A command-line tool: src/tools/NAME_main.cpp, run as `rosrun acc_identification NAME`; options
# parsed by CLI11, which writes --help from them.
function(acc_add_tool name)
  cmake_parse_arguments(ARG "" "" "LINK" ${ARGN})
  add_executable(${name} src/tools/${name}_main.cpp)
  target_link_libraries(${name} ${ARG_LINK} CLI11::CLI11)
  install(TARGETS ${name} RUNTIME DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})
endfunction()

# acc_add_benchmark(NAME [LINK target...])
# A Google Benchmark executable bench/NAME.cpp, run by `make bench`, never by `make test`.
function(acc_add_benchmark name)
  cmake_parse_arguments(ARG "" "" "LINK" ${ARGN})
  if(TARGET benchmark::benchmark)
    add_executable(${name} bench/${name}.cpp)
    target_link_libraries(${name} ${ARG_LINK} benchmark::benchmark)
  endif()
endfunction()
