// relative_state_node's loader on the parameters users write: the antennas' place by the one rule
// nmea_to_csv and Python follow, so that the node never pairs with an offset the tool refuses.
#include <gtest/gtest.h>

#include <string>

#include "acc_identification/parameters/yaml_parameter_source.h"
#include "acc_identification/relative_state/relative_state_parameters.h"

namespace
{
/// The loader's error on YAML text ("" when it loads), the settings it set in settings.
std::string loadError(const std::string& yaml, acc::RelativeStateSettings& settings)
{
  const acc::YamlParameterSource source = acc::YamlParameterSource::fromText(yaml, "relative_state");
  acc::ParameterReader reader(source);
  return acc::loadRelativeStateSettings(reader, settings) ? "" : reader.error();
}

std::string loadError(const std::string& yaml)
{
  acc::RelativeStateSettings settings;
  return loadError(yaml, settings);
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }
}  // namespace

TEST(RelativeStateParameters, TheNodePlacesTheAntennasByTheOneRule)
{
  acc::RelativeStateSettings settings;
  ASSERT_EQ(loadError("antenna_offset_m: 5.6\n", settings), "");
  EXPECT_EQ(settings.geometry.combinedOffset(), 5.6);
  ASSERT_EQ(loadError("leader_antenna_to_rear_bumper_m: 2.0\nfollower_antenna_to_front_bumper_m: 3\n", settings), "");
  EXPECT_EQ(settings.geometry.leader_antenna_to_rear_bumper_m, 2.0);
  EXPECT_EQ(settings.geometry.follower_antenna_to_front_bumper_m, 3.0);

  // Before the one rule the node took a lone offset with the other at 0, and any offset above -1000 m.
  const std::string unplaced = loadError("timeout_s: 3.0\n");
  EXPECT_TRUE(contains(unplaced, "~antenna_offset_m")) << unplaced;
  EXPECT_TRUE(contains(unplaced, "say where the antennas are")) << unplaced;
  EXPECT_TRUE(contains(loadError("leader_antenna_to_rear_bumper_m: 2.0\n"), "go together"));
  EXPECT_TRUE(contains(loadError("antenna_offset_m: 5.6\nfollower_antenna_to_front_bumper_m: 2.0\n"), "not both"));
  EXPECT_TRUE(contains(loadError("antenna_offset_m: 5600.0\n"), "not between -1000 and 1000"));
  EXPECT_EQ(loadError("antenna_offset_m: .nan\n"), "parameter ~antenna_offset_m is NaN");
  EXPECT_TRUE(contains(loadError("antenna_offset_m: five\n"), "not a number"));
}

// A slip elsewhere is named before the antennas' place is judged: the first problem in the file.
TEST(RelativeStateParameters, AWrongTypeIsNamedBeforeTheAntennasPlace)
{
  const std::string error = loadError("timeout_s: 1e6\n");
  EXPECT_TRUE(contains(error, "~timeout_s is the string \"1e6\"")) << error;
}
