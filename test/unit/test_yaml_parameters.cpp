// A node's parameters from a YAML file (nmea_to_csv --params) must read as the node reads them
// from the parameter server: the values below are test/rostest/node_parameters.test's, and each
// read must give the value, or refuse with the message, that the rostest holds the node to.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "acc_identification/parameters/parameter_reader.h"
#include "acc_identification/parameters/yaml_parameter_source.h"
#include "parameter_refusals.h"

namespace
{
const char* const kValues = R"(
yaml_exponent: 1e6
signed_exponent: 1.0e+6
unsigned_exponent: 1.0e6
integer: 7
whole_double: 200.0
half: 2.5
flag: true
word: along_track
quoted_number: "12"
topics: [fix, vel]
mixed_list: [fix, 3]
negative: -1.0
not_a_number: .nan
nested: {max_gap_s: 2.5}
)";

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

/// The reader's error for one read of name into a value of type T (its default kept).
template <typename T>
std::string refusal(const std::string& name, T value)
{
  const acc::YamlParameterSource source = acc::YamlParameterSource::fromText(kValues, "values");
  acc::ParameterReader reader(source);
  const T before = value;
  EXPECT_FALSE(reader.read(name, value)) << name;
  EXPECT_EQ(value, before) << name;
  return reader.error();
}
}  // namespace

TEST(YamlParameters, NumbersOfEitherYamlTypeAreRead)
{
  const acc::YamlParameterSource source = acc::YamlParameterSource::fromText(kValues, "values");
  ASSERT_TRUE(source.ok()) << source.error();
  acc::ParameterReader reader(source);
  double signed_exponent = 0.0, integer = 0.0, not_a_number = 0.0;
  int whole = 0;
  std::vector<std::string> topics;
  EXPECT_TRUE(reader.read("signed_exponent", signed_exponent));
  EXPECT_TRUE(reader.read("integer", integer));
  EXPECT_TRUE(reader.read("whole_double", whole));
  EXPECT_TRUE(reader.read("not_a_number", not_a_number));
  EXPECT_TRUE(reader.read("topics", topics));
  EXPECT_EQ(signed_exponent, 1e6);
  EXPECT_EQ(integer, 7.0);
  EXPECT_EQ(whole, 200);
  EXPECT_TRUE(std::isnan(not_a_number));
  EXPECT_EQ(topics, (std::vector<std::string>{"fix", "vel"}));
  EXPECT_TRUE(reader.ok()) << reader.error();
}

TEST(YamlParameters, AnExponentWithoutDotAndSignIsTextAsToRosparam)
{
  EXPECT_TRUE(contains(refusal("yaml_exponent", 2.0), "parameter ~yaml_exponent is the string \"1e6\", not a number"));
  EXPECT_TRUE(contains(refusal("yaml_exponent", 2.0), "write 1000000 or 1.0e+6"));
  EXPECT_TRUE(contains(refusal("unsigned_exponent", 2.0), "the string \"1.0e6\", not a number"));
}

TEST(YamlParameters, EveryWrongTypeIsRefusedByNameAsTheNodeRefusesIt)
{
  expectEveryWrongTypeRefusedByName([](const std::string& name, auto value) { return refusal(name, value); });
  EXPECT_EQ(refusal("nested", 1.0), "parameter ~nested is a dictionary, not a number");
}

TEST(YamlParameters, RangesAreCheckedAndKeysNeverReadAreNamed)
{
  const acc::YamlParameterSource source = acc::YamlParameterSource::fromText("negative: -1.0\nwindow_s: 120\n", "f");
  acc::ParameterReader reader(source);
  double value = 1.0;
  EXPECT_FALSE(reader.readAbove("negative", value, 0.0));
  EXPECT_EQ(reader.error(), "parameter ~negative = -1 must be finite and > 0");
  EXPECT_EQ(reader.unreadNote(), "parameter ~window_s is set but never read (misspelt?): ignored");
}

// A key given twice takes its last value, as rosparam loads the file for the node, and is said:
// nmea_to_csv --params once used the last antenna offset without a word.
TEST(YamlParameters, AKeyGivenTwiceIsSaid)
{
  const acc::YamlParameterSource source =
      acc::YamlParameterSource::fromText("antenna_offset_m: 5.6\nqueue_size: 2\nantenna_offset_m: 6.1\n", "f");
  ASSERT_TRUE(source.ok()) << source.error();
  EXPECT_DOUBLE_EQ(source.get("antenna_offset_m")->number, 6.1);
  EXPECT_EQ(source.repeatedKeysNote(),
            "key(s) given more than once: antenna_offset_m (the last value of each is used, as rosparam loads it)");
  EXPECT_EQ(acc::YamlParameterSource::fromText("queue_size: 2\n", "f").repeatedKeysNote(), "");
}

// PyYAML's resolver, which rosparam uses: what each plain scalar becomes.
TEST(YamlParameters, PlainScalarsResolveAsYaml11)
{
  using Type = acc::ParameterValue::Type;
  const std::vector<std::pair<std::string, Type>> cases{
      {"yes", Type::kBool},   {"Off", Type::kBool},      {"TRUE", Type::kBool},    {"y", Type::kString},
      {"0", Type::kInt},      {"-12", Type::kInt},       {"0x1F", Type::kInt},     {"017", Type::kInt},
      {"1_000", Type::kInt},  {"1.5", Type::kDouble},    {"-.5", Type::kString},   {".5", Type::kDouble},
      {"1.", Type::kDouble},  {"1.0e+3", Type::kDouble}, {"1.0e3", Type::kString}, {"1e3", Type::kString},
      {"-.inf", Type::kDouble}, {".NaN", Type::kDouble}, {"~", Type::kNull},       {"null", Type::kNull},
      {"nan", Type::kString}, {"08", Type::kString},
  };
  for (const auto& [text, type] : cases)
    EXPECT_EQ(acc::resolveYamlScalar(text).type, type) << text;
  EXPECT_EQ(acc::resolveYamlScalar("017").integer, 15);
  EXPECT_EQ(acc::resolveYamlScalar("0x1F").integer, 31);
  EXPECT_EQ(acc::resolveYamlScalar("1_000").integer, 1000);
  EXPECT_TRUE(acc::resolveYamlScalar("on").boolean);
  EXPECT_FALSE(acc::resolveYamlScalar("No").boolean);
  EXPECT_EQ(acc::resolveYamlScalar("-.inf").number, -INFINITY);
}

// Base 60, as PyYAML 6 reads it (yaml.safe_load("a: 1:30") is {'a': 90}): a node given 1:30 s gets
// 90, so a tool reading the same file must too.
TEST(YamlParameters, BaseSixtyNumbersAreNumbersAsRosparamReadsThem)
{
  using Type = acc::ParameterValue::Type;
  EXPECT_EQ(acc::resolveYamlScalar("1:30").type, Type::kInt);
  EXPECT_EQ(acc::resolveYamlScalar("1:30").integer, 90);
  EXPECT_EQ(acc::resolveYamlScalar("190:20:30").integer, 685230);
  EXPECT_EQ(acc::resolveYamlScalar("1_0:30").integer, 630);
  EXPECT_EQ(acc::resolveYamlScalar("-1:30").integer, -90);
  EXPECT_EQ(acc::resolveYamlScalar("-1:30.5").type, Type::kDouble);
  EXPECT_EQ(acc::resolveYamlScalar("-1:30.5").number, -90.5);
  EXPECT_EQ(acc::resolveYamlScalar("+1:00.25").number, 60.25);
  for (const char* text : {"01:30", "1:60", "1::30"})
    EXPECT_EQ(acc::resolveYamlScalar(text).type, Type::kString) << text;
  const acc::YamlParameterSource file = acc::YamlParameterSource::fromText("window_s: 2:00\n", "w.yaml");
  ASSERT_TRUE(file.get("window_s").has_value());
  EXPECT_EQ(file.get("window_s")->integer, 120);
}

TEST(YamlParameters, AFileThatIsNoMappingOrNoYamlIsRefusedWithItsName)
{
  EXPECT_TRUE(contains(acc::YamlParameterSource::fromFile("/nonexistent/p.yaml").error(), "/nonexistent/p.yaml"));
  EXPECT_TRUE(contains(acc::YamlParameterSource::fromText("[1, 2]", "list.yaml").error(), "list.yaml: not a mapping"));
  EXPECT_TRUE(contains(acc::YamlParameterSource::fromText("a: [1, 2", "cut.yaml").error(), "cut.yaml: not YAML"));
  const acc::YamlParameterSource empty = acc::YamlParameterSource::fromText("# nothing set\n", "empty.yaml");
  EXPECT_TRUE(empty.ok());
  EXPECT_TRUE(empty.names().empty());
}
