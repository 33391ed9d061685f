// rostest of a drive replayed as a user replays one (issue 26; see relative_state_record.test):
// the drivers replay at 20x, the leader's log starts a second after the follower's, the node waits
// for leader data with timeout_s 1e6, rosbag record records relative_state. The recording must
// hold every pairable epoch (every follower epoch with a leader epoch at its GNSS time) and as
// many samples as the node says it published. Before the fix the follower epochs of that first
// second held back every later one until the buffers overflowed, and the burst that followed
// overran the publisher's queue: a recording of some hundred samples.
#include "acc_identification/ros/relative_state_ros.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <thread>

#include <diagnostic_msgs/DiagnosticArray.h>
#include <ros/master.h>
#include <ros/network.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <xmlrpcpp/XmlRpc.h>

#include "acc_identification/gnss/nmea_log.h"
#include "ros_test_support.h"

namespace fs = std::filesystem;

namespace
{
/// GNSS times to the millisecond: the logs' centiseconds, compared without rounding trouble.
long long milliseconds(double time_s) { return std::llround(time_s * 1000.0); }

std::set<long long> epochTimes(const std::string& log)
{
  std::set<long long> times;
  for (const auto& fix : acc::readNmeaLog(log).fixes)
    times.insert(milliseconds(fix.gnss_time_s));
  return times;
}

struct Received
{
  std::size_t leader_fixes = 0, follower_fixes = 0;
  acc_test::DiagnosticStatusRecord diagnostics{"Relative state"};
  ros::WallTime last_fix = ros::WallTime::now();
  void onLeader(const acc_identification::GnssFix&)
  {
    ++leader_fixes;
    last_fix = ros::WallTime::now();
  }
  void onFollower(const acc_identification::GnssFix&)
  {
    ++follower_fixes;
    last_fix = ros::WallTime::now();
  }
};

void spinFor(double seconds)
{
  acc_test::spinFor(seconds, std::chrono::milliseconds(5));
}

/// True when the master lists node among topic's subscribers.
bool subscribes(const std::string& node, const std::string& topic)
{
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  if (!ros::master::execute("getSystemState", args, result, payload, false))
    return false;
  XmlRpc::XmlRpcValue& subscriptions = payload[1];
  for (int i = 0; i < subscriptions.size(); ++i)
    if (static_cast<std::string>(subscriptions[i][0]) == topic)
      for (int j = 0; j < subscriptions[i][1].size(); ++j)
        if (static_cast<std::string>(subscriptions[i][1][j]) == node)
          return true;
  return false;
}

/// Asks node to shut down (as rosnode kill does): rosbag record then closes its bag.
bool shutDown(const std::string& node)
{
  XmlRpc::XmlRpcValue args, result, payload;
  args[0] = ros::this_node::getName();
  args[1] = node;
  std::string host;
  std::uint32_t port = 0;
  if (!ros::master::execute("lookupNode", args, result, payload, false) ||
      !ros::network::splitURI(static_cast<std::string>(payload), host, port))
    return false;
  XmlRpc::XmlRpcClient client(host.c_str(), static_cast<int>(port), "/");
  XmlRpc::XmlRpcValue shutdown_args, shutdown_result;
  shutdown_args[0] = ros::this_node::getName();
  shutdown_args[1] = "the check has what it needs";
  return client.execute("shutdown", shutdown_args, shutdown_result);
}
}  // namespace

TEST(RelativeStateRecord, TheRecordingHoldsEveryPairableEpochAndEverySamplePublished)
{
  ros::NodeHandle node, private_node("~");
  std::string leader_log, follower_log, bag_path, recorder;
  ASSERT_TRUE(private_node.getParam("leader_log", leader_log));
  ASSERT_TRUE(private_node.getParam("follower_log", follower_log));
  ASSERT_TRUE(private_node.getParam("bag", bag_path));
  ASSERT_TRUE(private_node.getParam("recorder", recorder));
  const std::set<long long> leader_times = epochTimes(leader_log), follower_times = epochTimes(follower_log);
  std::set<long long> pairable;
  for (long long t : follower_times)
    if (leader_times.count(t))
      pairable.insert(t);
  ASSERT_GT(pairable.size(), 1000u);
  ASSERT_LT(pairable.size(), follower_times.size()) << "the leader's log should start later";
  fs::remove(bag_path);

  // The replay starts when this check subscribes to the fixes (wait_for_subscribers): only once
  // the recorder is registered and has had a moment to connect to relative_state_node.
  const ros::WallTime deadline = ros::WallTime::now() + ros::WallDuration(30.0);
  while (ros::ok() && !subscribes(recorder, "/relative_state") && ros::WallTime::now() < deadline)
    spinFor(0.1);
  ASSERT_TRUE(subscribes(recorder, "/relative_state")) << recorder << " did not subscribe";
  spinFor(1.0);
  Received received;
  auto diagnostics_sub = node.subscribe("/diagnostics", 100, &acc_test::DiagnosticStatusRecord::onDiagnostics,
                                        &received.diagnostics);
  auto leader_sub = node.subscribe("leader/fix", 100000, &Received::onLeader, &received);
  auto follower_sub = node.subscribe("follower/fix", 100000, &Received::onFollower, &received);
  // Until both logs are through, or nothing has come for 15 s; then two diagnostic periods.
  received.last_fix = ros::WallTime::now();
  while (ros::ok() && (received.leader_fixes < leader_times.size() || received.follower_fixes < follower_times.size()) &&
         (ros::WallTime::now() - received.last_fix).toSec() < 15.0)
    spinFor(0.1);
  spinFor(2.5);
  EXPECT_EQ(received.leader_fixes, leader_times.size());
  EXPECT_EQ(received.follower_fixes, follower_times.size());

  ASSERT_TRUE(shutDown(recorder)) << "could not ask " << recorder << " to shut down";
  const ros::WallTime closed_by = ros::WallTime::now() + ros::WallDuration(20.0);
  while (!fs::exists(bag_path) && ros::WallTime::now() < closed_by)
    spinFor(0.1);
  ASSERT_TRUE(fs::exists(bag_path)) << "the recorder did not close " << bag_path;
  rosbag::Bag bag(bag_path, rosbag::bagmode::Read);
  std::set<long long> recorded;
  std::size_t recorded_samples = 0;
  for (const rosbag::MessageInstance& message : rosbag::View(bag, rosbag::TopicQuery("/relative_state")))
  {
    auto state = message.instantiate<acc_identification::RelativeState>();
    ASSERT_TRUE(state);
    recorded.insert(milliseconds(state->header.stamp.toSec()));
    ++recorded_samples;
  }

  std::size_t missing = 0;
  for (long long t : pairable)
    missing += recorded.count(t) == 0;
  std::printf("%zu pairable epochs (follower %zu, leader %zu); node published %s; recorded %zu, %zu pairable "
              "missing; buffer_overflows %s, follower_unpaired %s\n",
              pairable.size(), follower_times.size(), leader_times.size(), received.diagnostics.values["published"].c_str(),
              recorded_samples, missing, received.diagnostics.values["buffer_overflows"].c_str(),
              received.diagnostics.values["follower_unpaired"].c_str());
  ASSERT_FALSE(received.diagnostics.values.empty()) << "no diagnostics from relative_state_node";
  EXPECT_EQ(std::to_string(recorded_samples), received.diagnostics.values["published"]);
  EXPECT_EQ(missing, 0u);
  EXPECT_EQ(recorded_samples, pairable.size());
  EXPECT_EQ(received.diagnostics.values["follower_unpaired"], std::to_string(follower_times.size() - pairable.size()));
  EXPECT_EQ(received.diagnostics.values["buffer_overflows"], "0");
}

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "relative_state_record_check");
  return RUN_ALL_TESTS();
}
