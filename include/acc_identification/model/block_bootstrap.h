#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace acc
{
/// Where a block of L samples may start in a segment of n.
enum class BlockPlacement
{
  /// In [0, n - L]: a block never leaves its segment (Kuensch 1989). Samples near the segment's
  /// ends are drawn less often, so E*[mean*] differs from the mean there.
  within_segment,
  /// In [0, n): a block wraps round its segment's end (Politis and Romano 1992), so every sample
  /// is drawn equally often and E*[mean*] is the mean itself.
  circular,
};

/// Moving-block bootstrap of the mean of a series made of independent segments (e.g. the held-out
/// halves of several runs), for series whose terms are correlated in time: the package's one
/// engine for it (the string-stability tests centre its replicates; the diagnosis's selection
/// rule reads percentile bounds from them).
///
/// Each replicate rebuilds every segment of n samples from ceil(n / L) blocks of L consecutive
/// samples of that same segment (L = min(block length, n)), whose starts are drawn uniformly as the
/// placement says; the last block is cut so that the segment keeps its n samples. Blocks never
/// take samples of another segment. The draws are made once (seeded, std::mt19937_64 with our own
/// integer mapping, so the same seed gives the same draws with every standard library), replicate
/// after replicate, segment after segment, and reused for every series given: the tests of
/// several series are then paired.
class MovingBlockBootstrap
{
public:
  MovingBlockBootstrap(std::vector<std::size_t> segment_lengths, std::size_t block_length_samples,
                       std::size_t replicates, std::uint64_t seed,
                       BlockPlacement placement = BlockPlacement::within_segment);

  std::size_t replicates() const { return replicates_; }
  std::size_t samples() const { return samples_; }
  /// Blocks per replicate, over all segments.
  std::size_t blocksPerReplicate() const { return blocks_per_replicate_; }

  /// The replicates mean*_b of the series x (all segments concatenated in order; x.size() must
  /// equal samples()); 0 for every replicate of an empty plan.
  std::vector<double> replicateMeans(const std::vector<double>& x) const;
  /// The same centred on their exact bootstrap expectation E*[mean*], so that they sample the null
  /// distribution of mean - E[mean].
  std::vector<double> centredReplicates(const std::vector<double>& x) const;

  /// p-value of H0: E[x] <= 0 against E[x] > 0: (1 + #{b: T*_b >= mean(x)}) / (B + 1).
  double pValueMeanPositive(const std::vector<double>& x) const;
  /// p-value of H0: E[x] >= 0 against E[x] < 0: (1 + #{b: T*_b <= mean(x)}) / (B + 1).
  double pValueMeanNegative(const std::vector<double>& x) const;

private:
  struct Segment
  {
    std::size_t offset = 0;
    std::size_t length = 0;
    std::size_t block = 0;       ///< block length used in this segment
    std::size_t full_blocks = 0; ///< blocks of full length per replicate
    std::size_t last_block = 0;  ///< length of the cut last block (0: none)
  };
  /// A segment's block sums, computed once per series (block_bootstrap.cpp).
  struct SegmentSums;
  /// Every segment's sums of x, after checking x's length against the plan.
  std::vector<SegmentSums> sumsOf(const std::vector<double>& x) const;
  /// The replicates' means from those sums.
  std::vector<double> meansFrom(const std::vector<double>& x, const std::vector<SegmentSums>& sums) const;
  /// E*[mean*] of x under this plan's placement, from the same sums.
  double expectedMean(const std::vector<double>& x, const std::vector<SegmentSums>& sums) const;

  BlockPlacement placement_;
  std::vector<Segment> segments_;
  std::size_t replicates_ = 0;
  std::size_t samples_ = 0;
  std::size_t blocks_per_replicate_ = 0;
  /// Block starts, replicate after replicate, segment after segment, block after block.
  std::vector<std::uint32_t> starts_;
};

}  // namespace acc
