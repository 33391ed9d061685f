// identifier_node's health: what its diagnostics say from its counters, and the catch-all that
// keeps its worker thread alive whatever a solve throws. The node itself, with an injected
// throwing solve, is test/rostest/identifier_faults.test.
#include <gtest/gtest.h>

#include <new>
#include <stdexcept>
#include <string>

#include <diagnostic_msgs/DiagnosticStatus.h>

#include "acc_identification/ros/identifier_ros.h"

namespace
{
using diagnostic_msgs::DiagnosticStatus;

acc::IdentifierCounters running()
{
  acc::IdentifierCounters c;
  c.received = 1000;
  c.solves = 10;
  c.published = 10;
  return c;
}

/// One bad sample makes one report WARN, not every report after it (the WARN used to latch).
TEST(IdentifierHealth, OneBadSampleWarnsInTheNextReportOnly)
{
  const acc::IdentifierCounters before = running();
  EXPECT_EQ(acc::identifierHealth(before, before, "").level, DiagnosticStatus::OK);
  acc::IdentifierCounters after = before;
  after.received += 1;
  after.out_of_order = 1;
  const acc::IdentifierHealth warn = acc::identifierHealth(after, before, "");
  EXPECT_EQ(warn.level, DiagnosticStatus::WARN);
  EXPECT_NE(warn.message.find("1 out-of-order"), std::string::npos) << warn.message;
  // The next report, nothing new: OK again, though the total is still 1.
  EXPECT_EQ(acc::identifierHealth(after, after, "").level, DiagnosticStatus::OK);
}

/// An input that stopped is said, once it has been silent for stale_after_s of wall time.
TEST(IdentifierHealth, AnInputThatStoppedWarns)
{
  const acc::IdentifierCounters now = running();
  EXPECT_EQ(acc::identifierHealth(now, now, "", 4.0, 5.0).level, DiagnosticStatus::OK);
  const acc::IdentifierHealth silent = acc::identifierHealth(now, now, "", 6.0, 5.0);
  EXPECT_EQ(silent.level, DiagnosticStatus::WARN);
  EXPECT_NE(silent.message.find("no relative_state for 6 s"), std::string::npos) << silent.message;
  // Before the first sample the older WARN says so instead.
  EXPECT_EQ(acc::identifierHealth(acc::IdentifierCounters{}, acc::IdentifierCounters{}, "", 60.0, 5.0).message,
            "no relative_state yet");
}

/// Samples that arrive while ROS time stands still (/use_sim_time left true by a replay, no
/// /clock): no period runs, and the node published nothing under an OK "identifying".
TEST(IdentifierHealth, SamplesWhileRosTimeStandsStillAreAnError)
{
  const acc::IdentifierCounters now = running();
  EXPECT_EQ(acc::identifierHealth(now, now, "", 0.1, 5.0, "", 4.0).level, DiagnosticStatus::OK);
  const acc::IdentifierHealth stalled = acc::identifierHealth(now, now, "", 0.1, 5.0, "", 30.0);
  EXPECT_EQ(stalled.level, DiagnosticStatus::ERROR);
  EXPECT_NE(stalled.message.find("relative_state arrives but ROS time has stood still for 30 s"), std::string::npos)
      << stalled.message;
  // Once the input stopped too (the end of a replay, /clock with it), that is what is said.
  EXPECT_EQ(acc::identifierHealth(now, now, "", 6.0, 5.0, "", 30.0).level, DiagnosticStatus::WARN);
}

/// A take-over by the driver is said (OK: the driver's choice); samples whose ACC state is unknown
/// while engagement is required are a fault of the source (WARN).
TEST(IdentifierHealth, AccOffIsSaidAndAnUnknownAccStateWarns)
{
  const acc::IdentifierCounters before = running();
  acc::IdentifierCounters off = before;
  off.acc_off = 12;
  const acc::IdentifierHealth said = acc::identifierHealth(off, before, "");
  EXPECT_EQ(said.level, DiagnosticStatus::OK);
  EXPECT_EQ(said.message, "ACC off (acc_engaged): 12 relative_state sample(s) since last report not used");
  EXPECT_EQ(acc::identifierHealth(off, off, "").message, "identifying");
  acc::IdentifierCounters unknown = before;
  unknown.acc_state_unknown = 3;
  const acc::IdentifierHealth warn = acc::identifierHealth(unknown, before, "");
  EXPECT_EQ(warn.level, DiagnosticStatus::WARN);
  EXPECT_NE(warn.message.find("3 with the ACC's state unknown (not used)"), std::string::npos) << warn.message;
}

TEST(IdentifierHealth, EveryKindOfBadSampleAndJumpIsReportedSinceTheLastReport)
{
  const acc::IdentifierCounters before = running();
  acc::IdentifierCounters after = before;
  after.time_outliers = 2;
  after.implausible = 1;
  after.non_finite = 1;
  after.restarts = 1;
  after.jumps_ahead = 1;
  const acc::IdentifierHealth health = acc::identifierHealth(after, before, "");
  EXPECT_EQ(health.level, DiagnosticStatus::WARN);
  for (const char* part : {"2 time outliers", "1 implausible", "1 non-finite", "1 time jumps back", "1 time jumps ahead"})
    EXPECT_NE(health.message.find(part), std::string::npos) << part << " in " << health.message;
  acc::IdentifierCounters skipped = before;
  skipped.skipped_periods = 3;
  EXPECT_EQ(acc::identifierHealth(skipped, before, "").level, DiagnosticStatus::WARN);
  EXPECT_EQ(acc::identifierHealth(skipped, skipped, "").level, DiagnosticStatus::OK);
  EXPECT_EQ(acc::identifierHealth(acc::IdentifierCounters{}, acc::IdentifierCounters{}, "").level,
            DiagnosticStatus::WARN);  // no relative_state yet
}

/// Samples that arrive and cannot be used (a 1 Hz receiver against max_gap_s 0.5 s) warn with the
/// window's own explanation, for the reports in which it happened.
TEST(IdentifierHealth, AWindowWithNothingToSimulateWarnsWithItsReason)
{
  const acc::IdentifierCounters before = running();
  acc::IdentifierCounters after = before;
  after.received += 10;
  after.unusable_windows = 1;
  const std::string why = "10 pieces of fewer than 20 samples ...: a receiver at 1 Hz";
  const acc::IdentifierHealth warn = acc::identifierHealth(after, before, "", 0.0, 5.0, why);
  EXPECT_EQ(warn.level, DiagnosticStatus::WARN);
  EXPECT_NE(warn.message.find("1 period(s) whose window had no piece long enough to simulate: " + why),
            std::string::npos)
      << warn.message;
  EXPECT_EQ(acc::identifierHealth(after, after, "", 0.0, 5.0, why).level, DiagnosticStatus::OK);
}

/// A failed solve is an ERROR that says what was thrown, for one report; the total stays counted.
TEST(IdentifierHealth, AFailureIsAnErrorWithWhatWasThrownThenOkAgain)
{
  const acc::IdentifierCounters before = running();
  acc::IdentifierCounters after = before;
  after.failures = 1;
  after.out_of_order = 5;  // an ERROR outranks the WARN
  const acc::IdentifierHealth error = acc::identifierHealth(after, before, "solve: std::bad_alloc");
  EXPECT_EQ(error.level, DiagnosticStatus::ERROR);
  EXPECT_NE(error.message.find("1 failed"), std::string::npos) << error.message;
  EXPECT_NE(error.message.find("solve: std::bad_alloc"), std::string::npos) << error.message;
  EXPECT_EQ(acc::identifierHealth(after, after, "solve: std::bad_alloc").level, DiagnosticStatus::OK);
}

/// The worker's catch: std::exception of any kind, and what is not a std::exception.
TEST(IdentifierWorker, CatchesEveryExceptionAndSaysWhat)
{
  std::string failure;
  EXPECT_TRUE(acc::runCatchingEverything([] {}, failure));
  EXPECT_TRUE(failure.empty());
  EXPECT_FALSE(acc::runCatchingEverything([] { throw std::runtime_error("NLopt roundoff"); }, failure));
  EXPECT_EQ(failure, "NLopt roundoff");
  EXPECT_FALSE(acc::runCatchingEverything([] { throw std::bad_alloc(); }, failure));
  EXPECT_EQ(failure, std::bad_alloc().what());
  EXPECT_FALSE(acc::runCatchingEverything([] { throw std::out_of_range("segment 3"); }, failure));
  EXPECT_EQ(failure, "segment 3");
  EXPECT_FALSE(acc::runCatchingEverything([] { throw 42; }, failure));
  EXPECT_NE(failure.find("not a std::exception"), std::string::npos) << failure;
}
}  // namespace
