#include "acc_identification/relative_state/clock_reset_rule.h"

#include <algorithm>
#include <cmath>

namespace acc
{
ClockResetRule::ClockResetRule(double time_reset_s, std::size_t confirm_fixes)
  : time_reset_s_(time_reset_s), confirm_fixes_(std::max<std::size_t>(1, confirm_fixes))
{
}

ClockResetRule::Step ClockResetRule::next(double time_s, double newest_s)
{
  Step step;
  const bool jumped_back = std::isfinite(newest_s) && time_s < newest_s - time_reset_s_;
  const bool jumped = jumped_back || (std::isfinite(newest_s) && time_s > newest_s + time_reset_s_);
  // Back on the stream's clock, or a held run this fix does not continue: what was held was no clock.
  // (Within time_reset_s of the newest held, so that the held fixes, let go in order once
  // confirmed, make one reset and not a second among themselves.)
  if (held_ > 0 && (!jumped || std::abs(time_s - held_newest_s_) > time_reset_s_))
  {
    step.stray = held_;
    held_ = 0;
  }
  if (!jumped)
    return step;
  held_newest_s_ = held_ == 0 ? time_s : std::max(held_newest_s_, time_s);
  ++held_;
  if (held_ < confirm_fixes_)
  {
    step.held = true;
    return step;
  }
  step.released = true;
  step.new_clock = jumped_back;
  held_ = 0;
  return step;
}

std::size_t ClockResetRule::endOfStream()
{
  const std::size_t stray = held_;
  held_ = 0;
  return stray;
}

}  // namespace acc
