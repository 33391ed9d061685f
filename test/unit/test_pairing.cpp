// Pairing by GNSS epoch: exact, interpolated, late and bursty, out of order, dropouts, time
// going back. The vehicles drive north on a straight line, so a fix's latitude tells its time.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "acc_identification/model/portable_uniform.h"
#include "acc_identification/relative_state/epoch_pairing.h"


namespace
{
constexpr double kDegPerSecond = 1e-4;  // the latitude of a fix encodes its GNSS time

acc::GnssFix fixAt(double time_s, double offset_deg = 0.0)
{
  acc::GnssFix fix;
  fix.gnss_time_s = time_s;
  fix.has_date = true;
  fix.latitude_deg = 45.0 + offset_deg + kDegPerSecond * time_s;
  fix.longitude_deg = 8.0;
  fix.speed_over_ground_mps = 10.0 + time_s;
  fix.course_rad = 0.0;
  fix.fix_quality = 1;
  fix.valid_fields = acc::GnssFix::kValidPosition | acc::GnssFix::kValidSpeed | acc::GnssFix::kValidCourse;
  return fix;
}

std::vector<double> epochs(double start_s, double end_s, double step_s = 0.1, double phase_s = 0.0)
{
  std::vector<double> times;
  for (int i = 0; start_s + i * step_s <= end_s + 1e-9; ++i)
    times.push_back(start_s + i * step_s + phase_s);
  return times;
}

void expectIncreasingAndFresh(const std::vector<acc::PairedEpoch>& pairs, double max_skew_s)
{
  for (std::size_t i = 0; i < pairs.size(); ++i)
  {
    if (i > 0)
    {
      EXPECT_GT(pairs[i].time_s, pairs[i - 1].time_s) << "output went back at " << i;
    }
    // The leader's latitude must be its position at the pair's own time: never stale data.
    EXPECT_NEAR(pairs[i].leader.latitude_deg, 45.0 + kDegPerSecond * pairs[i].time_s, 1e-9);
    EXPECT_LE(pairs[i].epoch_skew_s, max_skew_s);
  }
}
}  // namespace

TEST(Pairing, ExactEpochsPairOneToOne)
{
  acc::EpochPairer pairer;
  for (double t : epochs(0.0, 5.0))
  {
    pairer.addLeader(fixAt(t));
    pairer.addFollower(fixAt(t, -0.001));
  }
  auto pairs = pairer.takePairs();
  ASSERT_EQ(pairs.size(), 51u);
  EXPECT_EQ(pairer.counters().exact_pairs, 51u);
  EXPECT_EQ(pairer.counters().interpolated_pairs, 0u);
  EXPECT_TRUE(pairs.front().continuity_break);
  EXPECT_FALSE(pairs[1].continuity_break);
  for (const auto& pair : pairs)
    EXPECT_EQ(pair.epoch_skew_s, 0.0);
  expectIncreasingAndFresh(pairs, 0.0);
}

TEST(Pairing, InterpolatesALeaderWithAPhaseOffsetAndReportsTheSkew)
{
  acc::EpochPairer pairer;
  for (double t : epochs(0.0, 5.0))
  {
    pairer.addLeader(fixAt(t + 0.03));
    pairer.addFollower(fixAt(t, -0.001));
  }
  pairer.addLeader(fixAt(5.13));
  auto pairs = pairer.takePairs();
  // The first follower epoch (0.0) has no leader before it: it waits, then times out.
  ASSERT_EQ(pairs.size(), 50u);
  EXPECT_EQ(pairer.counters().interpolated_pairs, 50u);
  for (const auto& pair : pairs)
  {
    EXPECT_NEAR(pair.epoch_skew_s, 0.03, 1e-9);
    EXPECT_NEAR(pair.leader.speed_over_ground_mps, 10.0 + pair.time_s, 1e-9);
  }
  expectIncreasingAndFresh(pairs, 0.03 + 1e-9);
}

// A 5 Hz leader 50 ms off a 10 Hz follower: every other follower epoch lies exactly 0.15 s (the
// skew) before the next leader epoch, where the rounding of the times decided and most were lost.
// Within the exact tolerance of the skew they all pair. A 4 Hz leader (0.25 s apart) leaves some
// between two of its epochs unpaired every time, and the event says what to set.
TEST(Pairing, ALeaderAtHalfTheRateWithAPhaseOffsetPairsEveryEpochBetweenItsOwn)
{
  for (const double phase_s : {0.05, 0.049, 0.051})
  {
    acc::EpochPairer pairer;
    const std::vector<double> leader = epochs(0.0, 60.2, 0.2, phase_s);
    std::size_t next_leader = 0;
    std::size_t paired = 0;
    for (double t : epochs(1.0, 59.0))
    {
      for (; next_leader < leader.size() && leader[next_leader] <= t + 0.3; ++next_leader)
        pairer.addLeader(fixAt(leader[next_leader]));
      pairer.addFollower(fixAt(t, -0.001));
      paired += pairer.takePairs().size();
    }
    pairer.finish();
    paired += pairer.takePairs().size();
    EXPECT_EQ(paired, 581u) << phase_s;
    EXPECT_EQ(pairer.counters().follower_unpaired, 0u) << phase_s;
  }
  acc::EpochPairer pairer;
  for (double t : epochs(0.0, 10.0, 0.25, 0.05))
    pairer.addLeader(fixAt(t));
  for (double t : epochs(1.0, 9.0))
    pairer.addFollower(fixAt(t, -0.001));
  pairer.finish();
  EXPECT_GT(pairer.counters().follower_unpaired, 0u);
  bool said = false;
  for (const acc::PairingEvent& event : pairer.takeEvents())
    said = said || event.text.find("the leader's epochs are 0.25 s apart, more than max_interpolation_skew_s: set "
                                   "it to that period") != std::string::npos;
  EXPECT_TRUE(said);
}

TEST(Pairing, LateBurstyOutOfOrderLeaderIsStillPairedInOrder)
{
  acc::EpochPairer pairer;
  auto leader_times = epochs(0.0, 10.0);
  auto follower_times = epochs(0.0, 10.0);
  std::mt19937_64 random(7);
  std::size_t sent = 0;
  // The leader's fixes come 1.2 s late in bursts of 5, shuffled inside each burst (the burst
  // spans 0.4 s of leader time, less than exact_wait_s: every epoch is still paired exactly).
  for (std::size_t i = 0; i < follower_times.size(); ++i)
  {
    pairer.addFollower(fixAt(follower_times[i], -0.001));
    if (i % 5 == 4 && i >= 12)
    {
      std::size_t end = std::min(leader_times.size(), i - 11);
      std::vector<double> burst(leader_times.begin() + sent, leader_times.begin() + end);
      // (The first in order: the pairer learns the leader's epoch period from adjacent epochs.)
      if (sent > 0)
        acc::portableShuffle(burst, random);  // the same order with every standard library
      for (double t : burst)
        pairer.addLeader(fixAt(t));
      sent = end;
    }
  }
  for (std::size_t i = sent; i < leader_times.size(); ++i)  // the last 1.2 s, in order
    pairer.addLeader(fixAt(leader_times[i]));
  auto pairs = pairer.takePairs();
  EXPECT_EQ(pairs.size(), follower_times.size());
  EXPECT_EQ(pairer.counters().follower_unpaired, 0u);
  EXPECT_GT(pairer.counters().leader_out_of_order, 0u);
  EXPECT_EQ(pairer.counters().interpolated_pairs, 0u);
  expectIncreasingAndFresh(pairs, 0.0);
}

TEST(Pairing, ALostLeaderEpochIsInterpolatedOnceTheLeaderIsPastItByTheExactWait)
{
  acc::EpochPairer pairer;
  for (double t : epochs(0.0, 3.0))
  {
    if (std::abs(t - 1.0) > 1e-6)
      pairer.addLeader(fixAt(t));
    pairer.addFollower(fixAt(t, -0.001));
    // Not before the leader is exact_wait_s (0.5 s) past the lost epoch.
    if (t < 1.45)
    {
      for (const auto& pair : pairer.takePairs())
      {
        EXPECT_LT(pair.time_s, 0.95);
      }
    }
  }
  auto pairs = pairer.takePairs();
  auto lost = std::find_if(pairs.begin(), pairs.end(), [](const auto& p) { return std::abs(p.time_s - 1.0) < 1e-6; });
  ASSERT_NE(lost, pairs.end());
  EXPECT_TRUE(lost->interpolated);
  EXPECT_NEAR(lost->epoch_skew_s, 0.1, 1e-9);
  EXPECT_EQ(pairer.counters().interpolated_pairs, 1u);
  EXPECT_EQ(pairer.counters().follower_unpaired, 0u);
}

// A hole in the follower's own fixes longer than dropout_gap_s (0.5 s) breaks the continuity of
// the pairs, though every fix that is there pairs; a shorter one does not.
TEST(Pairing, AFollowerHoleBeyondTheDropoutGapBreaksContinuity)
{
  for (const double hole_s : {0.7, 0.3})
  {
    acc::EpochPairer pairer;
    for (double t : epochs(0.0, 4.0))
    {
      pairer.addLeader(fixAt(t));
      if (!(t > 1.05 && t < 1.05 + hole_s - 0.1))
        pairer.addFollower(fixAt(t, -0.001));
    }
    const auto pairs = pairer.takePairs();
    EXPECT_EQ(pairer.counters().follower_unpaired, 0u);
    const auto resumed = std::find_if(pairs.begin(), pairs.end(), [](const auto& p) { return p.time_s > 1.05; });
    ASSERT_NE(resumed, pairs.end());
    EXPECT_NEAR(resumed->time_s - std::prev(resumed)->time_s, hole_s, 1e-6);
    EXPECT_EQ(resumed->continuity_break, hole_s > 0.5) << hole_s;
    EXPECT_EQ(std::count_if(pairs.begin() + 1, pairs.end(), [](const auto& p) { return p.continuity_break; }),
              hole_s > 0.5 ? 1 : 0);
  }
}

TEST(Pairing, LeaderDropoutGivesNoSamplesACountAndABreak)
{
  acc::EpochPairer pairer;
  for (double t : epochs(0.0, 6.0))
  {
    bool in_dropout = t > 1.05 && t < 1.95;
    if (!in_dropout)
      pairer.addLeader(fixAt(t));
    pairer.addFollower(fixAt(t, -0.001));
  }
  auto pairs = pairer.takePairs();
  EXPECT_EQ(pairer.counters().leader_dropouts, 1u);
  EXPECT_EQ(pairer.counters().follower_unpaired, 9u);  // 1.1 .. 1.9: never bridged
  EXPECT_EQ(pairs.size(), 61u - 9u);
  for (const auto& pair : pairs)
    EXPECT_FALSE(pair.time_s > 1.05 && pair.time_s < 1.95) << pair.time_s;
  auto resumed = std::find_if(pairs.begin(), pairs.end(), [](const auto& p) { return p.time_s > 1.95; });
  ASSERT_NE(resumed, pairs.end());
  EXPECT_TRUE(resumed->continuity_break);
  expectIncreasingAndFresh(pairs, 0.0);
  auto events = pairer.takeEvents();
  EXPECT_TRUE(std::any_of(events.begin(), events.end(),
                          [](const acc::PairingEvent& e) {
                            return !e.per_epoch && e.text.find("leader dropout") != std::string::npos;
                          }));
}

// Receivers at 1 Hz against the default dropout_gap_s 0.5 s: every step is a dropout, each one
// counted; the pairer says once per stream what that means and what to do, and reports the rest
// throttled (per epoch) instead of two warnings a second. An isolated dropout stays one warning.
TEST(Pairing, AStreamWhoseEveryStepIsADropoutIsSaidOnceAndThrottled)
{
  acc::EpochPairer pairer;
  for (double t : epochs(0.0, 10.0, 1.0))
  {
    pairer.addLeader(fixAt(t));
    pairer.addFollower(fixAt(t, -0.001));
  }
  EXPECT_EQ(pairer.counters().leader_dropouts, 10u);
  EXPECT_EQ(pairer.counters().follower_dropouts, 10u);
  const auto events = pairer.takeEvents();
  const auto said = [&](const std::string& part, bool per_epoch) {
    return std::count_if(events.begin(), events.end(), [&](const acc::PairingEvent& e) {
      return e.per_epoch == per_epoch && e.text.find(part) != std::string::npos;
    });
  };
  EXPECT_EQ(said("leader: 3 dropouts in a row, the last 1.00 s: the stream is recorded more coarsely than "
                 "dropout_gap_s (0.50 s), a receiver at 1 Hz? Raise dropout_gap_s above its step",
                 false),
            1);
  EXPECT_EQ(said("follower: 3 dropouts in a row", false), 1);
  EXPECT_EQ(said("leader dropout", false), 2);  // the first two, before the stream is known coarse
  EXPECT_EQ(said("leader dropout", true), 8);

  // With the gap above the step, nothing is a dropout.
  acc::PairingSettings settings;
  settings.dropout_gap_s = 2.5;
  acc::EpochPairer coarse(settings);
  for (double t : epochs(0.0, 10.0, 1.0))
  {
    coarse.addLeader(fixAt(t));
    coarse.addFollower(fixAt(t, -0.001));
  }
  EXPECT_EQ(coarse.counters().leader_dropouts, 0u);
  EXPECT_EQ(coarse.takePairs().size(), 11u);
}

// A follower whose receiver sends neither RMC nor ZDA is timed from midnight, the leader from
// 1970: nothing pairs, and the report said only that the leader was past each epoch.
TEST(Pairing, AStreamWithoutADateIsNamedWhenNothingPairs)
{
  acc::EpochPairer pairer(acc::PairingSettings{});
  const double day_s = 1778544000.0;  // a UTC midnight
  for (double t : epochs(36000.0, 36003.0))
  {
    pairer.addLeader(fixAt(day_s + t, -kDegPerSecond * day_s));  // a latitude on the Earth
    acc::GnssFix undated = fixAt(t, -0.001);
    undated.has_date = false;
    pairer.addFollower(undated);
  }
  EXPECT_TRUE(pairer.takePairs().empty());
  EXPECT_GT(pairer.counters().follower_unpaired, 0u);
  bool named = false;
  for (const acc::PairingEvent& event : pairer.takeEvents())
    named = named || event.text.find("the follower's fixes carry no date (its receiver sends neither RMC nor ZDA)") !=
                         std::string::npos;
  EXPECT_TRUE(named);
}

TEST(Pairing, FollowerWaitsForTheLeaderOnlyUntilTheTimeout)
{
  acc::PairingSettings settings;
  settings.timeout_s = 1.05;
  acc::EpochPairer pairer(settings);
  for (double t : epochs(0.0, 3.0))
    pairer.addFollower(fixAt(t, -0.001));
  EXPECT_TRUE(pairer.takePairs().empty());
  // Epochs 0.0 .. 1.9 are older than 1.05 s on the follower's clock: given up; 2.0 .. 3.0 wait.
  EXPECT_EQ(pairer.counters().follower_unpaired, 20u);
  EXPECT_EQ(pairer.followerEpochsWaiting(), 11u);
  // A leader fix for a given-up epoch is late; one for a waiting epoch pairs it.
  pairer.addLeader(fixAt(0.5));
  pairer.addLeader(fixAt(2.5));
  EXPECT_EQ(pairer.counters().leader_too_late, 1u);
  auto pairs = pairer.takePairs();
  ASSERT_EQ(pairs.size(), 0u);  // 2.0 .. 2.4 still wait in front of 2.5, in order
  pairer.addFollower(fixAt(3.6, -0.001));
  pairs = pairer.takePairs();
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_NEAR(pairs[0].time_s, 2.5, 1e-9);
  EXPECT_TRUE(pairs[0].continuity_break);
}

TEST(Pairing, OutOfOrderFollowerEpochsAreSortedAndLateOnesCounted)
{
  acc::EpochPairer pairer;
  pairer.addFollower(fixAt(0.2, -0.001));
  pairer.addFollower(fixAt(0.1, -0.001));
  pairer.addFollower(fixAt(0.1, -0.001));  // duplicate
  for (double t : epochs(0.0, 0.3))
    pairer.addLeader(fixAt(t));
  auto pairs = pairer.takePairs();
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_NEAR(pairs[0].time_s, 0.1, 1e-9);
  EXPECT_NEAR(pairs[1].time_s, 0.2, 1e-9);
  EXPECT_EQ(pairer.counters().follower_out_of_order, 1u);
  EXPECT_EQ(pairer.counters().follower_duplicates, 1u);
  pairer.addFollower(fixAt(0.15, -0.001));  // older than a pair already output
  EXPECT_EQ(pairer.counters().follower_too_late, 1u);
  EXPECT_TRUE(pairer.takePairs().empty());
}

TEST(Pairing, TimeGoingBackRestartsThePairingAndIsReported)
{
  acc::EpochPairer pairer;
  for (int loop = 0; loop < 2; ++loop)  // a looping bag: the same 20 s twice
    for (double t : epochs(0.0, 20.0))
    {
      pairer.addLeader(fixAt(t));
      pairer.addFollower(fixAt(t, -0.001));
    }
  auto pairs = pairer.takePairs();
  EXPECT_EQ(pairer.counters().leader_time_resets, 1u);
  EXPECT_EQ(pairer.counters().follower_time_resets, 1u);
  ASSERT_EQ(pairs.size(), 2u * 201u);
  std::size_t breaks = 0;
  for (std::size_t i = 0; i < pairs.size(); ++i)
  {
    if (pairs[i].continuity_break)
      ++breaks;
    if (i > 0 && !pairs[i].continuity_break)
    {
      EXPECT_GT(pairs[i].time_s, pairs[i - 1].time_s);
    }
  }
  EXPECT_EQ(breaks, 2u);
  EXPECT_TRUE(pairs[201].continuity_break);
  EXPECT_NEAR(pairs[201].time_s, 0.0, 1e-9);
}

TEST(Pairing, FixesWithoutAPositionAreCountedAndNotUsed)
{
  acc::EpochPairer pairer;
  auto bad = fixAt(0.1);
  bad.fix_quality = 0;
  pairer.addLeader(fixAt(0.0));
  pairer.addLeader(bad);
  pairer.addLeader(fixAt(0.2));
  pairer.addFollower(fixAt(0.1, -0.001));
  EXPECT_EQ(pairer.counters().leader_invalid_fixes, 1u);
  auto pairs = pairer.takePairs();
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_TRUE(pairs[0].interpolated);  // from 0.0 and 0.2, not from the bad fix
  EXPECT_NEAR(pairs[0].epoch_skew_s, 0.1, 1e-9);
}

// A position off the Earth (a fix from another driver, a corrupted link) has no geodesic: it
// would give a NaN gap marked valid. It is counted as a fix without a usable position (found by
// test/fuzz/fuzz_relative_state.cpp).
TEST(Pairing, APositionOffTheEarthIsCountedAndNotUsed)
{
  acc::EpochPairer pairer;
  auto beyond_the_pole = fixAt(0.1);
  beyond_the_pole.latitude_deg = 145.0;
  auto beyond_the_date_line = fixAt(0.2, -0.001);
  beyond_the_date_line.longitude_deg = 188.0;
  pairer.addLeader(fixAt(0.0));
  pairer.addLeader(beyond_the_pole);
  pairer.addLeader(fixAt(0.2));
  pairer.addFollower(fixAt(0.1, -0.001));
  pairer.addFollower(beyond_the_date_line);
  EXPECT_EQ(pairer.counters().leader_invalid_fixes, 1u);
  EXPECT_EQ(pairer.counters().follower_invalid_fixes, 1u);
  const auto pairs = pairer.takePairs();
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_TRUE(pairs[0].interpolated);  // from 0.0 and 0.2, not from the fix beyond the pole

  auto at_the_pole = fixAt(0.3);
  at_the_pole.latitude_deg = -90.0;
  at_the_pole.longitude_deg = 180.0;
  EXPECT_TRUE(acc::hasUsablePosition(at_the_pole));  // the bounds themselves are on the Earth
  at_the_pole.latitude_deg = std::nextafter(-90.0, -91.0);
  EXPECT_FALSE(acc::hasUsablePosition(at_the_pole));
}

TEST(Pairing, InterpolationFollowsTheShorterTurnAndTheDateLine)
{
  auto a = fixAt(0.0), b = fixAt(1.0);
  a.course_rad = 6.2;
  b.course_rad = 0.1;
  a.longitude_deg = 179.9999;
  b.longitude_deg = -179.9999;
  auto mid = acc::interpolateFix(a, b, 0.5);
  EXPECT_NEAR(std::abs(std::remainder(mid.course_rad - (6.2 + (0.1 + 2 * M_PI - 6.2) / 2), 2 * M_PI)), 0.0, 1e-9);
  EXPECT_NEAR(std::abs(mid.longitude_deg), 180.0, 1e-9);
}

// Runs laid end to end (or a 20 s outage of both receivers): the leader fixes before the hole can
// serve no later pair and must be let go, not held as if from another time base until the
// buffer overflows (seen on the ZalaZone session: 1,500 overflows).
TEST(Pairing, LeaderFixesBeforeAHoleInBothStreamsAreLetGo)
{
  acc::PairingSettings settings;
  settings.max_buffered_fixes = 100;  // 10 s at 10 Hz: far less than the 250 s after the hole
  acc::EpochPairer pairer(settings);
  std::vector<double> times = epochs(0.0, 30.0);
  for (double t : epochs(50.0, 300.0))
    times.push_back(t);
  for (double t : times)
  {
    pairer.addLeader(fixAt(t));
    pairer.addFollower(fixAt(t, -0.001));
  }
  const auto pairs = pairer.takePairs();
  EXPECT_EQ(pairer.counters().buffer_overflows, 0u);
  EXPECT_EQ(pairer.counters().leader_time_resets, 0u);
  EXPECT_EQ(pairs.size(), times.size());
  expectIncreasingAndFresh(pairs, 0.0);
}

// Issue 26: the leader's stream starts after the follower's (its first fixes were published
// before relative_state_node subscribed, or its receiver got its first fix later). A follower
// epoch with no leader epoch before it can never be paired once the leader's stream, which
// arrives in order but for reordering within exact_wait_s, is past it: it is given up at once
// and holds back no epoch behind it, however long timeout_s is (as for a radio link that may be
// silent for a long time). Each pair is out at most exact_wait_s after both its fixes are in.
class PairingWithALongTimeout : public testing::TestWithParam<double>
{
protected:
  acc::PairingSettings settings() const
  {
    acc::PairingSettings settings;
    settings.timeout_s = GetParam();
    return settings;
  }
};

namespace
{
/// Feeds the two streams epoch by epoch (the follower's fix, then the leader's at the follower's
/// epoch plus leader_phase_s) and returns the pairs; held_back_s: the longest a pair was held
/// after its epoch's leader fix was in.
std::vector<acc::PairedEpoch> feedTogether(acc::EpochPairer& pairer, const std::vector<double>& follower_times,
                                           double leader_start_s, double leader_phase_s, double& held_back_s)
{
  std::vector<acc::PairedEpoch> pairs;
  held_back_s = 0.0;
  for (double t : follower_times)
  {
    pairer.addFollower(fixAt(t, -0.001));
    if (t + leader_phase_s >= leader_start_s - 1e-9)
      pairer.addLeader(fixAt(t + leader_phase_s));
    for (const auto& pair : pairer.takePairs())
    {
      held_back_s = std::max(held_back_s, t - pair.time_s);
      pairs.push_back(pair);
    }
  }
  return pairs;
}
}  // namespace

TEST_P(PairingWithALongTimeout, EpochsBeforeALateLeaderAreGivenUpAtOnceAndBlockNothing)
{
  acc::EpochPairer pairer(settings());
  const auto times = epochs(0.0, 300.0);  // 3001 epochs: more than max_buffered_fixes
  double held_back_s = 0.0;
  const auto pairs = feedTogether(pairer, times, 1.0, 0.0, held_back_s);
  // 0.0 .. 0.9 have no leader epoch before them; every epoch from 1.0 on is paired exactly.
  EXPECT_EQ(pairer.counters().follower_unpaired, 10u);
  EXPECT_EQ(pairer.counters().buffer_overflows, 0u);
  ASSERT_EQ(pairs.size(), times.size() - 10u);
  EXPECT_NEAR(pairs.front().time_s, 1.0, 1e-9);
  EXPECT_EQ(pairer.counters().exact_pairs, pairs.size());
  EXPECT_LE(held_back_s, pairer.settings().exact_wait_s + 1e-6);
  expectIncreasingAndFresh(pairs, 0.0);
}

TEST_P(PairingWithALongTimeout, TheLeadersFirstFiftyFixesLostWithAPhaseOffset)
{
  acc::EpochPairer pairer(settings());
  const auto times = epochs(0.0, 300.0);
  double held_back_s = 0.0;
  // The leader's epochs are 0.03 s after the follower's; the first 50 (0.03 .. 4.93 s) are lost.
  const auto pairs = feedTogether(pairer, times, 5.0, 0.03, held_back_s);
  // 0.0 .. 5.0 have no leader epoch before them (5.03 is the first); 5.1 on are interpolated.
  EXPECT_EQ(pairer.counters().follower_unpaired, 51u);
  EXPECT_EQ(pairer.counters().buffer_overflows, 0u);
  ASSERT_EQ(pairs.size(), times.size() - 51u);
  EXPECT_NEAR(pairs.front().time_s, 5.1, 1e-9);
  EXPECT_EQ(pairer.counters().interpolated_pairs, pairs.size());
  EXPECT_LE(held_back_s, pairer.settings().exact_wait_s + 1e-6);
  expectIncreasingAndFresh(pairs, 0.03 + 1e-9);
}

// A dropout of the leader: the follower epochs inside it are given up once the leader's stream is
// past them, not after timeout_s.
TEST_P(PairingWithALongTimeout, ALeaderDropoutBlocksNothing)
{
  acc::EpochPairer pairer(settings());
  std::vector<acc::PairedEpoch> pairs;
  double held_back_s = 0.0;
  for (double t : epochs(0.0, 60.0))
  {
    pairer.addFollower(fixAt(t, -0.001));
    if (!(t > 10.05 && t < 12.95))
      pairer.addLeader(fixAt(t));
    for (const auto& pair : pairer.takePairs())
    {
      held_back_s = std::max(held_back_s, t - pair.time_s);
      pairs.push_back(pair);
    }
  }
  EXPECT_EQ(pairer.counters().follower_unpaired, 29u);  // 10.1 .. 12.9: never bridged
  EXPECT_EQ(pairs.size(), 601u - 29u);
  EXPECT_LE(held_back_s, pairer.settings().exact_wait_s + 1e-6);
  expectIncreasingAndFresh(pairs, 0.0);
}

INSTANTIATE_TEST_SUITE_P(Pairing, PairingWithALongTimeout, testing::Values(1e6, 1e3));

// Giving up on an epoch the leader is past respects the reorder the pairer allows: a leader fix
// that comes out of order by less than exact_wait_s still pairs its epoch exactly.
TEST(Pairing, ALeaderFixOutOfOrderWithinTheExactWaitStillPairsAfterALateStart)
{
  acc::EpochPairer pairer;
  for (double t : epochs(0.0, 3.0))
  {
    pairer.addFollower(fixAt(t, -0.001));
    if (t > 0.95)
      pairer.addLeader(fixAt(t));
    if (std::abs(t - 1.3) < 1e-6)
      pairer.addLeader(fixAt(0.9));  // 0.4 s behind the leader's newest
  }
  auto pairs = pairer.takePairs();
  ASSERT_FALSE(pairs.empty());
  EXPECT_NEAR(pairs.front().time_s, 0.9, 1e-9);
  EXPECT_FALSE(pairs.front().interpolated);
  EXPECT_EQ(pairer.counters().follower_unpaired, 9u);  // 0.0 .. 0.8
  EXPECT_EQ(pairer.counters().leader_too_late, 0u);
  EXPECT_EQ(pairs.size(), 31u - 9u);
}

// A looping replay whose follower comes round first: the leader is still on the old time base,
// far ahead. That is no leader past the follower's new epochs: they wait for the leader's loop.
TEST(Pairing, AFollowerThatLoopsFirstWaitsForTheLeadersLoop)
{
  acc::EpochPairer pairer;
  for (double t : epochs(0.0, 20.0))
  {
    pairer.addLeader(fixAt(t));
    pairer.addFollower(fixAt(t, -0.001));
  }
  const auto loop = epochs(0.0, 20.0);
  for (std::size_t i = 0; i < loop.size(); ++i)
  {
    pairer.addFollower(fixAt(loop[i], -0.001));
    if (i >= 5)  // the leader's loop 0.5 s behind
      pairer.addLeader(fixAt(loop[i - 5]));
  }
  for (std::size_t i = loop.size() - 5; i < loop.size(); ++i)
    pairer.addLeader(fixAt(loop[i]));
  EXPECT_EQ(pairer.counters().follower_time_resets, 1u);
  EXPECT_EQ(pairer.counters().leader_time_resets, 1u);
  EXPECT_EQ(pairer.counters().follower_unpaired, 0u);
  EXPECT_EQ(pairer.takePairs().size(), 2u * 201u);
}

// A follower receiver whose time jumps back once and returns: one stray time stamp, counted and not
// used; nothing is reset or cleared (it was taken for a reset: the epochs waiting then were lost).
TEST(Pairing, AFollowerTimeGlitchIsAStrayStampThatClearsNothing)
{
  acc::PairingSettings settings;
  settings.timeout_s = 1e6;
  acc::EpochPairer pairer(settings);
  for (double t : epochs(0.0, 40.0))
  {
    pairer.addLeader(fixAt(t));
    pairer.addFollower(fixAt(std::abs(t - 20.0) < 1e-6 ? 10.0 : t, -0.001));
  }
  EXPECT_EQ(pairer.counters().follower_time_resets, 0u);
  EXPECT_EQ(pairer.counters().follower_stray_stamps, 1u);  // the epoch stamped 10.0
  EXPECT_EQ(pairer.counters().follower_unpaired, 0u);
  EXPECT_EQ(pairer.counters().buffer_overflows, 0u);
  EXPECT_EQ(pairer.takePairs().size(), 401u - 1u);
  bool said = false;
  for (const acc::PairingEvent& event : pairer.takeEvents())
    said = said || event.text.find("stray time stamps, not used (no reset)") != std::string::npos;
  EXPECT_TRUE(said);
}

// "More than time_reset_s" back is a clock of its own; exactly time_reset_s back is a late fix of
// this clock (counted too late), not a stray stamp. Steps of 0.125 s keep every stamp exact.
TEST(Pairing, AStampExactlyTimeResetBackIsLateAndOneStepFurtherIsStray)
{
  for (const double back_s : {5.0, 5.125})
  {
    acc::PairingSettings settings;
    ASSERT_EQ(settings.time_reset_s, 5.0);
    acc::EpochPairer pairer(settings);
    for (double t : epochs(0.0, 30.0, 0.125))
    {
      pairer.addLeader(fixAt(t));
      pairer.addFollower(fixAt(t, -0.001));
      if (t == 20.0)
        pairer.addFollower(fixAt(t - back_s, -0.001));
    }
    pairer.finish();
    const acc::PairingCounters& c = pairer.counters();
    const bool beyond = back_s > settings.time_reset_s;
    EXPECT_EQ(c.follower_stray_stamps, beyond ? 1u : 0u) << back_s;
    EXPECT_EQ(c.follower_too_late, beyond ? 0u : 1u) << back_s;
    EXPECT_EQ(c.follower_time_resets, 0u) << back_s;
    EXPECT_EQ(c.exact_pairs, 241u) << back_s;
  }
}
// A few fixes on another clock are stray until time_reset_confirm_fixes in a row confirm a reset;
// the fixes that confirm it are paired, not lost. Live, arrival order is real time and the follower
// epochs waiting for the leader's data were cleared by the stray stamp taken for a reset.
TEST(Pairing, AResetIsTakenOnceConfirmedAndItsFixesArePaired)
{
  for (const std::size_t strays : {1u, 4u, 5u})
  {
    acc::PairingSettings settings;
    acc::EpochPairer pairer(settings);
    const auto drive = epochs(0.0, 30.0);
    std::size_t fed = 0;
    for (std::size_t i = 0; i < drive.size(); ++i)
    {
      const bool stray = i >= 200 && i < 200 + strays;
      pairer.addLeader(fixAt(drive[i]));
      pairer.addFollower(fixAt(stray ? drive[i] - 100.0 : drive[i], -0.001));
      ++fed;
    }
    pairer.finish();
    const acc::PairingCounters& c = pairer.counters();
    const bool reset = strays >= settings.time_reset_confirm_fixes;
    EXPECT_EQ(c.follower_time_resets, reset ? 1u : 0u) << strays;
    EXPECT_EQ(c.follower_stray_stamps, reset ? 0u : strays) << strays;
    EXPECT_EQ(c.exact_pairs + c.interpolated_pairs, fed - strays) << strays;
    // A confirmed reset to a clock 100 s back meets no leader fix there: those epochs are unpaired.
    EXPECT_EQ(c.follower_unpaired, reset ? strays : 0u) << strays;
  }
}

// A follower receiver whose clock jumps back 20 s and stays there while the leader's runs on: its
// new labels would match leader fixes of 20 s before, and a pair of them is a gap hundreds of
// metres off that every check after the break would take. None is made; each epoch is counted
// unpaired, with the reason. Fails when the follower's epochs pair with the leader's buffered ones
// (every one did once its labels caught up with the leader's).
TEST(Pairing, AFollowerClockThatJumpsBackAloneIsPairedWithNothingFromTheOtherClock)
{
  acc::EpochPairer pairer;
  std::size_t before = 0;
  for (double t : epochs(0.0, 60.0))  // arrival order is real time: the leader runs on
  {
    pairer.addLeader(fixAt(t));
    pairer.addFollower(fixAt(t < 30.0 ? t : t - 20.0, -0.001));
    if (t < 30.0)
      before = pairer.counters().exact_pairs + pairer.counters().interpolated_pairs;
  }
  pairer.finish();
  EXPECT_EQ(pairer.counters().follower_time_resets, 1u);
  EXPECT_EQ(pairer.counters().leader_time_resets, 0u);
  EXPECT_EQ(pairer.counters().exact_pairs + pairer.counters().interpolated_pairs, before);
  EXPECT_EQ(pairer.counters().follower_unpaired, 601u - before);
  bool said = false;
  for (const acc::PairingEvent& event : pairer.takeEvents())
    said = said || event.text.find("the two clocks now disagree") != std::string::npos;
  EXPECT_TRUE(said);
}

// A looping replay whose leader comes round 10 s before the follower: when the follower loops, the
// leader is already on the new clock, ahead of it. Its epochs pair with the leader's buffered ones,
// as they should: the leader is not awaited to reset again.
TEST(Pairing, AFollowerThatLoopsAfterTheLeaderPairsOnTheLeadersNewClock)
{
  acc::PairingSettings settings;
  settings.max_buffered_fixes = 5000;
  acc::EpochPairer pairer(settings);
  const auto drive = epochs(0.0, 60.0);
  for (std::size_t i = 0; i < 2 * drive.size(); ++i)
  {
    pairer.addLeader(fixAt(drive[(i + 100) % drive.size()]));  // loops 100 epochs (10 s) earlier
    pairer.addFollower(fixAt(drive[i % drive.size()], -0.001));
  }
  pairer.finish();
  EXPECT_EQ(pairer.counters().follower_time_resets, 1u);
  EXPECT_EQ(pairer.counters().leader_time_resets, 2u);  // its second loop's end comes round too
  // Each loop pairs up to 50 s, where the leader's next reset clears what the follower's last
  // 10 s needed: the first from 10 s (the leader's first fix), 401 epochs; the second from 0 s,
  // 501. Awaiting the leader's reset at the follower's loop would leave the second unpaired (401).
  // The leader's reset is taken time_reset_confirm_fixes of its fixes in: the follower's epochs
  // pair for that many less one longer each loop.
  EXPECT_EQ(pairer.counters().exact_pairs, 401u + 501u + 2u * (settings.time_reset_confirm_fixes - 1u));
}

// The ROS node sizes its publisher's queue by mostPairsAtOnce(): no call may complete more, even
// when a reorder window as long as the timeout lets an early epoch hold back the buffer behind it.
TEST(Pairing, NoCallCompletesMorePairsThanMostPairsAtOnce)
{
  acc::PairingSettings settings;
  settings.timeout_s = 1e6;
  settings.exact_wait_s = 1e6;
  settings.max_buffered_fixes = 50;
  acc::EpochPairer pairer(settings);
  std::size_t largest = 0, total = 0;
  for (double t : epochs(0.0, 30.0))
  {
    pairer.addFollower(fixAt(t, -0.001));
    if (t > 0.05)  // the leader's first epoch never comes: 0.0 waits for it until the buffer overflows
      pairer.addLeader(fixAt(t));
    std::size_t completed = pairer.takePairs().size();
    largest = std::max(largest, completed);
    total += completed;
  }
  EXPECT_GT(pairer.counters().buffer_overflows, 0u);
  EXPECT_GT(largest, 1u);
  EXPECT_LE(largest, pairer.mostPairsAtOnce());
  EXPECT_EQ(total + pairer.counters().follower_unpaired, 301u);
}

// Two logs read in batch end with follower epochs still waiting for leader data that could have
// come live: finish() pairs what it can (an epoch the leader's own epoch was awaited for is
// interpolated) and counts the rest unpaired, so that every follower epoch is paired or counted.
TEST(Pairing, FinishPairsOrCountsEveryEpochStillWaitingAtTheEndOfTheStreams)
{
  acc::EpochPairer pairer;
  std::size_t paired = 0;
  for (double t : epochs(0.0, 6.0))
  {
    pairer.addFollower(fixAt(t, -0.001));
    if (t <= 5.0 + 1e-9 && std::abs(t - 4.9) > 1e-6)  // the leader's log ends at 5.0 and lacks 4.9
      pairer.addLeader(fixAt(t));
    paired += pairer.takePairs().size();
  }
  EXPECT_EQ(paired, 49u);  // 0.0-4.8: 4.9 awaits the leader's own epoch, 5.0 waits behind it
  pairer.finish();
  const std::vector<acc::PairedEpoch> last = pairer.takePairs();
  ASSERT_EQ(last.size(), 2u);
  EXPECT_TRUE(last[0].interpolated);
  EXPECT_NEAR(last[0].time_s, 4.9, 1e-9);
  EXPECT_FALSE(last[1].interpolated);
  EXPECT_EQ(pairer.counters().follower_unpaired, 10u);  // 5.1-6.0: no leader data after 5.0
  EXPECT_EQ(paired + last.size() + pairer.counters().follower_unpaired, 61u);
  bool said = false;
  for (const acc::PairingEvent& event : pairer.takeEvents())
    said = said || event.text.find("the streams ended") != std::string::npos;
  EXPECT_TRUE(said);
}
