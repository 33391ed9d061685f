#pragma once

#include <string>
#include <vector>

namespace acc
{
/// The problems of a reader ("path:line: why", one per rejected row) as a person reads them:
/// consecutive lines of one file with the same reason become one entry, "path:79-170 (92 lines):
/// why". A file with a stretch of empty cells otherwise prints a warning per row, and the one
/// that matters drowns. Entries of another form, and lines that do not follow on, are kept as they
/// are and in their order, so nothing is lost: every line is still named by its range.
std::vector<std::string> condenseProblemLines(const std::vector<std::string>& problems);

}  // namespace acc
