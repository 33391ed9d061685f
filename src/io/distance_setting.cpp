#include "acc_identification/io/distance_setting.h"

#include <map>

#include "acc_identification/model/plain_text.h"

namespace acc
{
std::string distanceSettingLetter(const std::string& word)
{
  static const std::map<std::string, std::string> kLetterOf = {
      {"S", "S"},      {"SHORT", "S"},  {"SHORTEST", "S"}, {"MIN", "S"},    {"MINIMUM", "S"},
      {"M", "M"},      {"MEDIUM", "M"}, {"MID", "M"},      {"MIDDLE", "M"}, {"L", "L"},
      {"LONG", "L"},   {"LONGEST", "L"}, {"MAX", "L"},     {"MAXIMUM", "L"},
  };
  const auto found = kLetterOf.find(upperCase(word));
  return found == kLetterOf.end() ? "" : found->second;
}

std::string describeDistanceSetting(const std::string& letter)
{
  if (letter == "S")
    return "the shortest setting";
  if (letter == "M")
    return "a middle setting";
  if (letter == "L")
    return "the longest setting";
  return "";
}

}  // namespace acc
