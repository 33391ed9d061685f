// libFuzzer target for the relative state (pairing by GNSS epoch, the gap, the jump, held-position
// and consistency checks): the two receivers' fixes as a radio link and a bad receiver can deliver
// them to relative_state_node (late, out of order, duplicated, across time resets and day
// rollovers, with positions anywhere and NaN or infinite fields), each setting drawn from its
// documented range, then the end of the streams as nmea_to_csv ends them (finish()). Built and
// run by scripts/test_hooks/fuzz_relative_state.sh with -fsanitize=fuzzer,address,undefined.
// Besides crashes it checks the estimator's promises: every follower fix is paired or counted
// under a reason once the streams end (nothing dropped silently), one state per pair, states in
// increasing GNSS time between the follower's time resets, and a valid state's numbers finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <vector>

#include <fuzzer/FuzzedDataProvider.h>

#include "acc_identification/relative_state/relative_state_estimator.h"
#include "fuzz_support.h"

namespace
{
using fuzz_support::check;
using fuzz_support::field;

/// Settings from each parameter's documented range (config/relative_state.yaml): small buffers
/// and short waits reach the overflow and give-up paths within a short input.
acc::RelativeStateSettings settingsFrom(FuzzedDataProvider& input)
{
  acc::RelativeStateSettings s;
  s.gap_mode = input.ConsumeBool() ? acc::GapMode::kAlongTrack : acc::GapMode::kStraightLine;
  s.geometry = {input.ConsumeFloatingPointInRange<double>(-5.0, 10.0), input.ConsumeFloatingPointInRange<double>(-5.0, 10.0)};
  s.pairing.exact_match_tolerance_s = input.ConsumeFloatingPointInRange<double>(0.0, 0.05);
  s.pairing.max_interpolation_skew_s = input.ConsumeFloatingPointInRange<double>(0.0, 1.0);
  s.pairing.exact_wait_s = input.ConsumeFloatingPointInRange<double>(0.0, 2.0);
  s.pairing.timeout_s = input.ConsumeFloatingPointInRange<double>(0.01, 5.0);
  s.pairing.dropout_gap_s = input.ConsumeFloatingPointInRange<double>(0.01, 3.0);
  s.pairing.time_reset_s = input.ConsumeFloatingPointInRange<double>(0.01, 10.0);
  s.pairing.time_reset_confirm_fixes = input.ConsumeIntegralInRange<std::size_t>(1, 8);
  s.pairing.max_buffered_fixes = input.ConsumeIntegralInRange<std::size_t>(1, 64);
  s.track_min_spacing_m = input.ConsumeFloatingPointInRange<double>(0.01, 5.0);
  s.jump_reference_max_age_s = input.ConsumeFloatingPointInRange<double>(0.0, 2.0);
  s.consistency_window_s = input.ConsumeFloatingPointInRange<double>(0.01, 20.0);
  return s;
}

/// One stream's clock: mostly 10 Hz steps, sometimes late, repeated, jumping or not a time.
struct StreamClock
{
  double time_s;

  double next(FuzzedDataProvider& input)
  {
    switch (input.ConsumeIntegralInRange<int>(0, 11))
    {
      case 0:
        return time_s;  // the same epoch again
      case 1:
        return time_s - input.ConsumeFloatingPointInRange<double>(0.0, 12.0);  // late, or a reset
      case 2:
        return time_s += input.ConsumeFloatingPointInRange<double>(0.0, 90000.0);  // a dropout, a day
      case 3:
        return field(input, -1e10, 1e10);  // anything, the clock left as it was
      default:
        return time_s += 0.1 + input.ConsumeFloatingPointInRange<double>(-0.02, 0.02);
    }
  }
};

acc::GnssFix fixFrom(FuzzedDataProvider& input, StreamClock& clock, bool has_date)
{
  acc::GnssFix fix;
  fix.gnss_time_s = clock.next(input);
  fix.has_date = has_date;
  fix.latitude_deg = 45.0 + field(input, -0.001, 0.001) * (input.ConsumeBool() ? 1.0 : 1e5);
  fix.longitude_deg = 7.6 + field(input, -0.001, 0.001) * (input.ConsumeBool() ? 1.0 : 1e5);
  fix.altitude_m = field(input, -100.0, 3000.0);
  fix.speed_over_ground_mps = field(input, -1.0, 60.0);
  fix.course_rad = field(input, 0.0, 6.3);
  fix.fix_quality = input.ConsumeIntegralInRange<std::uint8_t>(0, 8);
  fix.satellites_used = input.ConsumeIntegral<std::uint16_t>();
  fix.hdop = field(input, 0.5, 10.0);
  fix.latitude_sigma_m = field(input, 0.0, 5.0);
  fix.longitude_sigma_m = field(input, 0.0, 5.0);
  fix.valid_fields = input.ConsumeIntegral<std::uint32_t>() | (input.ConsumeBool() ? 0u : 0xFFu);
  return fix;
}

/// The states of one call: one per pair, increasing in time unless the follower's clock was reset.
struct StateChecks
{
  std::uint64_t states = 0;
  double last_time_s = -std::numeric_limits<double>::infinity();

  void take(acc::RelativeStateEstimator& estimator, std::uint64_t follower_resets_before)
  {
    if (estimator.pairingCounters().follower_time_resets != follower_resets_before)
      last_time_s = -std::numeric_limits<double>::infinity();
    for (const acc::RelativeState& state : estimator.takeStates())
    {
      ++states;
      check(std::isfinite(state.time_s), "a state has a finite time");
      check(state.time_s > last_time_s, "states come in increasing time between the follower's resets");
      last_time_s = state.time_s;
      check(state.valid == state.invalid_reason.empty(), "an invalid state says why, a valid one does not");
      if (state.valid)
        check(std::isfinite(state.space_gap_m) && std::isfinite(state.follower_speed_mps) &&
                  std::isfinite(state.leader_speed_mps) && std::isfinite(state.relative_speed_mps),
              "a valid state's gap and speeds are finite");
    }
  }
};

void checkEveryFixCounted(const acc::RelativeStateEstimator& estimator, std::uint64_t states)
{
  const acc::PairingCounters& c = estimator.pairingCounters();
  check(states == c.exact_pairs + c.interpolated_pairs, "one state per pair");
  check(estimator.counters().states == states, "the estimator counts every state it gave");
  const std::uint64_t follower_accounted = c.exact_pairs + c.interpolated_pairs + c.follower_invalid_fixes +
                                           c.follower_duplicates + c.follower_too_late + c.follower_unpaired +
                                           c.follower_stray_stamps;
  // Overflows are counted for both streams together: a follower fix discarded there is one of them.
  check(follower_accounted <= c.follower_fixes && c.follower_fixes <= follower_accounted + c.buffer_overflows,
        "every follower fix is paired or counted once the streams end");
  check(c.leader_invalid_fixes + c.leader_duplicates + c.leader_too_late + c.leader_stray_stamps <= c.leader_fixes,
        "no leader fix is counted twice");
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  FuzzedDataProvider input(data, size);
  acc::RelativeStateEstimator estimator(settingsFrom(input));
  const bool has_date = input.ConsumeBool();
  const double start_s = has_date ? 1.7e9 : input.ConsumeFloatingPointInRange<double>(0.0, 86400.0);
  StreamClock leader{start_s}, follower{start_s + input.ConsumeFloatingPointInRange<double>(-0.2, 0.2)};
  StateChecks states;
  while (input.remaining_bytes() > 0)
  {
    const std::uint64_t resets = estimator.pairingCounters().follower_time_resets;
    if (input.ConsumeBool())
      estimator.addLeader(fixFrom(input, leader, has_date));
    else
      estimator.addFollower(fixFrom(input, follower, has_date));
    states.take(estimator, resets);
    estimator.takeEvents();
  }
  const std::uint64_t resets = estimator.pairingCounters().follower_time_resets;
  estimator.finish();
  states.take(estimator, resets);
  checkEveryFixCounted(estimator, states.states);
  return 0;
}
