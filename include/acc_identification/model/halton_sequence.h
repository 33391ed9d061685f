#pragma once

#include <cstddef>
#include <vector>

namespace acc
{
/// The index-th point (index >= 1) of the Halton sequence in the first `dimensions` prime bases
/// (2, 3, 5, 7, 11, 13, 17, 19; at most 8), in [0, 1)^dimensions: low-discrepancy starting points
/// for every multistart search of the package (the paper's 100 random starts, spread evenly).
std::vector<double> haltonSequencePoint(std::size_t index, std::size_t dimensions);

}  // namespace acc
