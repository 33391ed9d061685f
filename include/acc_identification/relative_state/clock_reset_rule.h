#pragma once

#include <cstddef>
#include <limits>

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
class ClockResetRule
{
public:
  ClockResetRule(double time_reset_s, std::size_t confirm_fixes);

  /// What one fix does.
  struct Step
  {
    /// Fixes held before this one that are stray stamps: every fix held so far (let go, counted).
    std::size_t stray = 0;
    /// The fix is held, awaiting its clock's confirmation.
    bool held = false;
    /// The fix confirms the held ones' clock: they, this one the last, go on in order. A new clock
    /// (a reset) when they lie behind the stream's newest time (`new_clock`), the stream's own after
    /// a long dropout when ahead.
    bool released = false;
    bool new_clock = false;
  };

  /// The next usable fix of the stream, stamped time_s, the stream's newest time being newest_s
  /// (NaN before any).
  Step next(double time_s, double newest_s);

  /// The stream ends: the fixes still held (returned) are stray stamps, fewer than confirm a clock.
  std::size_t endOfStream();

  /// Fixes held now, awaiting confirmation.
  std::size_t held() const { return held_; }

private:
  double time_reset_s_;
  std::size_t confirm_fixes_;
  std::size_t held_ = 0;
  double held_newest_s_ = std::numeric_limits<double>::quiet_NaN();  ///< the newest of the held fixes' times
};

}  // namespace acc
