#include "acc_identification/calibration/drive_record.h"

#include <cmath>
#include <limits>
#include <map>

namespace acc
{
namespace
{
/// A block without a valid sample holds nothing the fit can use: it goes before any other.
constexpr double kEmptyBlockBand = -std::numeric_limits<double>::infinity();

std::int64_t blockIndex(double time_s, double block_s) { return static_cast<std::int64_t>(std::floor(time_s / block_s)); }

DriveBlock summarise(const std::deque<WindowSample>& samples, std::size_t first, std::size_t count)
{
  DriveBlock block{first, count, std::numeric_limits<double>::quiet_NaN(), 0.0};
  double mean = 0.0, squares = 0.0;
  std::size_t valid = 0;
  for (std::size_t i = first; i < first + count; ++i)
  {
    if (!samples[i].valid)
    {
      continue;
    }
    ++valid;  // Welford: a long block at highway speed loses no digits
    const double delta = samples[i].follower_speed_mps - mean;
    mean += delta / static_cast<double>(valid);
    squares += delta * (samples[i].follower_speed_mps - mean);
  }
  if (valid > 0)
  {
    block.mean_speed_mps = mean;
    block.speed_std_mps = valid > 1 ? std::sqrt(squares / static_cast<double>(valid - 1)) : 0.0;
  }
  return block;
}

double bandOf(const DriveBlock& block, double speed_band_mps)
{
  return std::isfinite(block.mean_speed_mps) ? std::floor(block.mean_speed_mps / speed_band_mps) : kEmptyBlockBand;
}
}  // namespace

std::vector<DriveBlock> driveBlocks(const std::deque<WindowSample>& samples, const DriveBound& bound)
{
  std::vector<DriveBlock> blocks;
  std::size_t first = 0;
  for (std::size_t i = 1; i <= samples.size(); ++i)
  {
    const bool ends = i == samples.size() ||
                      blockIndex(samples[i].time_s, bound.block_s) != blockIndex(samples[first].time_s, bound.block_s);
    if (ends)
    {
      blocks.push_back(summarise(samples, first, i - first));
      first = i;
    }
  }
  if (!blocks.empty())
  {
    blocks.pop_back();  // the newest block is still filling, and holds the newest sample
  }
  return blocks;
}

std::optional<DriveBlock> chooseBlockToLetGo(const std::vector<DriveBlock>& blocks, const DriveBound& bound)
{
  if (blocks.empty())
  {
    return std::nullopt;
  }
  std::map<double, std::size_t> blocks_per_band;  // ordered: ties go to the slowest band
  for (const DriveBlock& block : blocks)
  {
    ++blocks_per_band[bandOf(block, bound.speed_band_mps)];
  }
  // Blocks without data (the lowest key) go first, whatever the other bands hold.
  double fullest_band = blocks_per_band.begin()->first;
  std::size_t most = blocks_per_band.begin()->second;
  for (const auto& [band, count] : blocks_per_band)
  {
    if (fullest_band != kEmptyBlockBand && count > most)
    {
      fullest_band = band;
      most = count;
    }
  }
  const DriveBlock* chosen = nullptr;
  for (const DriveBlock& block : blocks)
  {
    if (bandOf(block, bound.speed_band_mps) == fullest_band &&
        (chosen == nullptr || block.speed_std_mps < chosen->speed_std_mps))
    {
      chosen = &block;  // strictly less: ties keep the oldest
    }
  }
  return *chosen;
}

DriveRecord::DriveRecord(double max_gap_s, std::size_t min_segment_samples, double max_forward_jump_s,
                         std::size_t confirm_samples, DriveBound bound)
  // A window that never slides (1e9 s is 31 years): the bound, not the length, limits it.
  : bound_(bound), samples_(1.0e9, max_gap_s, min_segment_samples, max_forward_jump_s, confirm_samples)
{
}

SlidingWindow::AddResult DriveRecord::add(const WindowSample& sample)
{
  const std::size_t before = samples_.size();
  const SlidingWindow::AddResult result = samples_.add(sample);
  if (result == SlidingWindow::AddResult::kRestarted)
  {
    taken_ = samples_.size();  // a new drive: what the confirmed jump brought
    let_go_this_drive_ = 0;
  }
  else if (samples_.size() > before)
  {
    taken_ += samples_.size() - before;
  }
  keepWithinBound();
  return result;
}

void DriveRecord::restart()
{
  samples_.clear();
  taken_ = 0;
  let_go_this_drive_ = 0;
}

void DriveRecord::keepWithinBound()
{
  if (bound_.max_samples == 0)
  {
    return;
  }
  while (samples_.size() > bound_.max_samples)
  {
    const std::optional<DriveBlock> block = chooseBlockToLetGo(driveBlocks(samples_.samples(), bound_), bound_);
    if (!block)
    {
      return;  // only the newest block is left: it stays
    }
    const std::size_t shrank = samples_.letGo(block->first, block->count);
    samples_let_go_ += shrank;
    let_go_this_drive_ += shrank;
    ++blocks_let_go_;
  }
}

}  // namespace acc
