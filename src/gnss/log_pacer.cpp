#include "acc_identification/gnss/log_pacer.h"

#include <algorithm>
#include <cmath>

#include "acc_identification/gnss/nmea_parser.h"
#include "acc_identification/gnss/utc_date.h"
#include "acc_identification/model/number_text.h"

namespace acc
{
namespace
{
/// A log time of day as hh:mm:ss.ss, for the description of a jump.
std::string clockText(double log_time_s)
{
  const double of_day = std::fmod(log_time_s, kSecondsPerDay);
  const int hours = static_cast<int>(of_day / 3600.0), minutes = static_cast<int>(std::fmod(of_day, 3600.0) / 60.0);
  return printfText("%02d:%02d:%05.2f", hours, minutes, std::fmod(of_day, 60.0));
}
}  // namespace

std::optional<double> LogPacer::dueOffsetS(const std::string& line)
{
  NmeaSentence sentence;  // parsed whole: a line whose checksum fails does not pace
  if (rate_ <= 0.0 || parseNmeaSentence(line, sentence) != NmeaParseOutcome::kOk ||
      std::isnan(sentence.time_of_day_s))
    return std::nullopt;
  double log_time_s = sentence.time_of_day_s + day_offset_s_;
  if (started_ && log_time_s < last_time_s_ - kSecondsPerDay / 2.0)  // midnight in the log
  {
    day_offset_s_ += kSecondsPerDay;
    log_time_s += kSecondsPerDay;
  }
  if (!started_)
  {
    started_ = true;
    anchor_log_s_ = last_time_s_ = log_time_s;
    return 0.0;
  }
  const double step_s = log_time_s - last_time_s_;
  if (step_s < -kBackwardToleranceS || step_s > kLongestWaitS)
  {
    ++clock_jumps_;
    last_clock_jump_ = clockText(last_time_s_) + " -> " + clockText(log_time_s);
    anchor_log_s_ = log_time_s;
    anchor_offset_s_ = last_offset_s_;
    last_time_s_ = log_time_s;
  }
  last_time_s_ = std::max(last_time_s_, log_time_s);
  last_offset_s_ = std::max(last_offset_s_, anchor_offset_s_ + (log_time_s - anchor_log_s_) / rate_);
  return last_offset_s_;
}

}  // namespace acc
