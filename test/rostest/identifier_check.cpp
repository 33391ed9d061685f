// Publishes /clock and relative_state from a synthetic run of known parameters, faster than real
// time, and checks what identifier_node publishes on acc_parameters.
#include <gtest/gtest.h>

#include <cmath>
#include <mutex>
#include <vector>

#include <ros/ros.h>
#include <rosgraph_msgs/Clock.h>

#include "acc_identification/synthesis/synthetic_runs.h"
#include "acc_identification/model/paper_settings.h"
#include "ros_test_support.h"

#include <acc_identification/AccParameters.h>
#include <acc_identification/RelativeState.h>


namespace
{
TEST(Identifier, SyntheticRelativeStateGivesTheTrueParameters)
{
  ros::NodeHandle node;
  ros::AsyncSpinner spinner(1);
  spinner.start();
  auto clock = node.advertise<rosgraph_msgs::Clock>("/clock", 10);
  auto states = node.advertise<acc_identification::RelativeState>("relative_state", 1000);
  acc_test::MessageLog<acc_identification::AccParameters> log;
  auto parameters = node.subscribe("acc_parameters", 100, &acc_test::MessageLog<acc_identification::AccParameters>::on, &log);
  ASSERT_TRUE(acc_test::waitForConnections([&] {
    return states.getNumSubscribers() > 0 && parameters.getNumPublishers() > 0 && clock.getNumSubscribers() > 0;
  })) << "identifier_node did not subscribe";

  const acc::AccParameters truth = acc::paperMinimumSetting();
  // 150 s from GNSS time 1000 s, with a 2 s hole (a dropout) after 50 s and one invalid sample at 70 s.
  const acc::CarFollowingRun run = acc::synthesizeRun(truth, 150.0, 0.1, 25.0, 7);
  const double t0 = 1000.0;
  std::size_t published = 0;
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    const double t = t0 + run.time_s[k];
    rosgraph_msgs::Clock now;
    now.clock = ros::Time(t);
    clock.publish(now);
    if (run.time_s[k] > 50.0 && run.time_s[k] < 52.0)
    {
      continue;
    }
    acc_identification::RelativeState state;
    state.header.stamp = ros::Time(t);
    state.space_gap_m = run.space_gap_m[k];
    state.follower_speed_mps = run.follower_speed_mps[k];
    state.leader_speed_mps = run.leader_speed_mps[k];
    state.relative_speed_mps = state.leader_speed_mps - state.follower_speed_mps;
    state.valid = k != 700;
    state.invalid_reason = state.valid ? "" : "test: invalid sample";
    states.publish(state);
    ++published;
    ros::WallDuration(0.01).sleep();  // ten times real time
  }
  // Let the last periods run.
  for (int i = 0; i < 30; ++i)
  {
    rosgraph_msgs::Clock now;
    now.clock = ros::Time(t0 + run.time_s.back() + 0.1 * (i + 1));
    clock.publish(now);
    ros::WallDuration(0.05).sleep();
  }
  std::unique_lock<std::mutex> lock(log.mutex);
  const std::vector<acc_identification::AccParameters>& received = log.messages;
  ASSERT_FALSE(received.empty()) << "no acc_parameters published";
  // Early windows (under 30 s of data) are reported, not fitted.
  EXPECT_FALSE(received.front().identifiable);
  EXPECT_EQ(received.front().optimizer_status, "NOT_SOLVED");
  EXPECT_TRUE(std::isnan(received.front().k1_per_s2));
  const acc_identification::AccParameters& last = received.back();
  ASSERT_TRUE(last.identifiable) << last.identifiability_note;
  // The 120 s window ends at the last sample; it holds every valid sample of that span (none
  // dropped: 1201 less 19 in the dropout and the invalid one), split by the dropout and the invalid
  // sample into three segments.
  EXPECT_NEAR((last.window_end - last.window_start).toSec(), 120.0, 0.11);
  EXPECT_NEAR(last.window_end.toSec(), t0 + run.time_s.back(), 1e-6);
  EXPECT_EQ(last.segments, 3u);
  EXPECT_GE(last.samples, 1180u);
  EXPECT_LE(last.samples, 1182u);
  // Within three standard errors of the truth plus 4 % of it, and the verdict of the truth: the
  // data are made ten times finer than the 10 Hz Euler recursion the node fits (no inverse crime),
  // so the fit carries that recursion's own bias, about h (k2 + k1 tau_e) / 2: 1-2 % here
  // (test_calibration_multistart measures it on noise-free data).
  const auto allowed = [](double se, double value) { return 3.0 * se + 0.04 * std::abs(value); };
  EXPECT_NEAR(last.k1_per_s2, truth.k1_per_s2, allowed(last.k1_std_error, truth.k1_per_s2));
  EXPECT_NEAR(last.k2_per_s, truth.k2_per_s, allowed(last.k2_std_error, truth.k2_per_s));
  EXPECT_NEAR(last.tau_e_s, truth.tau_e_s, allowed(last.tau_e_std_error, truth.tau_e_s));
  EXPECT_NEAR(last.eta_m, truth.eta_m, allowed(last.eta_std_error, truth.eta_m));
  EXPECT_LT(last.k1_std_error, 0.25 * truth.k1_per_s2);
  EXPECT_LT(last.rmse_speed_mps, 0.08);
  EXPECT_EQ(last.string_stable, acc_identification::AccParameters::STRING_UNSTABLE);
  // The drive fit of the truth's own data describes them.
  EXPECT_EQ(last.model_adequate, acc_identification::AccParameters::MODEL_ADEQUATE) << last.model_adequacy_reasons;
  EXPECT_GT(last.lambda2, 0.0);
  // The sequential verdict: looked at once there were samples to fit (e-values published), and a
  // decision, once in a message, in every later one (never withdrawn).
  EXPECT_FALSE(std::isnan(last.stability_e_value_unstable)) << last.stability_reason;
  EXPECT_GT(last.stability_samples, 0u);
  std::string taken = "undecided";
  for (const acc_identification::AccParameters& message : received)
  {
    if (taken != "undecided")
    {
      EXPECT_EQ(message.stability_verdict, taken) << message.stability_reason;
    }
    taken = message.stability_verdict;
  }
  // The solve is timed and published; its speed is a benchmark's business (bench_online_identifier).
  EXPECT_GE(last.solve_time_s, 0.0);

  // Latched: a subscriber that comes once the data have ended (the clock stands still, so nothing
  // new is published) still gets the last estimate.
  const acc_identification::AccParameters last_received = last;
  lock.unlock();
  acc_test::MessageLog<acc_identification::AccParameters> late;
  auto late_subscriber =
      node.subscribe("acc_parameters", 1, &acc_test::MessageLog<acc_identification::AccParameters>::on, &late);
  EXPECT_TRUE(acc_test::waitForConnections([&] {
    std::lock_guard<std::mutex> late_lock(late.mutex);
    return !late.messages.empty();
  }, 10.0)) << "a late subscriber got no acc_parameters: the topic is not latched";
  std::lock_guard<std::mutex> late_lock(late.mutex);
  ASSERT_EQ(late.messages.size(), 1u);
  EXPECT_EQ(late.messages.front().window_end, last_received.window_end);
  EXPECT_EQ(late.messages.front().stability_verdict, last_received.stability_verdict);
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "identifier_check");
  return RUN_ALL_TESTS();
}
