#include "acc_identification/model/block_bootstrap.h"
#include "acc_identification/model/sample_statistics.h"

#include <algorithm>
#include <random>
#include <stdexcept>
#include <utility>

#include "acc_identification/model/portable_uniform.h"

namespace acc
{
namespace
{
/// prefix[i] = x[offset] + ... + x[offset + i - 1].
std::vector<double> prefixSums(const std::vector<double>& x, std::size_t offset, std::size_t length)
{
  std::vector<double> prefix(length + 1, 0.0);
  for (std::size_t i = 0; i < length; ++i)
  {
    prefix[i + 1] = prefix[i] + x[offset + i];
  }
  return prefix;
}
}  // namespace

MovingBlockBootstrap::MovingBlockBootstrap(std::vector<std::size_t> segment_lengths, std::size_t block_length_samples,
                                           std::size_t replicates, std::uint64_t seed, BlockPlacement placement)
  : placement_(placement), replicates_(replicates)
{
  if (block_length_samples == 0)
  {
    throw std::invalid_argument("moving-block bootstrap: the block length must be at least one sample");
  }
  for (std::size_t length : segment_lengths)
  {
    if (length == 0)
    {
      continue;
    }
    Segment segment;
    segment.offset = samples_;
    segment.length = length;
    segment.block = std::min(block_length_samples, length);
    segment.full_blocks = length / segment.block;
    segment.last_block = length % segment.block;
    blocks_per_replicate_ += segment.full_blocks + (segment.last_block > 0 ? 1 : 0);
    samples_ += length;
    segments_.push_back(segment);
  }
  std::mt19937_64 engine(seed);
  starts_.reserve(replicates_ * blocks_per_replicate_);
  for (std::size_t b = 0; b < replicates_; ++b)
  {
    for (const Segment& segment : segments_)
    {
      const std::size_t blocks = segment.full_blocks + (segment.last_block > 0 ? 1 : 0);
      const std::size_t positions =
          placement_ == BlockPlacement::circular ? segment.length : segment.length - segment.block + 1;
      for (std::size_t j = 0; j < blocks; ++j)
      {
        starts_.push_back(static_cast<std::uint32_t>(uniformBelow(engine, positions)));
      }
    }
  }
}

/// A segment's block sums: every full block's by its start (computed once, so that a replicate
/// adds one number per drawn block), and the prefix sums a cut block within the segment reads.
struct MovingBlockBootstrap::SegmentSums
{
  std::vector<double> full_by_start;
  std::vector<double> prefix;
};

std::vector<MovingBlockBootstrap::SegmentSums> MovingBlockBootstrap::sumsOf(const std::vector<double>& x) const
{
  if (x.size() != samples_)
  {
    throw std::invalid_argument("moving-block bootstrap: series length differs from the plan's");
  }
  std::vector<SegmentSums> all;
  for (const Segment& segment : segments_)
  {
    SegmentSums sums;
    if (placement_ == BlockPlacement::within_segment)
    {
      sums.prefix = prefixSums(x, segment.offset, segment.length);
      for (std::size_t s = 0; s + segment.block <= segment.length; ++s)
        sums.full_by_start.push_back(sums.prefix[s + segment.block] - sums.prefix[s]);
    }
    else
    {
      sums.full_by_start.assign(segment.length, 0.0);
      for (std::size_t s = 0; s < segment.length; ++s)
      {
        for (std::size_t i = 0; i < segment.block; ++i)
          sums.full_by_start[s] += x[segment.offset + (s + i) % segment.length];
      }
    }
    all.push_back(std::move(sums));
  }
  return all;
}

std::vector<double> MovingBlockBootstrap::meansFrom(const std::vector<double>& x,
                                                    const std::vector<SegmentSums>& sums) const
{
  std::vector<double> result(replicates_, 0.0);
  if (samples_ == 0)
  {
    return result;
  }
  const double n = static_cast<double>(samples_);
  std::size_t k = 0;
  for (std::size_t b = 0; b < replicates_; ++b)
  {
    double total = 0.0;
    for (std::size_t s = 0; s < segments_.size(); ++s)
    {
      const Segment& segment = segments_[s];
      for (std::size_t j = 0; j < segment.full_blocks; ++j)
      {
        total += sums[s].full_by_start[starts_[k++]];
      }
      if (segment.last_block == 0)
        continue;
      const std::uint32_t start = starts_[k++];
      if (placement_ == BlockPlacement::within_segment)
      {
        total += sums[s].prefix[start + segment.last_block] - sums[s].prefix[start];
        continue;
      }
      for (std::size_t i = 0; i < segment.last_block; ++i)
        total += x[segment.offset + (start + i) % segment.length];
    }
    result[b] = total / n;
  }
  return result;
}

std::vector<double> MovingBlockBootstrap::replicateMeans(const std::vector<double>& x) const
{
  return meansFrom(x, sumsOf(x));
}

double MovingBlockBootstrap::expectedMean(const std::vector<double>& x, const std::vector<SegmentSums>& sums) const
{
  if (placement_ == BlockPlacement::circular)
  {
    return meanOf(x);  // every sample is drawn equally often
  }
  double expected_total = 0.0;
  for (std::size_t k = 0; k < segments_.size(); ++k)
  {
    const Segment& segment = segments_[k];
    const std::vector<double>& prefix = sums[k].prefix;
    // E* of a block's sum: the mean over all admissible starts, for the full and the cut block.
    const std::size_t positions = segment.length - segment.block + 1;
    double full = 0.0, cut = 0.0;
    for (std::size_t s = 0; s < positions; ++s)
    {
      full += sums[k].full_by_start[s];
      cut += prefix[s + segment.last_block] - prefix[s];
    }
    expected_total += (static_cast<double>(segment.full_blocks) * full + cut) / static_cast<double>(positions);
  }
  return expected_total / static_cast<double>(samples_);
}

std::vector<double> MovingBlockBootstrap::centredReplicates(const std::vector<double>& x) const
{
  const std::vector<SegmentSums> sums = sumsOf(x);
  std::vector<double> result = meansFrom(x, sums);
  if (samples_ == 0)
  {
    return result;
  }
  const double expected_mean = expectedMean(x, sums);
  for (double& mean : result)
  {
    mean -= expected_mean;
  }
  return result;
}

double MovingBlockBootstrap::pValueMeanPositive(const std::vector<double>& x) const
{
  const double observed = meanOf(x);
  std::size_t at_least = 0;
  for (double t : centredReplicates(x))
  {
    at_least += t >= observed ? 1 : 0;
  }
  return static_cast<double>(1 + at_least) / static_cast<double>(1 + replicates_);
}

double MovingBlockBootstrap::pValueMeanNegative(const std::vector<double>& x) const
{
  const double observed = meanOf(x);
  std::size_t at_most = 0;
  for (double t : centredReplicates(x))
  {
    at_most += t <= observed ? 1 : 0;
  }
  return static_cast<double>(1 + at_most) / static_cast<double>(1 + replicates_);
}

}  // namespace acc
