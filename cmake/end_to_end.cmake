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
endif()
