#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "acc_identification/calibration/sliding_window.h"


namespace
{
acc::WindowSample sampleAt(double t, bool valid = true)
{
  return acc::WindowSample{t, 20.0 + t, 10.0, 10.5, valid};
}

TEST(SlidingWindow, KeepsOnlyTheLastWindowLength)
{
  acc::SlidingWindow window(10.0, 0.5, 5);
  for (int k = 0; k <= 300; ++k)
  {
    EXPECT_EQ(window.add(sampleAt(0.1 * k)), acc::SlidingWindow::AddResult::kAdded);
  }
  EXPECT_NEAR(window.endTimeS(), 30.0, 1e-9);
  EXPECT_GE(window.startTimeS(), 20.0 - 1e-9);
  EXPECT_LE(window.startTimeS(), 20.1);
  const auto segments = window.segments();
  ASSERT_EQ(segments.size(), 1u);
  EXPECT_EQ(segments[0].size(), window.size());
  EXPECT_EQ(acc::describeRunProblem(segments[0]), "");
}

TEST(SlidingWindow, GapsAndInvalidSamplesSplitIntoSegments)
{
  acc::SlidingWindow window(100.0, 0.5, 5);
  for (int k = 0; k < 20; ++k) window.add(sampleAt(0.1 * k));          // 0.0 - 1.9
  for (int k = 30; k < 50; ++k) window.add(sampleAt(0.1 * k));         // gap of 1.1 s, 3.0 - 4.9
  EXPECT_EQ(window.add(sampleAt(5.0, false)), acc::SlidingWindow::AddResult::kInvalid);
  for (int k = 51; k < 60; ++k) window.add(sampleAt(0.1 * k));         // 5.1 - 5.9
  acc::WindowSample nan_sample = sampleAt(6.0);
  nan_sample.space_gap_m = std::numeric_limits<double>::quiet_NaN();
  EXPECT_EQ(window.add(nan_sample), acc::SlidingWindow::AddResult::kNonFinite);
  for (int k = 61; k < 64; ++k) window.add(sampleAt(0.1 * k));         // 3 samples: too short
  std::size_t short_pieces = 0;
  const auto segments = window.segments(&short_pieces);
  ASSERT_EQ(segments.size(), 3u);
  EXPECT_EQ(segments[0].size(), 20u);
  EXPECT_EQ(segments[1].size(), 20u);
  EXPECT_NEAR(segments[1].time_s.front(), 3.0, 1e-9);
  EXPECT_EQ(segments[2].size(), 9u);
  EXPECT_EQ(short_pieces, 1u);
  EXPECT_EQ(window.describeShortPieces(0), "");
  EXPECT_EQ(window.describeShortPieces(short_pieces),
            "1 piece of fewer than 5 samples between holes longer than 0.5 s or invalid samples not simulated");
}

// A 1 Hz receiver against max_gap_s 0.5: every step is a hole and nothing is simulated; the note
// says why and what to set, where the identification alone would only say "too little data".
TEST(SlidingWindow, AStreamSlowerThanMaxGapIsSaidToBeOne)
{
  acc::SlidingWindow window(100.0, 0.5, 5);
  for (int k = 0; k < 60; ++k)
    window.add(sampleAt(1.0 * k));
  std::size_t short_pieces = 0;
  EXPECT_TRUE(window.segments(&short_pieces).empty());
  EXPECT_EQ(short_pieces, 60u);
  EXPECT_EQ(window.describeShortPieces(short_pieces),
            "60 pieces of fewer than 5 samples between holes longer than 0.5 s or invalid samples not simulated: the "
            "samples' median step, 1 s, is itself such a hole (a receiver at 1 Hz); max_gap_s must exceed the step");
}

TEST(SlidingWindow, RejectsOutOfOrderAndRestartsWhenConsistentSamplesConfirmATimeReset)
{
  acc::SlidingWindow window(100.0, 0.5, 2);  // confirm a jump with 5 samples (default)
  for (int k = 0; k < 100; ++k) window.add(sampleAt(0.1 * k));
  EXPECT_EQ(window.add(sampleAt(9.9)), acc::SlidingWindow::AddResult::kOutOfOrder);
  EXPECT_EQ(window.add(sampleAt(9.8)), acc::SlidingWindow::AddResult::kOutOfOrder);
  EXPECT_EQ(window.size(), 100u);
  // A replay restarted at 1.0 s: held until five consistent samples, then the window restarts.
  for (int k = 0; k < 4; ++k)
  {
    EXPECT_EQ(window.add(sampleAt(1.0 + 0.1 * k)), acc::SlidingWindow::AddResult::kHeld);
    EXPECT_EQ(window.size(), 100u);
  }
  EXPECT_EQ(window.add(sampleAt(1.4)), acc::SlidingWindow::AddResult::kRestarted);
  EXPECT_EQ(window.size(), 5u);
  EXPECT_NEAR(window.startTimeS(), 1.0, 1e-12);
  EXPECT_EQ(window.droppedOutliers(), 0u);
  EXPECT_FALSE(acc::SlidingWindow::describe(acc::SlidingWindow::AddResult::kRestarted).empty());
}

/// Issue "one model core": one stamp 0.5 s in the past, or one in the future, emptied the window.
TEST(SlidingWindow, OneStampInThePastOrFutureNeverEmptiesTheWindow)
{
  acc::SlidingWindow window(120.0, 0.5, 2);
  for (int k = 0; k < 600; ++k) window.add(sampleAt(0.1 * k));  // 0-59.9 s
  // 0.6 s in the past (beyond max_gap_s), then the stream goes on.
  EXPECT_EQ(window.add(sampleAt(59.3)), acc::SlidingWindow::AddResult::kHeld);
  EXPECT_EQ(window.add(sampleAt(60.0)), acc::SlidingWindow::AddResult::kAdded);
  EXPECT_EQ(window.size(), 601u);
  EXPECT_EQ(window.droppedOutliers(), 1u);
  // A stamp a day in the future, then the stream goes on: nothing leaves the window.
  EXPECT_EQ(window.add(sampleAt(60.0 + 86400.0)), acc::SlidingWindow::AddResult::kHeld);
  EXPECT_EQ(window.add(sampleAt(60.1)), acc::SlidingWindow::AddResult::kAdded);
  EXPECT_EQ(window.size(), 602u);
  EXPECT_NEAR(window.startTimeS(), 0.0, 1e-12);
  EXPECT_EQ(window.droppedOutliers(), 2u);
}

TEST(SlidingWindow, AConfirmedJumpAheadMovesTheWindowOn)
{
  acc::SlidingWindow window(120.0, 0.5, 2);
  for (int k = 0; k < 600; ++k) window.add(sampleAt(0.1 * k));  // 0-59.9 s
  // The data resume 200 s later (a long outage): held, then confirmed by consistent samples.
  for (int k = 0; k < 4; ++k)
    EXPECT_EQ(window.add(sampleAt(260.0 + 0.1 * k)), acc::SlidingWindow::AddResult::kHeld);
  EXPECT_EQ(window.add(sampleAt(260.4)), acc::SlidingWindow::AddResult::kJumpedAhead);
  EXPECT_EQ(window.size(), 5u);  // the old samples are more than 120 s older: they left
  EXPECT_NEAR(window.startTimeS(), 260.0, 1e-12);
  // A jump within max_forward_jump_s (30 s) is a hole, not held: the window splits there.
  EXPECT_EQ(window.add(sampleAt(270.0)), acc::SlidingWindow::AddResult::kAdded);
}

/// Every sample the window does not take, and every jump it confirms, is counted by kind.
TEST(SlidingWindow, CountsEveryDroppedSampleAndEveryReset)
{
  acc::SlidingWindow window(120.0, 0.5, 2, 30.0, 3);
  EXPECT_EQ(window.confirmSamples(), 3u);
  for (int k = 0; k < 100; ++k) window.add(sampleAt(0.1 * k));  // 0-9.9 s
  EXPECT_EQ(window.add(sampleAt(9.9)), acc::SlidingWindow::AddResult::kOutOfOrder);      // duplicate
  EXPECT_EQ(window.add(sampleAt(9.6)), acc::SlidingWindow::AddResult::kOutOfOrder);      // late
  EXPECT_EQ(window.add(sampleAt(std::nan(""))), acc::SlidingWindow::AddResult::kNonFinite);
  EXPECT_EQ(window.add(sampleAt(5.0)), acc::SlidingWindow::AddResult::kHeld);           // 4.9 s back
  EXPECT_EQ(window.add(sampleAt(1e6)), acc::SlidingWindow::AddResult::kHeld);           // far ahead
  EXPECT_EQ(window.heldSamples(), 1u);  // the first was contradicted by the second: dropped
  EXPECT_EQ(window.add(sampleAt(10.0)), acc::SlidingWindow::AddResult::kAdded);         // old base goes on
  EXPECT_EQ(window.heldSamples(), 0u);
  EXPECT_EQ(window.size(), 101u);
  acc::SlidingWindow::Counts c = window.counts();
  EXPECT_EQ(c.out_of_order, 2u);
  EXPECT_EQ(c.non_finite_times, 1u);
  EXPECT_EQ(c.time_outliers, 2u);
  EXPECT_EQ(c.restarts, 0u);
  EXPECT_EQ(c.jumps_ahead, 0u);
  // A sustained jump ahead (data resume after 100 s), then a sustained jump back (bag loop).
  for (int k = 0; k < 3; ++k) window.add(sampleAt(110.0 + 0.1 * k));
  for (int k = 0; k < 3; ++k) window.add(sampleAt(1.0 + 0.1 * k));
  c = window.counts();
  EXPECT_EQ(c.jumps_ahead, 1u);
  EXPECT_EQ(c.restarts, 1u);
  EXPECT_EQ(c.time_outliers, 2u);  // unchanged: confirmed jumps drop nothing
  EXPECT_EQ(window.size(), 3u);
  EXPECT_NEAR(window.startTimeS(), 1.0, 1e-12);
}

/// A sample its caller counted already (the ACC was off, a value implausible) is placed, held or
/// rejected as any other, and never counted again: every sample is counted once.
TEST(SlidingWindow, ASampleTheCallerCountedIsNotCountedAgain)
{
  auto counted = [](double t) {
    acc::WindowSample s = sampleAt(t, false);
    s.counted = true;
    return s;
  };
  acc::SlidingWindow window(120.0, 0.5, 2, 30.0, 3);
  for (int k = 0; k < 100; ++k) window.add(sampleAt(0.1 * k));  // 0-9.9 s
  EXPECT_EQ(window.add(counted(9.9)), acc::SlidingWindow::AddResult::kOutOfOrder);
  EXPECT_EQ(window.add(counted(std::nan(""))), acc::SlidingWindow::AddResult::kNonFinite);
  EXPECT_EQ(window.add(counted(1e6)), acc::SlidingWindow::AddResult::kHeld);
  EXPECT_EQ(window.add(sampleAt(5.0)), acc::SlidingWindow::AddResult::kHeld);  // drops the counted one
  EXPECT_EQ(window.add(sampleAt(10.0)), acc::SlidingWindow::AddResult::kAdded);  // drops the uncounted one
  acc::SlidingWindow::Counts c = window.counts();
  EXPECT_EQ(c.out_of_order, 0u);
  EXPECT_EQ(c.non_finite_times, 0u);
  EXPECT_EQ(c.time_outliers, 1u);
  // A counted sample in order is a split point, as an invalid one.
  EXPECT_EQ(window.add(counted(10.1)), acc::SlidingWindow::AddResult::kInvalid);
  for (int k = 2; k < 10; ++k) window.add(sampleAt(10.0 + 0.1 * k));
  EXPECT_EQ(window.segments().size(), 2u);
}

/// How many consistent samples confirm a jump is a setting (identifier_node: ~jump_confirm_samples).
TEST(SlidingWindow, TheConfirmationCountIsASetting)
{
  for (std::size_t confirm : {2u, 5u, 8u})
  {
    acc::SlidingWindow window(120.0, 0.5, 2, 30.0, confirm);
    for (int k = 0; k < 100; ++k) window.add(sampleAt(100.0 + 0.1 * k));
    for (std::size_t k = 0; k + 1 < confirm; ++k)
    {
      EXPECT_EQ(window.add(sampleAt(1.0 + 0.1 * static_cast<double>(k))), acc::SlidingWindow::AddResult::kHeld)
          << confirm;
      EXPECT_EQ(window.size(), 100u) << confirm;
    }
    EXPECT_EQ(window.add(sampleAt(1.0 + 0.1 * static_cast<double>(confirm - 1))),
              acc::SlidingWindow::AddResult::kRestarted)
        << confirm;
    EXPECT_EQ(window.size(), confirm);
  }
}

/// A stamp in the future just before a real time reset: the outlier is dropped, the reset happens.
TEST(SlidingWindow, AnOutlierBeforeARealTimeResetIsDroppedAndTheResetStillHappens)
{
  acc::SlidingWindow window(120.0, 0.5, 2);  // 5 samples confirm
  for (int k = 0; k < 100; ++k) window.add(sampleAt(500.0 + 0.1 * k));
  EXPECT_EQ(window.add(sampleAt(5000.0)), acc::SlidingWindow::AddResult::kHeld);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(window.add(sampleAt(0.1 * k)), acc::SlidingWindow::AddResult::kHeld);
  EXPECT_EQ(window.add(sampleAt(0.4)), acc::SlidingWindow::AddResult::kRestarted);
  EXPECT_EQ(window.counts().time_outliers, 1u);
  EXPECT_EQ(window.counts().restarts, 1u);
  EXPECT_EQ(window.size(), 5u);
  EXPECT_NEAR(window.startTimeS(), 0.0, 1e-12);
  // Held samples go with clear(): a later sample cannot confirm a jump from before it.
  EXPECT_EQ(window.add(sampleAt(9000.0)), acc::SlidingWindow::AddResult::kHeld);
  window.clear();
  EXPECT_EQ(window.heldSamples(), 0u);
  EXPECT_EQ(window.add(sampleAt(3.0)), acc::SlidingWindow::AddResult::kAdded);
}
}  // namespace
