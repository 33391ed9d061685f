# End to end (issue 5): launch/replay.launch, `make demo`, and rostests that replay bags of raw
# NMEA sentences through both drivers (topic source), relative_state and the identifier.
install(FILES launch/replay.launch launch/drive.launch launch/replay_nmea.launch launch/chain.launch
  DESTINATION ${CATKIN_PACKAGE_SHARE_DESTINATION}/launch)
install(PROGRAMS scripts/demo_listener.py DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})

# A rostest of test/rostest/TEMPLATE on a bag made at build time (target BAG_TARGET): a small
# launch file in the build tree, NAME.test, passes the bag's path on as the template's "bag"
# argument, so that the target's name holds no absolute path (as cmake/relative_state.cmake does).
function(acc_add_bag_rostest NAME TEMPLATE BAG BAG_TARGET)
  set(_acc_launch ${PROJECT_BINARY_DIR}/rostest/${NAME}.test)
  file(CONFIGURE OUTPUT ${_acc_launch} @ONLY CONTENT [=[
<!-- Made by cmake/end_to_end.cmake from test/rostest/@TEMPLATE@. -->
<launch>
  <include file="$(find acc_identification)/test/rostest/@TEMPLATE@">
    <arg name="bag" value="@BAG@"/>
  </include>
</launch>
]=])
  add_rostest(${_acc_launch} DEPENDENCIES ${ACC_END_TO_END_TARGETS} ${BAG_TARGET})
endfunction()

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
  # A receiver at 1 Hz: a drive synthesize makes at build time (seeded), replayed with max_gap_s 2.5.
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
    acc_add_bag_rostest(end_to_end_coarse_1hz end_to_end_coarse.test ${_acc_coarse_bag} end_to_end_coarse_bag)
  else()
    message(WARNING "end_to_end: synthesize is not built (ACC_COMPONENTS): no 1 Hz end-to-end rostest")
  endif()
  # A take-over by the safety driver: the Casale part 3 bag with the ACC's engagement reports a
  # drive records on /acc_engaged (off from 100 s to 130 s), made at build time from the bundled bag.
  set(_acc_take_over_dir ${PROJECT_BINARY_DIR}/rostest/take_over)
  set(_acc_take_over_bag ${_acc_take_over_dir}/casale_part3_take_over.bag)
  add_custom_command(
    OUTPUT ${_acc_take_over_bag}
    COMMAND ${CMAKE_COMMAND} -E make_directory ${_acc_take_over_dir}
    COMMAND ${PYTHON_EXECUTABLE} ${PROJECT_SOURCE_DIR}/test/rostest/add_take_over.py
            ${PROJECT_SOURCE_DIR}/bags/casale_part3_sentences.bag ${_acc_take_over_bag} 100 130
    DEPENDS ${PROJECT_SOURCE_DIR}/test/rostest/add_take_over.py ${PROJECT_SOURCE_DIR}/bags/casale_part3_sentences.bag
    COMMENT "the Casale part 3 drive with a take-over on /acc_engaged, for end_to_end_take_over"
    VERBATIM)
  add_custom_target(end_to_end_take_over_bag DEPENDS ${_acc_take_over_bag})
  add_dependencies(tests end_to_end_take_over_bag)
  acc_add_bag_rostest(end_to_end_take_over end_to_end_take_over.test ${_acc_take_over_bag} end_to_end_take_over_bag)
endif()
