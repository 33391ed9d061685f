// The one rule that tells a receiver's clock reset from stray time stamps (ClockResetRule), which
// the live pairing and nmea_to_csv's split into stretches both follow.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "acc_identification/relative_state/clock_reset_rule.h"

namespace
{
constexpr double kResetS = 5.0;
constexpr double kNaN = std::nan("");
using Rule = acc::ClockResetRule<std::size_t>;  // holds each fix's index
using Indices = std::vector<std::size_t>;

/// Steps of the rule over these times, each fix held by its index, the stream's newest time as the
/// pairing keeps it (the newest on-clock fix; a confirmed clock's newest time).
std::vector<Rule::Step> stepsOver(const std::vector<double>& times_s, std::size_t confirm)
{
  Rule rule(kResetS, confirm);
  std::vector<Rule::Step> steps;
  double newest = kNaN;
  for (std::size_t i = 0; i < times_s.size(); ++i)
  {
    const double t = times_s[i];
    steps.push_back(rule.next(i, t, newest));
    if (!steps.back().held)
      newest = steps.back().new_clock || !std::isfinite(newest) ? t : std::max(newest, t);
  }
  return steps;
}

/// The fixes [first, end) are held, nothing let go.
void expectHeld(const std::vector<Rule::Step>& steps, std::size_t first, std::size_t end)
{
  for (std::size_t k = first; k < end; ++k)
  {
    EXPECT_TRUE(steps[k].held) << k;
    EXPECT_TRUE(steps[k].released.empty()) << k;
  }
}
}  // namespace

TEST(ClockResetRule, FixesOnTheClockAreNeitherHeldNorStray)
{
  for (const Rule::Step& step : stepsOver({100.0, 100.1, 99.0, 100.2, 96.0}, 5))
  {
    EXPECT_FALSE(step.held);
    EXPECT_FALSE(step.new_clock);
    EXPECT_TRUE(step.stray.empty());
    EXPECT_TRUE(step.released.empty());
  }
}

TEST(ClockResetRule, ConfirmFixesInARowOnANewClockAreAReset)
{
  const auto steps = stepsOver({100.0, 100.1, 10.0, 10.1, 10.2, 10.3, 10.4, 10.5}, 5);
  expectHeld(steps, 2, 6);
  EXPECT_TRUE(steps[6].new_clock);
  EXPECT_EQ(steps[6].released, (Indices{2, 3, 4, 5, 6}));  // in order, this one the last
  EXPECT_FALSE(steps[6].held);
  EXPECT_FALSE(steps[7].held);  // on the new clock now
  EXPECT_FALSE(steps[7].new_clock);
  // One fix is enough when the setting says so.
  EXPECT_TRUE(stepsOver({100.0, 10.0}, 1)[1].new_clock);
}

TEST(ClockResetRule, FewerThenBackOnTheClockAreStrayStamps)
{
  const auto steps = stepsOver({100.0, 100.1, 10.0, 10.1, 10.2, 100.2}, 5);
  EXPECT_TRUE(steps[4].held);
  EXPECT_EQ(steps[5].stray, (Indices{2, 3, 4}));
  EXPECT_FALSE(steps[5].held);
  EXPECT_FALSE(steps[5].new_clock);
}

TEST(ClockResetRule, AJumpedFixThatDoesNotContinueTheHeldOnesStartsAnotherHold)
{
  // 10 s, then 50 s: both far behind 100 s, on no one clock.
  const auto steps = stepsOver({100.0, 10.0, 10.1, 50.0}, 5);
  EXPECT_EQ(steps[3].stray, (Indices{1, 2}));
  EXPECT_TRUE(steps[3].held);
  // Held times that drift back step by step (96 within 5 s of 100, 92 not): the held fixes would
  // make two resets among themselves, so the older are stray.
  const auto drifting = stepsOver({200.0, 100.0, 96.0, 92.0}, 5);
  EXPECT_TRUE(drifting[2].stray.empty());
  EXPECT_EQ(drifting[3].stray, (Indices{1, 2}));
  EXPECT_TRUE(drifting[3].held);
}

TEST(ClockResetRule, WhatIsHeldAtTheStreamsEndIsStray)
{
  Rule rule(kResetS, 5);
  rule.next(0, 100.0, kNaN);
  EXPECT_TRUE(rule.next(1, 10.0, 100.0).held);
  EXPECT_TRUE(rule.next(2, 10.1, 100.0).held);
  EXPECT_EQ(rule.held(), 2u);
  EXPECT_EQ(rule.endOfStream(), (Indices{1, 2}));
  EXPECT_EQ(rule.held(), 0u);
  EXPECT_TRUE(rule.endOfStream().empty());
}

TEST(ClockResetRule, AStampFarAheadIsHeldTooAndStrayWhenTheStreamGoesOn)
{
  // One fix an hour ahead, then the stream on its clock: a stray stamp, not a clock to fall back from.
  const auto glitch = stepsOver({100.0, 100.1, 3700.2, 100.3, 100.4}, 5);
  EXPECT_TRUE(glitch[2].held);
  EXPECT_EQ(glitch[3].stray, (Indices{2}));
  EXPECT_FALSE(glitch[3].held);
  EXPECT_TRUE(glitch[4].released.empty());
  // A dropout longer than time_reset_s: the fixes after it are the stream's own, let go once
  // confirmed, and no reset.
  const auto dropout = stepsOver({100.0, 100.1, 110.0, 110.1, 110.2, 110.3, 110.4, 110.5}, 5);
  expectHeld(dropout, 2, 6);
  EXPECT_EQ(dropout[6].released, (Indices{2, 3, 4, 5, 6}));
  EXPECT_FALSE(dropout[6].new_clock);
  EXPECT_FALSE(dropout[7].held);
}
