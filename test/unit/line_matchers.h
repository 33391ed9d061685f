#pragma once

// Matching the notes and problems the package writes, for the unit tests.

#include <string>
#include <vector>

namespace acc_test
{
/// Whether some line of lines contains every part.
inline bool anyContains(const std::vector<std::string>& lines, const std::vector<std::string>& parts)
{
  for (const std::string& line : lines)
  {
    bool all = true;
    for (const std::string& part : parts)
      all = all && line.find(part) != std::string::npos;
    if (all)
      return true;
  }
  return false;
}
}  // namespace acc_test
