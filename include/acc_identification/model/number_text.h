#pragma once

#include <cstdio>
#include <string>

namespace acc
{
/// Numbers in the package's texts (reasons, notes, tables), written one way everywhere.

/// printf into a std::string: every reason is a short sentence with its numbers (at most 255
/// characters).
template <typename... Args>
std::string printfText(const char* pattern, Args... args)
{
  char text[256];
  std::snprintf(text, sizeof text, pattern, args...);
  return text;
}

/// The value with `digits` significant digits, as "%.*g" (0.1235, 1.2e-05, 80): the numbers of
/// reasons and notes.
std::string significant(double value, int digits = 4);

/// A table cell: printfText(pattern, value), "inf" or "-inf" for an infinite value (an interval's
/// end the data do not bound), "NaN" for a value that is not available.
std::string cellNumber(const char* pattern, double value);

}  // namespace acc
