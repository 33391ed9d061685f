#include "acc_identification/gnss/log_pacer.h"

#include <algorithm>

#include "acc_identification/gnss/nmea_parser.h"
#include "acc_identification/gnss/utc_date.h"

namespace acc
{
std::optional<double> LogPacer::dueOffsetS(const std::string& line)
{
  double time_of_day_s = 0.0;
  if (rate_ <= 0.0 || !nmeaLineTimeOfDay(line, time_of_day_s))
    return std::nullopt;
  double log_time_s = time_of_day_s + day_offset_s_;
  if (started_ && log_time_s < last_time_s_ - kSecondsPerDay / 2.0)  // midnight in the log
  {
    day_offset_s_ += kSecondsPerDay;
    log_time_s += kSecondsPerDay;
  }
  if (!started_)
  {
    started_ = true;
    log_start_s_ = log_time_s;
  }
  last_time_s_ = std::max(last_time_s_, log_time_s);
  return std::max(0.0, (log_time_s - log_start_s_) / rate_);
}

}  // namespace acc
