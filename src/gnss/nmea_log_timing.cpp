#include "acc_identification/gnss/nmea_log_timing.h"

#include <cmath>
#include <fstream>
#include <optional>

#include "acc_identification/gnss/nmea_parser.h"
#include "acc_identification/gnss/utc_date.h"

namespace acc
{
namespace
{
constexpr double kHalfDay_s = 0.5 * kSecondsPerDay;
// Lines whose times of day differ by less than this belong to the same epoch.
constexpr double kSameEpoch_s = 1e-6;

struct RawLine
{
  std::string text;
  std::optional<double> time_of_day_s;
  std::optional<std::int64_t> day;
};

std::optional<std::int64_t> dayIn(const std::string& line)
{
  NmeaSentence sentence;
  if (parseNmeaSentence(line, sentence) == NmeaParseOutcome::kOk && sentence.day)
    return sentence.day;
  return std::nullopt;
}

/// The day of a line sent before the first dated one (first_day at first_time_of_day_s).
std::int64_t dayBeforeFirstDate(double time_of_day_s, std::int64_t first_day, double first_time_of_day_s)
{
  if (time_of_day_s > first_time_of_day_s + kHalfDay_s)
    return first_day - 1;  // the log started before midnight
  if (time_of_day_s < first_time_of_day_s - kHalfDay_s)
    return first_day + 1;
  return first_day;
}
}  // namespace

TimedNmeaLog readTimedNmeaLog(const std::string& path, const NmeaLineTiming& timing)
{
  TimedNmeaLog log;
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    log.error = "cannot read " + path;
    return log;
  }
  std::vector<RawLine> raw;
  std::optional<std::size_t> first_dated;
  std::size_t without_checksum = 0;
  for (std::string text; std::getline(in, text);)
  {
    while (!text.empty() && (text.back() == '\r' || text.back() == '\n'))
      text.pop_back();
    if (text.empty())
      continue;
    without_checksum += lacksChecksumField(text) ? 1 : 0;
    RawLine line{text, std::nullopt, std::nullopt};
    double time_of_day_s = 0.0;
    if (nmeaLineTimeOfDay(text, time_of_day_s))
    {
      line.time_of_day_s = time_of_day_s;
      line.day = dayIn(text);
      if (line.day && !first_dated)
        first_dated = raw.size();
    }
    raw.push_back(std::move(line));
  }
  if (!first_dated)
  {
    log.error = path + ": no line carries a date (RMC or ZDA), so the lines cannot be given UTC times";
    if (without_checksum > 0)
      log.error += " (" + std::to_string(without_checksum) + " of its " + std::to_string(raw.size()) +
                   " lines have no checksum *hh, which every sentence needs here)";
    return log;
  }

  UtcDateTracker tracker;
  const RawLine& first = raw[*first_dated];
  std::optional<double> previous_stamp_s;
  std::optional<double> epoch_time_of_day_s;
  int index_in_epoch = 0;
  for (std::size_t i = 0; i < raw.size(); ++i)
  {
    const RawLine& line = raw[i];
    if (!line.time_of_day_s)
    {
      ++log.untimed_lines;
      log.lines.push_back({previous_stamp_s ? *previous_stamp_s + timing.sentence_spacing_s : std::nan(""), line.text});
      if (previous_stamp_s)
        previous_stamp_s = log.lines.back().receive_time_s;
      continue;
    }
    std::optional<std::int64_t> day = tracker.dayOf(*line.time_of_day_s, line.day);
    if (!day)
      day = dayBeforeFirstDate(*line.time_of_day_s, *first.day, *first.time_of_day_s);
    const bool same_epoch = epoch_time_of_day_s && std::abs(*epoch_time_of_day_s - *line.time_of_day_s) < kSameEpoch_s;
    index_in_epoch = same_epoch ? index_in_epoch + 1 : 0;
    epoch_time_of_day_s = *line.time_of_day_s;
    const double stamp_s = static_cast<double>(*day) * kSecondsPerDay + *line.time_of_day_s +
                           timing.first_sentence_latency_s + index_in_epoch * timing.sentence_spacing_s;
    log.lines.push_back({stamp_s, line.text});
    previous_stamp_s = stamp_s;
  }
  // Untimed lines before the first timed one arrive with it.
  for (TimedNmeaLine& line : log.lines)
  {
    if (!std::isnan(line.receive_time_s))
      break;
    for (const TimedNmeaLine& later : log.lines)
      if (!std::isnan(later.receive_time_s))
      {
        line.receive_time_s = later.receive_time_s;
        break;
      }
  }
  return log;
}

}  // namespace acc
