// Reads the parameters test/rostest/node_parameters.test sets: acc::ParameterReader on values of
// every type as users write them, the three nodes' loaders on a slip each, and the shipped config
// files, which every node must read whole and without an error.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include <ros/ros.h>

#include "acc_identification/ros/gps_driver_ros.h"
#include "acc_identification/ros/identifier_ros.h"
#include "acc_identification/ros/relative_state_ros.h"
#include "acc_identification/ros/ros_parameter_source.h"
#include "../unit/parameter_refusals.h"

namespace
{
/// A reader of the parameters in one namespace, with the source it reads.
struct NodeParameters
{
  explicit NodeParameters(const std::string& ns) : source(ros::NodeHandle(ns)) {}
  acc::RosParameterSource source;
  acc::ParameterReader reader{source};
};

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

TEST(ParameterReader, NumbersOfEitherYamlTypeAreRead)
{
  NodeParameters reader_parameters("~");
  acc::ParameterReader& reader = reader_parameters.reader;
  double signed_exponent = 0.0, integer = 0.0, launch_exponent = 0.0;
  int whole = 0;
  EXPECT_TRUE(reader.read("signed_exponent", signed_exponent));
  EXPECT_TRUE(reader.read("integer", integer));
  EXPECT_TRUE(reader.read("launch_exponent_with_dot", launch_exponent));  // <param value="1.0e6">
  EXPECT_TRUE(reader.read("whole_double", whole));
  EXPECT_EQ(signed_exponent, 1e6);
  EXPECT_EQ(integer, 7.0);
  EXPECT_EQ(launch_exponent, 1e6);
  EXPECT_EQ(whole, 200);
  EXPECT_TRUE(reader.ok()) << reader.error();
}

TEST(ParameterReader, AnUnsetParameterKeepsTheDefault)
{
  NodeParameters reader_parameters("~");
  acc::ParameterReader& reader = reader_parameters.reader;
  double value = 0.25;
  std::string word = "kept";
  EXPECT_TRUE(reader.read("nowhere", value));
  EXPECT_TRUE(reader.read("nowhere_either", word));
  EXPECT_EQ(value, 0.25);
  EXPECT_EQ(word, "kept");
}

TEST(ParameterReader, AYamlExponentWithoutDotAndSignIsAStringNamedWithTheFix)
{
  NodeParameters reader_parameters("~");
  acc::ParameterReader& reader = reader_parameters.reader;
  double value = 2.0;
  EXPECT_FALSE(reader.read("yaml_exponent", value));
  EXPECT_EQ(value, 2.0);
  EXPECT_TRUE(contains(reader.error(), "parameter ~yaml_exponent is the string \"1e6\", not a number")) << reader.error();
  EXPECT_TRUE(contains(reader.error(), "write 1000000 or 1.0e+6")) << reader.error();
  // roslaunch's <param value="1e6"> (and arg:=1e6) is text too: it wants a dot.
  NodeParameters launch_reader_parameters("~");
  acc::ParameterReader& launch_reader = launch_reader_parameters.reader;
  EXPECT_FALSE(launch_reader.read("launch_exponent", value));
  EXPECT_TRUE(contains(launch_reader.error(), "~launch_exponent is the string \"1e6\"")) << launch_reader.error();
}

/// The reader's error for one read of ~name into a value of type T (its default kept).
template <typename T>
std::string refusal(const std::string& name, T value)
{
  NodeParameters reader_parameters("~");
  acc::ParameterReader& reader = reader_parameters.reader;
  const T before = value;
  EXPECT_FALSE(reader.read(name, value)) << name;
  EXPECT_EQ(value, before) << name;
  return reader.error();
}

TEST(ParameterReader, EveryWrongTypeIsRefusedByName)
{
  expectEveryWrongTypeRefusedByName([](const std::string& name, auto value) { return refusal(name, value); });
}

TEST(ParameterReader, ListsOfStringsAreRead)
{
  NodeParameters reader_parameters("~");
  acc::ParameterReader& reader = reader_parameters.reader;
  std::vector<std::string> topics;
  EXPECT_TRUE(reader.read("topics", topics));
  EXPECT_EQ(topics, (std::vector<std::string>{"fix", "vel"}));
}

TEST(ParameterReader, RangesAreCheckedAndNanIsRefused)
{
  NodeParameters above_parameters("~");
  acc::ParameterReader& above = above_parameters.reader;
  double value = 1.0;
  EXPECT_FALSE(above.readAbove("negative", value, 0.0));
  EXPECT_EQ(above.error(), "parameter ~negative = -1 must be finite and > 0");
  NodeParameters at_least_parameters("~");
  acc::ParameterReader& at_least = at_least_parameters.reader;
  EXPECT_FALSE(at_least.readAtLeast("not_a_number", value, 0.0));
  EXPECT_TRUE(contains(at_least.error(), "must be finite and >= 0")) << at_least.error();
  NodeParameters integers_parameters("~");
  acc::ParameterReader& integers = integers_parameters.reader;
  int count = 1;
  EXPECT_FALSE(integers.readAtLeast("integer", count, 8));
  EXPECT_EQ(integers.error(), "parameter ~integer = 7 must be >= 8");
}

TEST(ParameterReader, TheFirstErrorStaysAndLaterReadsAreSkipped)
{
  NodeParameters reader_parameters("~");
  acc::ParameterReader& reader = reader_parameters.reader;
  double first = 0.0, later = 0.0;
  EXPECT_FALSE(reader.read("yaml_exponent", first));
  EXPECT_FALSE(reader.read("signed_exponent", later));
  EXPECT_EQ(later, 0.0);
  EXPECT_FALSE(reader.require(false, "a second problem"));
  EXPECT_TRUE(contains(reader.error(), "~yaml_exponent")) << reader.error();
}

TEST(ParameterReader, ParametersNeverReadAreNamed)
{
  NodeParameters reader_parameters("~identifier_slip");
  acc::ParameterReader& reader = reader_parameters.reader;
  double max_gap_s = 0.0;
  EXPECT_TRUE(reader.read("max_gap_s", max_gap_s));
  EXPECT_EQ(reader.unreadNote(), "parameter ~window_s is set but never read (misspelt?): ignored");
  double window_s = 0.0;
  reader.read("window_s", window_s);
  EXPECT_EQ(reader.unreadNote(), "");
}

TEST(NodeParameters, TheIdentifierRefusesAStringWindow)
{
  NodeParameters reader_parameters("~identifier_slip");
  acc::ParameterReader& reader = reader_parameters.reader;
  acc::IdentifierSettings settings;
  EXPECT_FALSE(acc::loadIdentifierSettings(reader, settings));
  EXPECT_TRUE(contains(reader.error(), "parameter ~window_s is the string \"3e2\"")) << reader.error();
}

/// 1 for true, as a launch file's value="1" gives: an int, which the node will not read as a bool.
TEST(NodeParameters, TheIdentifierRefusesAnIntegerForRequireAccEngaged)
{
  NodeParameters reader_parameters("~identifier_engagement_slip");
  acc::ParameterReader& reader = reader_parameters.reader;
  acc::IdentifierSettings settings;
  EXPECT_FALSE(acc::loadIdentifierSettings(reader, settings));
  EXPECT_TRUE(contains(reader.error(), "~require_acc_engaged")) << reader.error();
}

TEST(NodeParameters, RelativeStateRefusesAStringTimeoutAndAnEmptyQueue)
{
  NodeParameters reader_parameters("~relative_state_slip");
  acc::ParameterReader& reader = reader_parameters.reader;
  acc::RelativeStateSettings settings;
  EXPECT_FALSE(acc::loadRelativeStateSettings(reader, settings));
  EXPECT_TRUE(contains(reader.error(), "parameter ~timeout_s is the string \"1e6\"")) << reader.error();
  EXPECT_FALSE(acc::RelativeStateRos(ros::NodeHandle(), ros::NodeHandle("~relative_state_range")).ok());
}

TEST(NodeParameters, TheDriverRefusesAnIntegerForABoolAndExits)
{
  acc::GpsDriverRos driver(ros::NodeHandle("gps_slip"), ros::NodeHandle("~gps_driver_slip"));
  EXPECT_FALSE(driver.ok());
  EXPECT_EQ(driver.run(), 1);
}

TEST(NodeParameters, TheShippedConfigsReadWholeAndWithoutError)
{
  NodeParameters identifier_reader_parameters("~identifier_config");
  acc::ParameterReader& identifier_reader = identifier_reader_parameters.reader;
  acc::IdentifierSettings identifier;
  identifier.window_s = -1.0;  // to see that the file's value is read
  EXPECT_TRUE(acc::loadIdentifierSettings(identifier_reader, identifier)) << identifier_reader.error();
  EXPECT_GT(identifier.window_s, 0.0);
  EXPECT_EQ(identifier_reader.unreadNote(), "");
  EXPECT_EQ(acc::identifierSettingsNote(identifier), "");  // the shipped window can be fitted
  identifier.window_s = 0.5 * identifier.criteria.min_duration_s;
  EXPECT_TRUE(contains(acc::identifierSettingsNote(identifier), "is shorter than ~min_duration_s"))
      << acc::identifierSettingsNote(identifier);

  NodeParameters relative_reader_parameters("~relative_state_config");
  acc::ParameterReader& relative_reader = relative_reader_parameters.reader;
  acc::RelativeStateSettings relative;
  EXPECT_TRUE(acc::loadRelativeStateSettings(relative_reader, relative)) << relative_reader.error();
  // The node reads the rest (its own stale_after_s, queue_size, ...): built whole, nothing is left unread.
  acc::RelativeStateRos relative_node(ros::NodeHandle("relative_config"), ros::NodeHandle("~relative_state_config"));
  EXPECT_TRUE(relative_node.ok());
  EXPECT_EQ(relative_node.unreadParameters(), "");

  acc::GpsDriverRos driver(ros::NodeHandle("gps_config"), ros::NodeHandle("~gps_driver_config"));
  EXPECT_TRUE(driver.ok());
  EXPECT_EQ(driver.unreadParameters(), "");
}
}  // namespace

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  ros::init(argc, argv, "node_parameters_check");
  return RUN_ALL_TESTS();
}
