# End to end (issue 5): launch/replay.launch, `make demo`, and rostests that replay bags of raw
# NMEA sentences through both drivers (topic source), relative_state and the identifier.
install(FILES launch/replay.launch launch/drive.launch launch/replay_nmea.launch launch/chain.launch
  DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/launch)
install(PROGRAMS scripts/demo_listener.py DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

if(CATKIN_ENABLE_TESTING)
  # The chain's nodes and the batch calibrate the tests compare with.
  set(ACC_END_TO_END_TARGETS)
  foreach(target gps_driver_node relative_state_node identifier_node calibrate)
    if(TARGET ${target})
      list(APPEND ACC_END_TO_END_TARGETS ${target})
    else()
      message(WARNING "end_to_end: target ${target} is not built (ACC_COMPONENTS); its rostests will fail")
    endif()
  endforeach()
  # Synthetic bag at 20x: parameters within tolerance of the truth, and no sample dropped.
  add_rostest(test/rostest/end_to_end_synthetic.test DEPENDENCIES ${ACC_END_TO_END_TARGETS})
  # Real (Casale) bag at 20x: parameters as a batch calibrate of the same samples, no sample dropped.
  add_rostest(test/rostest/end_to_end_real.test DEPENDENCIES ${ACC_END_TO_END_TARGETS})
  # A real perturbation session (ZalaZone): the verdict decided live, before the end of the drive.
  add_rostest(test/rostest/end_to_end_zalazone.test DEPENDENCIES ${ACC_END_TO_END_TARGETS})
  # Both drivers hold 10 Hz at rate 1 (hztest), decoding the bag's sentences from the topic.
  add_rostest(test/rostest/end_to_end_rate.test DEPENDENCIES ${ACC_END_TO_END_TARGETS})
  # A 5 s leader dropout: no parameters from the gap, recovery after it.
  add_rostest(test/rostest/end_to_end_dropout.test DEPENDENCIES ${ACC_END_TO_END_TARGETS})
  # A receiver at 1 Hz: a drive synthesize makes at build time (seeded), replayed with max_gap_s
  # 2.5. As relative_state.cmake does, a small launch file in the build tree passes the bag's path
  # on, so that the target's name holds no absolute path.
  if(TARGET synthesize)
    set(_acc_coarse_dir ${PROJECT_BINARY_DIR}/rostest/coarse_1hz)
    set(_acc_coarse_bag ${_acc_coarse_dir}/synthetic_min_F_1hz.bag)
    add_custom_command(
      OUTPUT ${_acc_coarse_bag}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${_acc_coarse_dir}
      COMMAND synthesize --profile F --setting min --seed 1 --rate-hz 1 --leader-log ${_acc_coarse_dir}/leader.nmea
              --follower-log ${_acc_coarse_dir}/follower.nmea --parameters-json ${_acc_coarse_dir}/parameters.json
              --bag ${_acc_coarse_bag}
      DEPENDS synthesize
      COMMENT "a 1 Hz synthetic drive for end_to_end_coarse"
      VERBATIM)
    add_custom_target(end_to_end_coarse_bag DEPENDS ${_acc_coarse_bag})
    add_dependencies(tests end_to_end_coarse_bag)
    set(_acc_launch ${PROJECT_BINARY_DIR}/rostest/end_to_end_coarse_1hz.test)
    file(CONFIGURE OUTPUT ${_acc_launch} @ONLY CONTENT [=[
<!-- Made by cmake/end_to_end.cmake: the 1 Hz synthetic drive. -->
<launch>
  <include file="$(find acc_identification)/test/rostest/end_to_end_coarse.test">
    <arg name="bag" value="@_acc_coarse_bag@"/>
  </include>
</launch>
]=])
    add_rostest(${_acc_launch} DEPENDENCIES ${ACC_END_TO_END_TARGETS} end_to_end_coarse_bag)
  else()
    message(WARNING "end_to_end: synthesize is not built (ACC_COMPONENTS): no 1 Hz end-to-end rostest")
  endif()
endif()
