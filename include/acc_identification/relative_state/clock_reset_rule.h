#pragma once

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <utility>
#include <vector>

namespace acc
{
/// Tells a receiver's clock reset from stray time stamps, fix by fix: the one rule the live
/// pairing (epoch_pairing.h) and the batch converter's split of a log into stretches on one clock
/// (nmea_logs_to_csv.h) follow, so that both see a reset at the same fix.
///
/// A fix stamped more than time_reset_s behind the stream's newest time, or ahead of it, is held.
/// When time_reset_confirm_fixes are held in a row, each within time_reset_s of the newest held
/// before it, the stream runs on their clock: behind, a new clock (a looped log, a receiver reset);
/// ahead, the same clock after a long dropout, the held fixes let go in order a few epochs late. A
/// fix back on the stream's clock ends the hold: what was held were stray stamps (a glitched or
/// corrupted time, one fix an hour ahead or behind), as is a held run that the next far-off fix
/// does not continue. Judges only the fixes the stream would use (a usable position,
/// hasUsablePosition); a fix without a finite time is on no clock and ends a hold like a fix on the
/// stream's. time_reset_s must exceed the stream's step (describePairingSettingsProblem).
///
/// It holds what its user gives with each fix (the fix itself live, its index in the log in batch)
/// and hands it back when the hold ends, stray or released.
template <typename Held>
class ClockResetRule
{
public:
  ClockResetRule(double time_reset_s, std::size_t confirm_fixes)
    : time_reset_s_(time_reset_s), confirm_fixes_(std::max<std::size_t>(1, confirm_fixes))
  {
  }

  /// What one fix does.
  struct Step
  {
    /// What was held before this fix, now known to be stray stamps: let go, counted.
    std::vector<Held> stray;
    /// The fix is held, awaiting its clock's confirmation.
    bool held = false;
    /// The fix confirmed the held ones' clock: they, this one the last, go on in order. A new clock
    /// (a reset, `new_clock`) when they lie behind the stream's newest time; the stream's own after
    /// a long dropout when ahead. Empty otherwise.
    std::vector<Held> released;
    bool new_clock = false;
  };

  /// The next usable fix of the stream, stamped time_s, the stream's newest time being newest_s
  /// (NaN before any); `item` is what is held for it.
  Step next(Held item, double time_s, double newest_s)
  {
    Step step;
    const bool behind = std::isfinite(newest_s) && time_s < newest_s - time_reset_s_;
    const bool far_off = behind || (std::isfinite(newest_s) && time_s > newest_s + time_reset_s_);
    // Back on the stream's clock, or a held run this fix does not continue: what was held was no
    // clock. (Within time_reset_s of the newest held, so that the held fixes, let go in order once
    // confirmed, make one reset and not a second among themselves.)
    if (!held_.empty() && (!far_off || std::abs(time_s - held_newest_s_) > time_reset_s_))
      step.stray.swap(held_);
    if (!far_off)
      return step;
    held_newest_s_ = held_.empty() ? time_s : std::max(held_newest_s_, time_s);
    held_.push_back(std::move(item));
    if (held_.size() < confirm_fixes_)
    {
      step.held = true;
      return step;
    }
    step.released.swap(held_);
    step.new_clock = behind;
    return step;
  }

  /// The stream ends: what is still held (returned) are stray stamps, fewer than confirm a clock.
  std::vector<Held> endOfStream()
  {
    std::vector<Held> stray;
    stray.swap(held_);
    return stray;
  }

  /// Fixes held now, awaiting confirmation.
  std::size_t held() const { return held_.size(); }

private:
  double time_reset_s_;
  std::size_t confirm_fixes_;
  std::vector<Held> held_;
  double held_newest_s_ = std::numeric_limits<double>::quiet_NaN();  ///< the newest of the held fixes' times
};

}  // namespace acc
