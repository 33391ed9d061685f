// identifier_node's wrapper (acc::IdentifierRos) in this process, its solve replaced by one the test
// controls, fed relative_state with the input faults of a real drive: a late sample, a stamp a day
// in the future, one in the past, a sustained time reset, an implausible speed; then solves that
// throw a std::exception and something that is not one; and a safety driver's take-over reported on
// acc_engaged. Checks the window (what the solve is
// given), the diagnostics (level since the last report, totals, what was thrown) and that the node
// goes on publishing.
#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/ros.h>
#include <std_msgs/Bool.h>
#include <std_msgs/String.h>

#include "acc_identification/ros/identifier_ros.h"

namespace
{
using diagnostic_msgs::DiagnosticStatus;

// The solve the node runs: counts what it is given, throws when told to.
enum class SolveMode
{
  kFine,
  kThrowStd,
  kThrowOther,
};
std::atomic<SolveMode> solve_mode{SolveMode::kFine};
std::atomic<std::size_t> window_samples{0};
std::atomic<std::size_t> solves{0};

acc::OnlineUpdate injectedSolve(acc::OnlineIdentifier&, const std::vector<acc::CarFollowingRun>& window,
                                const std::vector<acc::CarFollowingRun>& drive)
{
  std::size_t samples = 0;
  for (const acc::CarFollowingRun& segment : window)
    samples += segment.size();
  window_samples = samples;
  ++solves;
  switch (solve_mode.load())
  {
    case SolveMode::kThrowStd: throw std::runtime_error("injected solver failure");
    case SolveMode::kThrowOther: throw 42;
    case SolveMode::kFine: break;
  }
  acc::OnlineUpdate update;
  update.window.note = "injected solve";
  update.drive.note = "injected solve";
  for (const acc::CarFollowingRun& segment : drive)
    update.drive_samples += segment.size();
  return update;
}

struct Report
{
  std::uint8_t level = 0;
  std::string message;
  std::map<std::string, std::string> values;
  std::uint64_t count(const std::string& key) const
  {
    const auto found = values.find(key);
    return found == values.end() ? ~0ull : std::stoull(found->second);
  }
};

std::mutex mutex;
std::vector<Report> reports;
std::atomic<std::size_t> parameters_received{0};

void onDiagnostics(const diagnostic_msgs::DiagnosticArray::ConstPtr& array)
{
  for (const auto& status : array->status)
  {
    if (status.name.find("ACC identification") == std::string::npos)
      continue;
    Report report;
    report.level = static_cast<std::uint8_t>(status.level);
    report.message = status.message;
    for (const auto& kv : status.values)
      report.values[kv.key] = kv.value;
    std::lock_guard<std::mutex> lock(mutex);
    reports.push_back(report);
  }
}

std::string last_setting;  ///< acc_setting of the last acc_parameters, under mutex

void onParameters(const acc_identification::AccParameters::ConstPtr& message)
{
  {
    std::lock_guard<std::mutex> lock(mutex);
    last_setting = message->acc_setting;
  }
  ++parameters_received;
}

std::size_t reportCount()
{
  std::lock_guard<std::mutex> lock(mutex);
  return reports.size();
}

/// The first report from index `from` on that satisfies `wanted`, waiting up to timeout_s.
bool waitForReport(std::size_t from, const std::function<bool(const Report&)>& wanted, Report& found,
                   double timeout_s = 8.0)
{
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeout_s);
  while (std::chrono::steady_clock::now() < deadline && ros::ok())
  {
    {
      std::lock_guard<std::mutex> lock(mutex);
      for (std::size_t i = from; i < reports.size(); ++i)
      {
        if (wanted(reports[i]))
        {
          found = reports[i];
          return true;
        }
      }
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return false;
}

std::string describe(const Report& report)
{
  std::string text = "level " + std::to_string(report.level) + " '" + report.message + "'";
  for (const auto& [key, value] : report.values)
    text += "; " + key + " = " + value;
  return text;
}

/// The last report received, for failure messages.
std::string lastReport()
{
  std::lock_guard<std::mutex> lock(mutex);
  return reports.empty() ? std::string("no report") : describe(reports.back());
}

bool isOk(const Report& report) { return report.level == DiagnosticStatus::OK; }

/// Whether the node subscribes to the publisher's topic within 20 s.
bool subscribed(const ros::Publisher& publisher)
{
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(20);
  while (publisher.getNumSubscribers() == 0 && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  return publisher.getNumSubscribers() > 0;
}

class Feed
{
public:
  explicit Feed(ros::NodeHandle& node) : publisher_(node.advertise<acc_identification::RelativeState>("relative_state", 1000)) {}

  bool connected() { return subscribed(publisher_); }

  void publish(double time_s, double follower_speed_mps = 20.0)
  {
    acc_identification::RelativeState state;
    state.header.stamp = ros::Time(time_s);
    state.space_gap_m = 30.0;
    state.follower_speed_mps = follower_speed_mps;
    state.leader_speed_mps = 20.5;
    state.relative_speed_mps = 0.5;
    state.valid = true;
    publisher_.publish(state);
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }

  /// count samples 0.1 s apart from start_s.
  void publishRun(double start_s, int count)
  {
    for (int k = 0; k < count; ++k)
      publish(start_s + 0.1 * k);
  }

private:
  ros::Publisher publisher_;
};

std::unique_ptr<Feed> feed;

/// Waits until the solve has been given `expected` window samples (a period after the last sample).
bool windowHolds(std::size_t expected)
{
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (std::chrono::steady_clock::now() < deadline)
  {
    if (window_samples == expected)
      return true;
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  return false;
}

TEST(IdentifierFaults, OneLateSampleWarnsInOneReportThenOkAgain)
{
  ASSERT_TRUE(feed->connected());
  feed->publishRun(1000.0, 50);  // 1000.0 - 1004.9
  Report report;
  ASSERT_TRUE(waitForReport(0, [](const Report& r) { return isOk(r) && r.count("samples received") == 50; }, report))
      << lastReport();
  ASSERT_TRUE(windowHolds(50)) << window_samples;
  const std::size_t before = reportCount();
  feed->publish(1004.7);  // late by 0.2 s: rejected, counted
  ASSERT_TRUE(waitForReport(before, [](const Report& r) { return r.level == DiagnosticStatus::WARN; }, report))
      << lastReport();
  EXPECT_NE(report.message.find("1 out-of-order"), std::string::npos) << describe(report);
  EXPECT_EQ(report.count("out-of-order samples (rejected)"), 1u) << describe(report);
  // Nothing new since: the next reports are OK, the total still shown. (WARN used to latch.)
  ASSERT_TRUE(waitForReport(before, [](const Report& r) { return isOk(r); }, report)) << lastReport();
  EXPECT_EQ(report.count("out-of-order samples (rejected)"), 1u) << describe(report);
  EXPECT_TRUE(windowHolds(50)) << window_samples;
}

TEST(IdentifierFaults, OneStampInTheFutureAndOneInThePastLeaveTheWindowAlone)
{
  const std::size_t before = reportCount();
  feed->publish(1004.9 + 86400.0);  // a day ahead: held
  feed->publishRun(1005.0, 10);     // the time base goes on: the held sample is dropped
  feed->publish(1000.0);            // 5.9 s back: held
  feed->publishRun(1006.0, 10);     // dropped too
  ASSERT_TRUE(windowHolds(70)) << "the window lost samples: it holds " << window_samples;
  Report report;
  ASSERT_TRUE(waitForReport(before, [](const Report& r) { return r.count("time outliers (dropped)") == 2; }, report))
      << lastReport();
  EXPECT_EQ(report.count("time jumps back (window cleared)"), 0u) << describe(report);
  EXPECT_EQ(report.count("time jumps ahead (confirmed)"), 0u) << describe(report);
  ASSERT_TRUE(waitForReport(before, [](const Report& r) { return r.level == DiagnosticStatus::WARN; }, report))
      << lastReport();
  EXPECT_NE(report.message.find("time outliers"), std::string::npos) << describe(report);
  ASSERT_TRUE(waitForReport(before, [](const Report& r) { return isOk(r) && r.count("time outliers (dropped)") == 2; },
                            report))
      << lastReport();
}

/// ~jump_confirm_samples is 3 in identifier_faults.test (5 by default): the third sample of a
/// sustained jump back restarts the window, as a replay restart must.
TEST(IdentifierFaults, ASustainedTimeResetRestartsTheWindowAfterTheConfiguredCount)
{
  const std::size_t before = reportCount();
  feed->publishRun(500.0, 3);
  ASSERT_TRUE(windowHolds(3)) << "no restart after 3 consistent samples: the window holds " << window_samples;
  Report report;
  ASSERT_TRUE(waitForReport(before, [](const Report& r) { return r.count("time jumps back (window cleared)") == 1; },
                            report))
      << lastReport();
  EXPECT_EQ(report.count("drive resets"), 1u) << describe(report);
  EXPECT_EQ(report.count("time outliers (dropped)"), 2u) << describe(report);
}

/// The batch readers' plausibility bounds, live: the sample is a split point, counted and reported.
TEST(IdentifierFaults, AnImplausibleSampleIsASplitPointCountedAndReported)
{
  feed->publishRun(500.3, 7);  // 500.3 - 500.9
  ASSERT_TRUE(windowHolds(10)) << window_samples;
  const std::size_t before = reportCount();
  feed->publish(501.0, 1.0e9);  // 1e9 m/s
  feed->publishRun(501.1, 10);
  ASSERT_TRUE(windowHolds(20)) << window_samples;  // the bad sample is in none of the segments
  Report report;
  ASSERT_TRUE(waitForReport(before, [](const Report& r) { return r.level == DiagnosticStatus::WARN; }, report))
      << lastReport();
  EXPECT_NE(report.message.find("1 implausible"), std::string::npos) << describe(report);
  EXPECT_EQ(report.count("implausible samples (split points)"), 1u) << describe(report);
  ASSERT_TRUE(waitForReport(before, [](const Report& r) { return isOk(r); }, report)) << lastReport();
  // Implausible and late: counted once, for its first reason (it used to be out-of-order too).
  feed->publish(501.95, 1.0e9);
  ASSERT_TRUE(waitForReport(before, [](const Report& r) { return r.count("implausible samples (split points)") == 2; },
                            report))
      << lastReport();
  EXPECT_EQ(report.count("out-of-order samples (rejected)"), 1u) << describe(report);
}

/// Reports on acc_engaged, waiting until the node has the one sent (its diagnostics say it).
void reportEngagement(ros::Publisher& engagement, bool engaged)
{
  std_msgs::Bool report;
  report.data = engaged;
  engagement.publish(report);
  Report found;
  const std::string latest = engaged ? "engaged" : "off";
  ASSERT_TRUE(waitForReport(reportCount(), [&](const Report& r) { return r.values.count("ACC engagement (latest report)") &&
                                                                        r.values.at("ACC engagement (latest report)") == latest; },
                            found))
      << lastReport();
}

/// A take-over by the safety driver: the samples while the ACC reports itself off are split points,
/// in no segment, counted, and said in an OK report (the driver's choice is no fault).
TEST(IdentifierFaults, SamplesWhileTheAccIsOffAreSplitPointsCountedAndNotUsed)
{
  ros::NodeHandle node;
  ros::Publisher engagement = node.advertise<std_msgs::Bool>("acc_engaged", 10);
  ASSERT_TRUE(subscribed(engagement));
  ASSERT_TRUE(windowHolds(20)) << window_samples;  // 500.3 - 502.0 from the test before
  const std::size_t before = reportCount();
  reportEngagement(engagement, false);
  feed->publishRun(502.1, 10);  // 502.1 - 503.0, ACC off
  feed->publish(502.95);        // late while the ACC is off: counted once, as ACC off
  reportEngagement(engagement, true);
  feed->publishRun(503.1, 10);  // 503.1 - 504.0
  ASSERT_TRUE(windowHolds(30)) << "the window holds " << window_samples << ", not the 20 + 10 samples the ACC drove";
  Report report;
  ASSERT_TRUE(waitForReport(before, [](const Report& r) { return r.count("samples with the ACC off (split points, not used)") == 11; },
                            report))
      << lastReport();
  EXPECT_EQ(report.count("out-of-order samples (rejected)"), 1u) << describe(report);
  EXPECT_EQ(report.count("ACC disengagements reported"), 1u) << describe(report);
  EXPECT_EQ(report.count("acc_engaged reports"), 2u) << describe(report);
  EXPECT_EQ(report.count("invalid samples (split points)"), 0u) << describe(report);
  ASSERT_TRUE(waitForReport(before, [](const Report& r) { return r.message.find("ACC off (acc_engaged)") != std::string::npos; },
                            report))
      << lastReport();
  EXPECT_EQ(report.level, DiagnosticStatus::OK) << describe(report);
}

/// The driver changes the ACC's distance setting: what came before is another setting's, so the
/// window is cleared and a new drive starts; the messages say which setting they are of.
TEST(IdentifierFaults, ANewAccSettingStartsANewDrive)
{
  ros::NodeHandle node;
  ros::Publisher setting = node.advertise<std_msgs::String>("acc_setting", 10);
  ASSERT_TRUE(subscribed(setting));
  ASSERT_TRUE(windowHolds(30)) << window_samples;  // from the test before
  Report report;
  ASSERT_TRUE(waitForReport(reportCount(), [](const Report&) { return true; }, report)) << lastReport();
  const std::uint64_t resets_before = report.count("drive resets");
  std_msgs::String max;
  max.data = "max";
  setting.publish(max);
  ASSERT_TRUE(waitForReport(reportCount(), [](const Report& r) { return r.values.count("ACC setting (latest report)") &&
                                                                        r.values.at("ACC setting (latest report)") == "max"; },
                            report))
      << lastReport();
  EXPECT_EQ(report.count("ACC setting changes reported"), 1u) << describe(report);
  feed->publishRun(504.1, 10);
  ASSERT_TRUE(windowHolds(10)) << "the window holds " << window_samples << ", not the new setting's 10 samples";
  ASSERT_TRUE(waitForReport(reportCount(), [&](const Report& r) { return r.count("drive resets") == resets_before + 1; },
                            report))
      << lastReport();
  const auto published_deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  std::string setting_seen;
  while (setting_seen != "max" && std::chrono::steady_clock::now() < published_deadline)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    std::lock_guard<std::mutex> lock(mutex);
    setting_seen = last_setting;
  }
  EXPECT_EQ(setting_seen, "max");
  setting.publish(max);  // repeated: no change, no new drive
  feed->publishRun(505.1, 5);
  EXPECT_TRUE(windowHolds(15)) << window_samples;
}

/// Whatever the solve throws, the worker catches it, counts it, says what it was (ERROR), and the
/// node goes on: the next fine solve is published and the level is OK again.
TEST(IdentifierFaults, AThrowingSolveIsAnErrorWithWhatItThrewAndTheNodeGoesOn)
{
  std::size_t before = reportCount();
  solve_mode = SolveMode::kThrowStd;
  Report report;
  ASSERT_TRUE(waitForReport(before, [](const Report& r) { return r.level == DiagnosticStatus::ERROR; }, report))
      << lastReport();
  EXPECT_NE(report.message.find("injected solver failure"), std::string::npos) << describe(report);
  EXPECT_GE(report.count("failed solves or tests"), 1u) << describe(report);
  EXPECT_NE(report.values["last failure"].find("injected solver failure"), std::string::npos) << describe(report);

  before = reportCount();
  solve_mode = SolveMode::kThrowOther;
  ASSERT_TRUE(waitForReport(before,
                            [](const Report& r) {
                              return r.level == DiagnosticStatus::ERROR &&
                                     r.message.find("not a std::exception") != std::string::npos;
                            },
                            report))
      << lastReport();

  solve_mode = SolveMode::kFine;
  const std::size_t published = parameters_received;
  before = reportCount();
  ASSERT_TRUE(waitForReport(before, [](const Report& r) { return isOk(r); }, report)) << lastReport();
  EXPECT_GE(report.count("failed solves or tests"), 2u) << describe(report);
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(5);
  while (parameters_received <= published && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  EXPECT_GT(parameters_received.load(), published) << "nothing published after the failures";
}

/// A receiver slower than ~max_gap_s allows (1 Hz against 0.5 s): samples arrive and none can be
/// simulated. The diagnostics used to stay OK ("identifying"); they warn, and say the samples' rate.
TEST(IdentifierFaults, SamplesThatArriveButCannotBeSimulatedWarn)
{
  const std::size_t before = reportCount();
  for (int k = 0; k < 32; ++k)  // 507 - 538 s at 1 Hz: the 30 s window ends up holding only these
    feed->publish(507.0 + k);
  ASSERT_TRUE(windowHolds(0)) << "the solve was given " << window_samples << " samples to simulate";
  Report report;
  ASSERT_TRUE(waitForReport(before, [](const Report& r) { return r.level == DiagnosticStatus::WARN &&
                                                               r.message.find("no piece long enough") != std::string::npos; },
                            report))
      << lastReport();
  EXPECT_NE(report.message.find("a receiver at 1 Hz"), std::string::npos) << describe(report);
  EXPECT_GE(report.count("windows with no piece long enough to simulate"), 1u) << describe(report);
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "identifier_faults");
  ros::NodeHandle node;
  ros::AsyncSpinner spinner(2);
  spinner.start();
  ros::Subscriber diagnostics = node.subscribe("/diagnostics", 100, onDiagnostics);
  ros::Subscriber parameters = node.subscribe("acc_parameters", 100, onParameters);
  int result = 1;
  {
    acc::IdentifierRos identifier(node, ros::NodeHandle("~"), injectedSolve);
    if (!identifier.ok())
      return 1;
    feed = std::make_unique<Feed>(node);
    result = RUN_ALL_TESTS();
    feed.reset();
  }
  spinner.stop();
  return result;
}
