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
  /// Not used, and already counted by the caller for why (the ACC was off, a value implausible): the
  /// window counts no rejection of it, so that every sample is counted once, for its first reason.
  bool counted = false;
};

/// The identifier's sliding window: the last length_s seconds of samples, split into segments
/// wherever the data has a hole (an invalid sample, or more than max_gap_s between samples), so
/// that each segment is simulated from its own measured start.
///
/// A jump in time (more than max_gap_s back, or more than max_forward_jump_s ahead) is held until
/// confirm_samples consistent samples confirm the new time base: then the window restarts (back:
/// a bag loop, a clock reset) or moves on (ahead: the data resume after a long outage). Should the
/// old time base go on instead, the held samples were outliers: dropped and counted. So one bad
/// stamp, in the past or in the future, never empties the window. A sample at most max_gap_s
/// back (late, or a duplicate) is rejected and counted. "Consistent": each held sample is newer
/// than the one held before it, by at most max_gap_s.
class SlidingWindow
{
public:
  /// Every sample the window did not take (but those the caller had counted), and every jump it
  /// confirmed, since construction.
  struct Counts
  {
    std::size_t out_of_order = 0;      ///< at most max_gap_s back (late or duplicate): rejected
    std::size_t time_outliers = 0;     ///< held after a jump, then dropped: the old time base went on
    std::size_t non_finite_times = 0;  ///< a NaN or infinite time: cannot be ordered, rejected
    std::size_t restarts = 0;          ///< confirmed jumps back: the window was cleared
    std::size_t jumps_ahead = 0;       ///< confirmed jumps ahead: older samples left the window
  };

  enum class AddResult
  {
    kAdded,
    kInvalid,      ///< stored as a split point
    kNonFinite,    ///< marked valid but with a non-finite value: stored as a split point
    kOutOfOrder,   ///< not after the newest sample (duplicate or late): rejected
    kRestarted,    ///< a jump back (bag loop, clock reset), now confirmed: window cleared, held samples added
    kHeld,         ///< a jump in time, held until consistent samples confirm it (or drop it)
    kJumpedAhead,  ///< a jump ahead, now confirmed: held samples added, older ones leave the window
  };

  SlidingWindow(double length_s, double max_gap_s, std::size_t min_segment_samples,
                double max_forward_jump_s = 30.0, std::size_t confirm_samples = 5);

  AddResult add(const WindowSample& sample);
  /// Empties the window, held samples included (the counts stay).
  void clear()
  {
    samples_.clear();
    held_.clear();
  }

  /// Usable segments, oldest first; pieces shorter than min_segment_samples are left out (they
  /// carry no dynamics) and counted in short_pieces.
  std::vector<CarFollowingRun> segments(std::size_t* short_pieces = nullptr) const;
  /// What short_pieces of segments() mean, for a note: "" for none; else how many pieces were not
  /// simulated and, when the samples' median step exceeds max_gap_s (a 1 Hz receiver against the
  /// default 0.5 s), that every step is a hole and max_gap_s must exceed the step.
  std::string describeShortPieces(std::size_t short_pieces) const;

  std::size_t size() const { return samples_.size(); }
  /// Samples that jumped in time and were dropped because the old time base went on.
  std::size_t droppedOutliers() const { return counts_.time_outliers; }
  const Counts& counts() const { return counts_; }
  /// Samples of a jump waiting for confirmation (neither in the window nor dropped yet).
  std::size_t heldSamples() const { return held_.size(); }
  std::size_t confirmSamples() const { return confirm_samples_; }
  bool empty() const { return samples_.empty(); }
  double startTimeS() const { return samples_.empty() ? 0.0 : samples_.front().time_s; }
  double endTimeS() const { return samples_.empty() ? 0.0 : samples_.back().time_s; }
  double lengthS() const { return length_s_; }
  /// The samples the window holds, oldest first (split points included).
  const std::deque<WindowSample>& samples() const { return samples_; }
  /// Lets go of count samples from index first on (never the newest sample, which the time-fault
  /// checks compare with). Used to bound a window that never slides (the drive so far): the
  /// samples either side are then further apart than max_gap_s, so they stay in separate segments
  /// without a split point (or, across a shorter stretch, with one). Returns by how many samples
  /// the window shrank.
  std::size_t letGo(std::size_t first, std::size_t count);

  static std::string describe(AddResult result);

private:
  double length_s_;
  double max_gap_s_;
  std::size_t min_segment_samples_;
  double max_forward_jump_s_;
  std::size_t confirm_samples_;
  std::deque<WindowSample> samples_;
  std::vector<WindowSample> held_;  ///< a jump waiting for confirmation
  Counts counts_;

  /// Appends a sample in time order (validity checked), dropping what left the window.
  AddResult append(const WindowSample& sample);
  /// Holds a sample that jumped; returns the outcome once held_ is confirmed.
  AddResult hold(const WindowSample& sample);
};

}  // namespace acc
