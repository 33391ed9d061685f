#pragma once

#include <cstdint>

namespace acc
{
/// When identifier_node asks its sequential string-stability verdict for a look at the drive so
/// far: at most once per look period while the drive grows, and once more as soon as the data
/// stop (the end of a replay, a pause), so that the last verdict is the look at every sample, as a
/// batch calibrate of them would give. Plain logic, called from the node's timer thread only.
class StabilityLookSchedule
{
public:
  /// look_period_s: the shortest ROS time between two looks while the data come (~stability_period_s).
  explicit StabilityLookSchedule(double look_period_s);

  struct Decision
  {
    bool run_period = true;     ///< false: nothing new to fit, look at or publish (the last estimate stands)
    bool look = false;          ///< ask the verdict for a look at the drive so far
    bool data_stopped = false;  ///< the look is the one at every sample: the data stopped
  };

  /// One period at ROS time now_s, with drive_samples taken by the drive so far (the kept count may
  /// stay level while samples are let go of). catch_up: /clock stood still for a second (under sim
  /// time no sample comes without it: the data stopped). all_looks_published: every look made is
  /// in a published message.
  Decision decide(double now_s, std::uint64_t drive_samples, bool catch_up, bool all_looks_published);

  /// The look last asked for was not made (its period was skipped, or the verdict's thread was
  /// still busy): the next period asks again.
  void lookLost() { last_look_samples_ = 0; }

private:
  double look_period_s_;
  double last_look_s_ = -1.0e300;         ///< ROS time of the last look asked for
  std::uint64_t last_look_samples_ = 0;   ///< drive samples taken then (0: none, or lost)
  std::uint64_t previous_period_samples_ = 0;
  /// Whether the last look asked for was the one made as the data stopped: a look made while they
  /// still came, at the same count, left its last, partial block to that one.
  bool last_look_data_stopped_ = false;
};
}  // namespace acc
