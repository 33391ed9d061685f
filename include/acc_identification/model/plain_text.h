#pragma once

#include <string>
#include <vector>

namespace acc
{
/// Lists and letter case in the package's texts (notes, reasons, names).

/// The parts with `separator` between them ("a, b, c"; "" for none).
std::string join(const std::vector<std::string>& parts, const std::string& separator);

/// The text in capitals (ASCII letters; "min" -> "MIN"), for names matched in any case.
std::string upperCase(std::string text);

/// Natural order: digit runs compare as numbers, so dynamic_part5 comes before dynamic_part12 (and
/// "part5 Hyundai#2" before "part5 Hyundai#10"). The order the tools put files and runs in.
bool naturalLess(const std::string& a, const std::string& b);
}  // namespace acc
