// The estimator end to end on synthetic drives: gap and speeds, time gap, the jump bound, the
// gap-versus-Doppler consistency, the along-track option on a curve, and continuity breaks.
#include <gtest/gtest.h>

#include <GeographicLib/LocalCartesian.hpp>

#include <cmath>
#include <functional>
#include <vector>

#include "acc_identification/relative_state/relative_state_estimator.h"


namespace
{
constexpr double kOffset_m = 5.6;

/// A drive along a path: position(s) in the local plane at arc length s; both cars follow it.
struct Drive
{
  std::function<void(double s_m, double& east_m, double& north_m)> path;
  std::function<double(double t_s)> leader_s_m, follower_s_m, leader_v_mps, follower_v_mps;
  /// Added to the leader's position along its path: a position error the Doppler does not see.
  std::function<double(double t_s)> leader_position_error_m = [](double) { return 0.0; };
};

acc::GnssFix fixOf(const Drive& drive, double t, double s_m, double v_mps)
{
  static const GeographicLib::LocalCartesian plane(45.13, 8.45, 0.0);
  double east = 0, north = 0, height = 0;
  drive.path(s_m, east, north);
  acc::GnssFix fix;
  plane.Reverse(east, north, 0.0, fix.latitude_deg, fix.longitude_deg, height);
  fix.gnss_time_s = t;
  fix.has_date = true;
  fix.speed_over_ground_mps = v_mps;
  fix.course_rad = 0.0;
  fix.fix_quality = 1;
  fix.valid_fields = acc::GnssFix::kValidPosition | acc::GnssFix::kValidSpeed | acc::GnssFix::kValidCourse;
  return fix;
}

Drive straightDrive()
{
  Drive drive;
  drive.path = [](double s, double& e, double& n) { e = 0.0; n = s; };
  // The leader brakes and accelerates (sinusoid); the follower keeps 25 m/s.
  drive.leader_s_m = [](double t) { return 40.0 + 25.0 * t + 10.0 * std::sin(0.3 * t); };
  drive.leader_v_mps = [](double t) { return 25.0 + 3.0 * std::cos(0.3 * t); };
  drive.follower_s_m = [](double t) { return 25.0 * t; };
  drive.follower_v_mps = [](double) { return 25.0; };
  return drive;
}

std::vector<acc::RelativeState> run(acc::RelativeStateEstimator& estimator, const Drive& drive, double duration_s,
                                   std::function<void(double, acc::GnssFix&, acc::GnssFix&)> tamper = nullptr,
                                   double step_s = 0.1)
{
  for (int i = 0; i * step_s <= duration_s + 1e-9; ++i)
  {
    double t = 1000.0 + i * step_s;
    double tr = i * step_s;
    auto leader = fixOf(drive, t, drive.leader_s_m(tr) + drive.leader_position_error_m(tr), drive.leader_v_mps(tr));
    auto follower = fixOf(drive, t, drive.follower_s_m(tr), drive.follower_v_mps(tr));
    if (tamper)
      tamper(tr, leader, follower);
    estimator.addLeader(leader);
    estimator.addFollower(follower);
  }
  return estimator.takeStates();
}

acc::RelativeStateSettings settingsWithOffset()
{
  acc::RelativeStateSettings settings;
  settings.geometry.leader_antenna_to_rear_bumper_m = kOffset_m;
  return settings;
}
}  // namespace

TEST(RelativeStateEstimator, GapSpeedsAndTimeGapOnAStraightRoad)
{
  acc::RelativeStateEstimator estimator(settingsWithOffset());
  Drive drive = straightDrive();
  auto states = run(estimator, drive, 30.0);
  ASSERT_EQ(states.size(), 301u);
  for (std::size_t i = 0; i < states.size(); ++i)
  {
    double t = i * 0.1;
    const auto& s = states[i];
    ASSERT_TRUE(s.valid) << s.invalid_reason;
    EXPECT_NEAR(s.space_gap_m, drive.leader_s_m(t) - drive.follower_s_m(t) - kOffset_m, 0.01);
    EXPECT_NEAR(s.relative_speed_mps, drive.leader_v_mps(t) - 25.0, 1e-9);
    EXPECT_NEAR(s.time_gap_s, s.space_gap_m / 25.0, 1e-9);
    EXPECT_EQ(s.epoch_skew_s, 0.0);
  }
  // Consistent positions and Doppler speeds: only trapezoid error remains (centimetres).
  EXPECT_TRUE(std::isnan(states[50].gap_doppler_residual_m));
  EXPECT_LT(states.back().gap_doppler_residual_m, 0.02);
}

TEST(RelativeStateEstimator, ConsistencyFigureSeesAPositionErrorTheDopplerDoesNot)
{
  acc::RelativeStateEstimator estimator(settingsWithOffset());
  Drive drive = straightDrive();
  drive.leader_position_error_m = [](double t) { return 1.0 * std::sin(0.2 * t); };  // wandering 1 m
  auto states = run(estimator, drive, 60.0);
  EXPECT_GT(states.back().gap_doppler_residual_m, 0.3);
}

// Receivers given the other way round (the follower's fixes as the leader's): the gap is the same
// distance, the relative speed changes its sign, so over the recent windows the gap's change
// follows the relative speed's integral with a slope of -1, and the one rule (batch and the node's
// diagnostics) says swapped; the right way round it says 1, not swapped. Fails if the slope or
// the rule does not tell the two apart.
TEST(RelativeStateEstimator, ReceiversTheOtherWayRoundAreToldByTheGapAgainstTheDoppler)
{
  for (const bool swapped : {false, true})
  {
    acc::RelativeStateEstimator estimator(settingsWithOffset());
    run(estimator, straightDrive(), 30.0, [swapped](double, acc::GnssFix& leader, acc::GnssFix& follower) {
      if (swapped)
        std::swap(leader, follower);
    });
    const acc::GapDopplerConsistency& check = estimator.consistency();
    EXPECT_NEAR(check.recentGapPerDopplerSlope(), swapped ? -1.0 : 1.0, 0.05) << swapped;
    EXPECT_GT(check.recentDopplerIntegralRms(), 1.0);
    EXPECT_EQ(acc::receiversLookSwapped(check.recentGapPerDopplerSlope(), check.recentDopplerIntegralRms(),
                                        check.recentWindows()),
              swapped);
  }
  // Too little relative motion decides nothing, whatever the slope.
  EXPECT_FALSE(acc::receiversLookSwapped(-1.0, 0.5, 100));
  EXPECT_FALSE(acc::receiversLookSwapped(-1.0, 5.0, 9));
}

TEST(RelativeStateEstimator, ImpossibleJumpIsRejectedAndSaidSo)
{
  acc::RelativeStateEstimator estimator(settingsWithOffset());
  auto states = run(estimator, straightDrive(), 5.0, [](double t, acc::GnssFix& leader, acc::GnssFix&) {
    if (std::abs(t - 2.0) < 1e-6)
      leader.latitude_deg += 1e-4;  // 11 m north for one epoch: multipath, a bad fix
  });
  ASSERT_EQ(states.size(), 51u);
  const auto& bad = states[20];
  EXPECT_FALSE(bad.valid);
  EXPECT_NE(bad.invalid_reason.find("max_gap_rate"), std::string::npos) << bad.invalid_reason;
  EXPECT_TRUE(states[19].valid);
  EXPECT_TRUE(states[21].valid);  // judged against the last accepted sample, not the bad one
  EXPECT_EQ(estimator.counters().jumps_rejected, 1u);
  EXPECT_EQ(estimator.counters().invalid_states, 1u);
}

// One receiver's time labels a second off from 2 s on (a leap second applied by the leader's only):
// each of its fixes is where the leader was a second later, 25 m further. The jump check sees the
// step for jump_reference_max_age_s (1 s) and then took the shifted gaps as valid; the gap against
// the Doppler speeds since the last valid sample holds them invalid for the rest of the drive.
// A position error of 8 m for 3 s is held for those 3 s and no longer, and a lasting 2 m step (a
// receiver's position correcting: under both bounds) costs nothing.
TEST(RelativeStateEstimator, AStepTheDopplerSpeedsDoNotExplainStaysInvalid)
{
  const Drive drive = straightDrive();
  acc::RelativeStateEstimator shifted(settingsWithOffset());
  auto states = run(shifted, drive, 30.0, [&drive](double t, acc::GnssFix& leader, acc::GnssFix&) {
    if (t >= 2.0 - 1e-9)
      leader = fixOf(drive, leader.gnss_time_s, drive.leader_s_m(t + 1.0), drive.leader_v_mps(t + 1.0));
  });
  ASSERT_EQ(states.size(), 301u);
  EXPECT_TRUE(states[19].valid);
  for (std::size_t i = 20; i < states.size(); ++i)
    ASSERT_FALSE(states[i].valid) << i << ": gap " << states[i].space_gap_m;
  EXPECT_NE(states.back().invalid_reason.find("that the Doppler speeds do not explain"), std::string::npos)
      << states.back().invalid_reason;
  EXPECT_EQ(shifted.counters().jumps_rejected, 281u);

  for (const double error_m : {8.0, 2.0})
  {
    acc::RelativeStateEstimator moved(settingsWithOffset());
    const bool lasting = error_m < 5.0;
    auto moved_states = run(moved, drive, 10.0, [error_m, lasting](double t, acc::GnssFix& leader, acc::GnssFix&) {
      if (t >= 2.0 - 1e-9 && (lasting || t < 5.0 - 1e-9))
        leader.latitude_deg += error_m / 111195.0;  // the leader placed error_m further north
    });
    std::size_t invalid = 0;
    for (const acc::RelativeState& state : moved_states)
      invalid += state.valid ? 0 : 1;
    EXPECT_EQ(invalid, lasting ? 0u : 30u) << error_m;
    EXPECT_TRUE(moved_states.back().valid) << error_m << ": " << moved_states.back().invalid_reason;
  }
}

// OpenACC ZalaZone run 26: the follower's receiver updated its position every third or fourth
// epoch and repeated it in between, so the gap grew by its speed each epoch and jumped back (2.5 m
// in 0.1 s, under the jump bound). Fails when the repeated positions pass as measured gaps.
TEST(RelativeStateEstimator, AHeldPositionIsInvalidAndCounted)
{
  acc::RelativeStateEstimator estimator(settingsWithOffset());
  acc::GnssFix held;
  auto states = run(estimator, straightDrive(), 3.0, [&](double t, acc::GnssFix&, acc::GnssFix& follower) {
    const int epoch = static_cast<int>(std::lround(t / 0.1));
    if (t > 0.95 && t < 2.05 && epoch % 4 != 0)
      follower.latitude_deg = held.latitude_deg, follower.longitude_deg = held.longitude_deg;
    else
      held = follower;
  });
  ASSERT_EQ(states.size(), 31u);
  std::size_t invalid = 0;
  for (std::size_t i = 0; i < states.size(); ++i)
  {
    const bool held_here = i >= 10 && i <= 20 && i % 4 != 0;
    EXPECT_EQ(states[i].valid, !held_here) << i << ": " << states[i].invalid_reason;
    invalid += states[i].valid ? 0 : 1;
  }
  EXPECT_EQ(states[10].invalid_reason,
            "follower position held: the same as at 1000.90 s while its speed says it moved 2.50 m (a receiver "
            "that repeats its position between updates)");
  EXPECT_EQ(estimator.counters().held_positions, invalid);
  EXPECT_EQ(invalid, 8u);
  EXPECT_EQ(estimator.counters().jumps_rejected, 0u);
}

// A car that stands still repeats its position too: that is no held position.
TEST(RelativeStateEstimator, AStandingCarsRepeatedPositionIsValid)
{
  acc::RelativeStateEstimator estimator(settingsWithOffset());
  Drive drive = straightDrive();
  drive.follower_s_m = [](double) { return 0.0; };
  drive.follower_v_mps = [](double) { return 0.0; };
  auto states = run(estimator, drive, 1.0);
  for (const auto& state : states)
    EXPECT_TRUE(state.valid) << state.invalid_reason;
  EXPECT_EQ(estimator.counters().held_positions, 0u);
}

TEST(RelativeStateEstimator, SpeedJumpIsRejectedToo)
{
  acc::RelativeStateEstimator estimator(settingsWithOffset());
  auto states = run(estimator, straightDrive(), 3.0, [](double t, acc::GnssFix&, acc::GnssFix& follower) {
    if (std::abs(t - 1.0) < 1e-6)
      follower.speed_over_ground_mps += 5.0;  // 5 m/s in 0.1 s is 5 g
  });
  EXPECT_FALSE(states[10].valid);
  EXPECT_NE(states[10].invalid_reason.find("follower speed jump"), std::string::npos);
}

// One Doppler spike (a corrupt RMC speed field, 80 m/s for one epoch) is one invalid sample. Its
// speed once entered the relative speed's integral that the gap is checked against, carried the
// gap 8 m off, and every later sample of the drive was rejected as a gap jump the speeds did not
// explain. The same when the epoch's position glitches too (a gap jump and a speed jump at once).
TEST(RelativeStateEstimator, ADopplerSpikeCostsItsOwnSampleAndNoOther)
{
  for (const bool position_too : {false, true})
  {
    acc::RelativeStateEstimator estimator(settingsWithOffset());
    auto states = run(estimator, straightDrive(), 30.0, [&](double t, acc::GnssFix& leader, acc::GnssFix& follower) {
      if (std::abs(t - 10.0) < 1e-6)
      {
        follower.speed_over_ground_mps += 80.0;
        if (position_too)
          leader.latitude_deg += 1e-4;  // 11 m north
      }
    });
    ASSERT_EQ(states.size(), 301u);
    for (std::size_t i = 0; i < states.size(); ++i)
      EXPECT_EQ(states[i].valid, i != 100) << position_too << " at " << i << ": " << states[i].invalid_reason;
    EXPECT_EQ(estimator.counters().invalid_states, 1u) << position_too;
  }
}

TEST(RelativeStateEstimator, MissingSpeedAndStandstillAreInvalidOrNaNNotInvented)
{
  acc::RelativeStateEstimator estimator(settingsWithOffset());
  Drive drive = straightDrive();
  drive.follower_v_mps = [](double) { return 0.5; };
  auto states = run(estimator, drive, 1.0, [](double t, acc::GnssFix& leader, acc::GnssFix&) {
    if (std::abs(t - 0.5) < 1e-6)
      leader.valid_fields &= ~acc::GnssFix::kValidSpeed;
  });
  EXPECT_TRUE(std::isnan(states[0].time_gap_s));  // below min_speed_for_time_gap
  EXPECT_FALSE(states[5].valid);
  EXPECT_NE(states[5].invalid_reason.find("leader speed missing"), std::string::npos);
  EXPECT_EQ(estimator.counters().missing_speed, 1u);
}

// Speeds that are numbers but no car's overflow their difference: never a valid state that is not
// a number (found by test/fuzz/fuzz_relative_state.cpp).
TEST(RelativeStateEstimator, SpeedsNoCarHasGiveAnInvalidStateNotAnInfiniteOne)
{
  acc::RelativeStateEstimator estimator(settingsWithOffset());
  const auto states = run(estimator, straightDrive(), 0.3, [](double t, acc::GnssFix& leader, acc::GnssFix& follower) {
    if (std::abs(t - 0.2) < 1e-6)
    {
      leader.speed_over_ground_mps = 1.7e308;
      follower.speed_over_ground_mps = -1.7e308;
    }
  });
  ASSERT_EQ(states.size(), 4u);
  EXPECT_TRUE(states[1].valid);
  EXPECT_FALSE(states[2].valid);
  EXPECT_NE(states[2].invalid_reason.find("not a finite number"), std::string::npos) << states[2].invalid_reason;
  EXPECT_EQ(estimator.counters().invalid_states, 1u);
}

TEST(RelativeStateEstimator, DropoutRestartsTheConsistencyWindowAndLeavesNoSamples)
{
  acc::RelativeStateEstimator estimator(settingsWithOffset());
  std::vector<double> leader_times;
  auto states = run(estimator, straightDrive(), 40.0, [](double t, acc::GnssFix& leader, acc::GnssFix&) {
    if (t > 15.0 && t < 17.0)
      leader.fix_quality = 0;  // leader lost its fix for 2 s
  });
  EXPECT_EQ(estimator.pairingCounters().leader_invalid_fixes, 19u);
  EXPECT_EQ(estimator.pairingCounters().leader_dropouts, 1u);
  for (const auto& s : states)
    EXPECT_FALSE(s.time_s > 1015.05 && s.time_s < 1016.95) << "stale sample at " << s.time_s;
  // After the dropout the consistency needs a full new window.
  for (const auto& s : states)
  {
    if (s.time_s > 1017.0 && s.time_s < 1026.9)
    {
      EXPECT_TRUE(std::isnan(s.gap_doppler_residual_m)) << s.time_s;
    }
  }
  EXPECT_TRUE(std::isfinite(states.back().gap_doppler_residual_m));
}

TEST(RelativeStateEstimator, AlongTrackOptionMeasuresTheGapAlongACurve)
{
  const double radius_m = 80.0;
  Drive drive;
  drive.path = [radius_m](double s, double& e, double& n) {
    e = radius_m * std::cos(s / radius_m);
    n = radius_m * std::sin(s / radius_m);
  };
  drive.leader_s_m = [](double t) { return 45.0 + 15.0 * t; };
  drive.follower_s_m = [](double t) { return 15.0 * t; };
  drive.leader_v_mps = drive.follower_v_mps = [](double) { return 15.0; };
  auto settings = settingsWithOffset();
  acc::RelativeStateEstimator straight(settings);
  settings.gap_mode = acc::GapMode::kAlongTrack;
  acc::RelativeStateEstimator along(settings);
  auto chord_states = run(straight, drive, 12.0);
  auto along_states = run(along, drive, 12.0);
  ASSERT_EQ(chord_states.size(), along_states.size());
  const auto& last_chord = chord_states.back();
  const auto& last_along = along_states.back();
  EXPECT_NEAR(last_chord.space_gap_m, 2 * radius_m * std::sin(45.0 / (2 * radius_m)) - kOffset_m, 0.01);
  EXPECT_NEAR(last_along.space_gap_m, 45.0 - kOffset_m, 0.05);
  // At the start the leader's path does not reach back to the follower: straight line, counted.
  EXPECT_GT(along.counters().along_track_fallbacks, 0u);
  EXPECT_LT(along.counters().along_track_fallbacks, 35u);
}

TEST(RelativeStateEstimator, GapModeNamesRoundTrip)
{
  acc::GapMode mode = acc::GapMode::kStraightLine;
  EXPECT_TRUE(acc::parseGapMode("along_track", mode));
  EXPECT_EQ(mode, acc::GapMode::kAlongTrack);
  EXPECT_STREQ(acc::gapModeName(mode), "along_track");
  EXPECT_FALSE(acc::parseGapMode("chord", mode));
}

// Receivers at 1 Hz and 0.5 Hz, with dropout_gap_s above their step: the jump check looks back one
// step of the stream, however far that is beyond jump_reference_max_age_s (1 s). Fails when a
// 2 s step leaves every sample unchecked.
TEST(RelativeStateEstimator, ASlowStreamIsJumpCheckedAcrossItsOwnStep)
{
  for (const double step_s : {1.0, 2.0})
  {
    acc::RelativeStateSettings settings = settingsWithOffset();
    settings.pairing.dropout_gap_s = 2.5 * step_s;
    acc::RelativeStateEstimator estimator(settings);
    auto states = run(
        estimator, straightDrive(), 20.0,
        [step_s](double t, acc::GnssFix& leader, acc::GnssFix&) {
          if (std::abs(t - 5.0 * step_s) < 1e-6)
            leader.latitude_deg += 1e-3;  // 111 m north for one epoch
        },
        step_s);
    ASSERT_GT(states.size(), 6u);
    EXPECT_FALSE(states[5].valid) << step_s << " s";
    EXPECT_NE(states[5].invalid_reason.find("max_gap_rate"), std::string::npos) << states[5].invalid_reason;
    EXPECT_TRUE(states[6].valid) << step_s << " s";
    EXPECT_EQ(estimator.counters().jumps_rejected, 1u) << step_s << " s";
  }
}
