#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace acc
{
/// Moving-block bootstrap (Kuensch 1989) of the mean of a series made of independent segments
/// (e.g. the held-out halves of several runs), for series whose terms are correlated in time.
///
/// Each replicate rebuilds every segment of n samples from ceil(n / L) blocks of L consecutive
/// samples of that same segment (L = min(block length, n)), whose starts are drawn uniformly from
/// [0, n - L]; the last block is cut so that the segment keeps its n samples. Blocks never straddle
/// segments. The draws are made once (seeded, std::mt19937_64 with our own integer mapping, so the
/// same seed gives the same draws with every standard library) and reused for every series given:
/// the tests of several series are then paired.
///
/// The replicates are centred on their exact bootstrap expectation E*[mean*] (which differs from
/// the sample mean near the ends of the segments), so that they sample the null distribution of
/// mean - E[mean].
class MovingBlockBootstrap
{
public:
  MovingBlockBootstrap(std::vector<std::size_t> segment_lengths, std::size_t block_length_samples,
                       std::size_t replicates, std::uint64_t seed);

  std::size_t replicates() const { return replicates_; }
  std::size_t samples() const { return samples_; }
  /// Blocks per replicate, over all segments.
  std::size_t blocksPerReplicate() const { return blocks_per_replicate_; }

  /// Centred replicates mean*_b - E*[mean*] of the series x (all segments concatenated in order;
  /// x.size() must equal samples()).
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
  std::vector<Segment> segments_;
  std::size_t replicates_ = 0;
  std::size_t samples_ = 0;
  std::size_t blocks_per_replicate_ = 0;
  /// Block starts, replicate after replicate, segment after segment, block after block.
  std::vector<std::uint32_t> starts_;
};

}  // namespace acc
