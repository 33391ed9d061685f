#pragma once

#include <cstddef>
#include <deque>
#include <string>
#include <vector>

#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// One relative-state sample as the identifier receives it.
struct WindowSample
{
  double time_s = 0.0;
  double space_gap_m = 0.0;
  double follower_speed_mps = 0.0;
  double leader_speed_mps = 0.0;
  bool valid = true;  ///< false: the pairing marked it invalid; it splits the window, never used
};

/// The identifier's sliding window: the last length_s seconds of samples, split into segments
/// wherever the data has a hole (an invalid sample, or more than max_gap_s between samples), so
/// that each segment is simulated from its own measured start.
class SlidingWindow
{
public:
  enum class AddResult
  {
    kAdded,
    kInvalid,      ///< stored as a split point
    kNonFinite,    ///< marked valid but with a non-finite value: stored as a split point
    kOutOfOrder,   ///< not after the newest sample (duplicate or late): rejected
    kRestarted,    ///< time jumped back by more than max_gap_s (bag loop, clock reset): window cleared
  };

  SlidingWindow(double length_s, double max_gap_s, std::size_t min_segment_samples);

  AddResult add(const WindowSample& sample);
  void clear() { samples_.clear(); }

  /// Usable segments, oldest first; pieces shorter than min_segment_samples are left out (they
  /// carry no dynamics) and counted in short_pieces.
  std::vector<CarFollowingRun> segments(std::size_t* short_pieces = nullptr) const;

  std::size_t size() const { return samples_.size(); }
  bool empty() const { return samples_.empty(); }
  double startTimeS() const { return samples_.empty() ? 0.0 : samples_.front().time_s; }
  double endTimeS() const { return samples_.empty() ? 0.0 : samples_.back().time_s; }
  double lengthS() const { return length_s_; }

  static std::string describe(AddResult result);

private:
  double length_s_;
  double max_gap_s_;
  std::size_t min_segment_samples_;
  std::deque<WindowSample> samples_;
};

}  // namespace acc
