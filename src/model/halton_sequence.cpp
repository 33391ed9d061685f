#include "acc_identification/model/halton_sequence.h"

namespace acc
{
std::vector<double> haltonSequencePoint(std::size_t index, std::size_t dimensions)
{
  static const unsigned kPrimes[] = {2, 3, 5, 7, 11, 13, 17, 19};
  std::vector<double> point(dimensions, 0.0);
  for (std::size_t d = 0; d < dimensions && d < 8; ++d)
  {
    // The radical inverse of index in base kPrimes[d]: its digits mirrored behind the point.
    double fraction = 1.0;
    double value = 0.0;
    for (std::size_t i = index; i > 0; i /= kPrimes[d])
    {
      fraction /= kPrimes[d];
      value += fraction * static_cast<double>(i % kPrimes[d]);
    }
    point[d] = value;
  }
  return point;
}

}  // namespace acc
