#pragma once

#include <cstdint>
#include <optional>

namespace acc
{
constexpr double kSecondsPerDay = 86400.0;

/// NMEA writes two-digit years; readers take 80-99 as 19xx and 00-79 as 20xx (the GPS era), so
/// only the years from kNmeaFirstYear to kNmeaFirstYear + 99 survive a log.
constexpr int kNmeaFirstYear = 1980;
/// The year of an NMEA two-digit year yy (0-99).
constexpr int nmeaYear(int yy) { return yy < kNmeaFirstYear % 100 ? 2000 + yy : 1900 + yy; }

/// Days since 1970-01-01 of a proleptic Gregorian date (H. Hinnant's days_from_civil).
std::int64_t daysFromCivil(int year, unsigned month, unsigned day);
/// True when day exists in that month of that year.
bool isValidDate(int year, unsigned month, unsigned day);

/// Gives each epoch its UTC day. NMEA sends the time of day in every sentence but the date only in
/// RMC and ZDA, so the day of an epoch without a date is carried forward from the last epoch
/// that had one:
/// - before any date is known the day is unknown (the fix then carries time of day only);
/// - when the time of day jumps back by more than half a day, midnight was crossed: day + 1
///   (and a jump forward by more than half a day is a late sentence of the day before);
/// - a date that lags the rollover (same day as before although the time of day wrapped, as
///   some receivers do for one sentence after midnight) is corrected to day + 1 and counted.
class UtcDateTracker
{
public:
  /// The day of an epoch at time_of_day_s; sentence_day is the date the epoch itself carried.
  std::optional<std::int64_t> dayOf(double time_of_day_s, std::optional<std::int64_t> sentence_day);
  std::uint64_t lagCorrections() const { return lag_corrections_; }
  /// The time of an epoch that has no day (no date known yet): its time of day plus a day for each
  /// midnight passed since the first such epoch, by the same half-day rule, so that the time of a
  /// log without dates (GGA and VTG only) keeps increasing over midnight instead of jumping back
  /// a day, which the pairing would take for a receiver reset.
  double undatedTimeS(double time_of_day_s);

private:
  std::optional<std::int64_t> known_day_;
  double known_time_of_day_s_ = 0.0;
  std::uint64_t lag_corrections_ = 0;
  std::optional<double> undated_time_of_day_s_;  ///< the last undated epoch's
  std::int64_t undated_days_ = 0;                ///< midnights passed since the first undated epoch
};

}  // namespace acc
