#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "acc_identification/calibration/sliding_window.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// How much of the drive so far the identifier keeps, and what it lets go of first.
struct DriveBound
{
  /// At most this many samples are kept (36,000: an hour at 10 Hz, about 1.2 MB of samples); 0
  /// keeps every sample (unbounded memory and a period cost growing with the drive).
  std::size_t max_samples = 36000;
  /// The drive is let go of in whole blocks of this length [s], aligned on multiples of it in
  /// the data's own time, so the kept data stay long pieces that a simulation can follow.
  double block_s = 60.0;
  /// Blocks are grouped by their mean follower speed into bands this wide [m/s].
  double speed_band_mps = 2.0;
};

/// A block of the drive as the bound sees it.
struct DriveBlock
{
  std::size_t first = 0;  ///< index of its first sample in the drive
  std::size_t count = 0;  ///< samples, split points included
  double mean_speed_mps = 0.0;
  double speed_std_mps = 0.0;  ///< of the follower, over its valid samples: how much it excites the model
};

/// The drive's blocks, oldest first, the newest (still filling) left out: it is never let go of.
std::vector<DriveBlock> driveBlocks(const std::deque<WindowSample>& samples, const DriveBound& bound);

/// Which block to let go of: from the speed band holding the most blocks (ties: the slowest
/// band), the block whose follower speed varies least (ties: the oldest). So the kept drive keeps
/// covering every speed band it has seen, which is what separates tau_e from eta (the equilibrium
/// gap eta + tau_e v is pinned at each speed the drive holds), and within a band its strongest
/// manoeuvres, which pin k1 and k2 and decide the stability verdict. Steady cruising at a speed
/// the drive has seen for a long time goes first. None when there is no block to let go of.
std::optional<DriveBlock> chooseBlockToLetGo(const std::vector<DriveBlock>& blocks, const DriveBound& bound);

/// The drive so far, bounded: a SlidingWindow that never slides (so it takes the same decisions
/// on faults in time as the sliding window), which lets go of whole blocks by chooseBlockToLetGo
/// once it holds more than max_samples (it may then hold up to one block more: the newest block
/// is never let go of). What it let go of is counted, never silent.
class DriveRecord
{
public:
  /// The time-fault settings are SlidingWindow's, with its defaults.
  DriveRecord(double max_gap_s, std::size_t min_segment_samples, double max_forward_jump_s = 30.0,
              std::size_t confirm_samples = 5, DriveBound bound = {});

  /// Adds a sample as SlidingWindow::add does, then lets go of blocks while over the bound.
  SlidingWindow::AddResult add(const WindowSample& sample);

  /// Starts a new drive with the next sample (the ACC's setting changed): the kept samples go,
  /// the totals over every drive stay.
  void restart();

  std::vector<CarFollowingRun> segments() const { return samples_.segments(); }
  std::size_t size() const { return samples_.size(); }
  double startTimeS() const { return samples_.startTimeS(); }
  const SlidingWindow& window() const { return samples_; }
  const DriveBound& bound() const { return bound_; }

  /// Samples taken into this drive since it began (since the last confirmed jump back): grows
  /// with the drive while size() stays bounded.
  std::uint64_t samplesTaken() const { return taken_; }
  /// Samples let go of in this drive (the kept ones are size()).
  std::uint64_t samplesLetGoThisDrive() const { return let_go_this_drive_; }
  /// Since construction, over every drive.
  std::uint64_t samplesLetGo() const { return samples_let_go_; }
  std::uint64_t blocksLetGo() const { return blocks_let_go_; }

private:
  void keepWithinBound();

  DriveBound bound_;
  SlidingWindow samples_;
  std::uint64_t taken_ = 0;
  std::uint64_t let_go_this_drive_ = 0;
  std::uint64_t samples_let_go_ = 0;
  std::uint64_t blocks_let_go_ = 0;
};

}  // namespace acc
