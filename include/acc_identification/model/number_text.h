#pragma once

#include <cstdio>
#include <string>

namespace acc
{
/// Numbers in the package's texts (reasons, notes, tables), written one way everywhere.

/// printf into a std::string: a reason or note, a sentence with its numbers, whole whatever its
/// length (it was cut at 255 characters, mid-word, without a sign).
template <typename... Args>
std::string printfText(const char* pattern, Args... args)
{
  const int length = std::snprintf(nullptr, 0, pattern, args...);
  if (length <= 0)
    return "";
  std::string text(static_cast<std::size_t>(length) + 1, '\0');
  std::snprintf(text.data(), text.size(), pattern, args...);
  text.resize(static_cast<std::size_t>(length));
  return text;
}

/// The value with `digits` significant digits, as "%.*g" (0.1235, 1.2e-05, 80): the numbers of
/// reasons and notes.
std::string significant(double value, int digits = 4);

/// A table cell: printfText(pattern, value), "inf" or "-inf" for an infinite value (an interval's
/// end the data do not bound), "NaN" for a value that is not available.
std::string cellNumber(const char* pattern, double value);

}  // namespace acc
