#include "acc_identification/gnss/utc_date.h"

namespace acc
{
std::int64_t daysFromCivil(int year, unsigned month, unsigned day)
{
  // Howard Hinnant, "chrono-Compatible Low-Level Date Algorithms": exact for every Gregorian date.
  const std::int64_t y = static_cast<std::int64_t>(year) - (month <= 2 ? 1 : 0);
  const std::int64_t era = (y >= 0 ? y : y - 399) / 400;
  const std::int64_t year_of_era = y - era * 400;
  const std::int64_t day_of_year = (153 * (month > 2 ? month - 3 : month + 9) + 2) / 5 + day - 1;
  const std::int64_t day_of_era = year_of_era * 365 + year_of_era / 4 - year_of_era / 100 + day_of_year;
  return era * 146097 + day_of_era - 719468;
}

bool isValidDate(int year, unsigned month, unsigned day)
{
  static constexpr unsigned kDays[] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
  if (month < 1 || month > 12 || day < 1)
    return false;
  const bool leap = (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
  return day <= kDays[month - 1] + (month == 2 && leap ? 1u : 0u);
}

std::optional<std::int64_t> UtcDateTracker::dayOf(double time_of_day_s, std::optional<std::int64_t> sentence_day)
{
  constexpr double kHalfDay = kSecondsPerDay / 2.0;
  std::optional<std::int64_t> day = sentence_day;
  if (known_day_)
  {
    std::int64_t carried = *known_day_;
    if (time_of_day_s < known_time_of_day_s_ - kHalfDay)
      carried += 1;
    else if (time_of_day_s > known_time_of_day_s_ + kHalfDay)
      carried -= 1;
    if (!day)
      day = carried;
    else if (*day == *known_day_ && carried == *known_day_ + 1)
    {
      day = carried;  // the receiver's date lagged the midnight rollover
      ++lag_corrections_;
    }
  }
  if (day)
  {
    known_day_ = day;
    known_time_of_day_s_ = time_of_day_s;
  }
  return day;
}

double UtcDateTracker::undatedTimeS(double time_of_day_s)
{
  constexpr double kHalfDay = kSecondsPerDay / 2.0;
  if (undated_time_of_day_s_)
  {
    if (time_of_day_s < *undated_time_of_day_s_ - kHalfDay)
      ++undated_days_;
    else if (time_of_day_s > *undated_time_of_day_s_ + kHalfDay)
      --undated_days_;  // a late sentence of the day before
  }
  undated_time_of_day_s_ = time_of_day_s;
  return static_cast<double>(undated_days_) * kSecondsPerDay + time_of_day_s;
}

}  // namespace acc
