// Real receivers of many makes (gpsd's regression logs, see test/data/nmea_captures/ATTRIBUTION.md)
// through the driver's receive path, compared with gpsd's own decoding of the same sentences.
//
// Each capture is X.nmea (raw receiver output) with X.chk (gpsd's output: every sentence it
// accepted, echoed, followed by the JSON reports it made; TPV = time-position-velocity). The
// bytes go through exactly what gps_driver_node does with a file source: FileSource at rate 0,
// 4096-byte reads, NmeaDecoder::feed, and NmeaDecoder::finish at the end of the file.
//
// Checked for every capture:
//   - nothing crashes, and every input line is accounted for: non-empty input lines =
//     lines handed out (each republished raw, counted under one parse outcome) - extra pieces of
//     lines cut by a '$' + lines of stray bytes only + overlong lines;
//   - at most one fix per epoch (no two fixes of the same UTC time);
//   - where gpsd and the driver report the same epoch (same UTC time), time, position, speed and
//     course agree within the tolerances below (the precision gpsd prints, finer than any
//     sentence's; for speed also VTG's two roundings). gpsd's own inferences (dates from a build
//     date or another sentence, speed derived from two positions, no-fix rules of its own) are
//     counted apart, not compared.
//
// By default the committed excerpts in test/data/nmea_captures/ are checked. For the full
// captures, point ACC_NMEA_CAPTURES_DIR at a folder of X.nmea + X.chk pairs; with
// ACC_NMEA_CAPTURES_REPORT=file the per-capture table is written there as Markdown (the table
// of docs/GNSS_RECEIVERS.md), and ACC_NMEA_CAPTURES_VERBOSE=1 prints every difference.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <dirent.h>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "acc_identification/gnss/file_source.h"
#include "acc_identification/gnss/nmea_decoder.h"
#include "acc_identification/gnss/utc_date.h"

using acc::GnssFix;

namespace
{
constexpr double kPi = 3.14159265358979323846;

// Tolerances: gpsd prints time to the millisecond, latitude and longitude to 1e-9 degree,
// altitude and course to 1e-4, speed to 1e-3 m/s; each bound is that half-unit plus margin.
// Times are matched to the millisecond; a gpsd TPV within kTimeWindow_s of a fix but not at its
// millisecond is a time disagreement (epochs are at least 50 ms apart in every capture).
constexpr double kTimeWindow_s = 0.02;
constexpr double kPositionTolerance_deg = 1e-9;
constexpr double kAltitudeTolerance_m = 1e-3;
constexpr double kSpeedTolerance_mps = 1e-3;
constexpr double kCourseTolerance_deg = 1e-3;

// ---------------------------------------------------------------- gpsd's .chk

/// One TPV report of gpsd.
struct Tpv
{
  bool has_time = false;
  double time_s = 0.0;  ///< seconds since the Unix epoch
  int mode = 0;         ///< 0/1 no fix, 2 2D, 3 3D
  double lat = NAN, lon = NAN, alt = NAN, speed = NAN, track = NAN;
  bool velocity_reported = false;  ///< its cycle had an RMC or VTG (speed not derived)
  std::string after;               ///< the sentence type echoed just before it
};

/// A number or string value of "key" in a flat JSON object; false when absent.
bool jsonValue(const std::string& object, const std::string& key, std::string& value)
{
  const std::string needle = "\"" + key + "\":";
  const std::size_t at = object.find(needle);
  if (at == std::string::npos)
    return false;
  std::size_t begin = at + needle.size();
  if (begin < object.size() && object[begin] == '"')
  {
    const std::size_t end = object.find('"', begin + 1);
    value = object.substr(begin + 1, end - begin - 1);
    return true;
  }
  std::size_t end = begin;
  while (end < object.size() && object[end] != ',' && object[end] != '}')
    ++end;
  value = object.substr(begin, end - begin);
  return true;
}

double jsonNumber(const std::string& object, const std::string& key)
{
  std::string value;
  return jsonValue(object, key, value) ? std::strtod(value.c_str(), nullptr) : NAN;
}

/// "2022-10-18T11:32:58.000Z" into seconds since the Unix epoch.
bool isoTime(const std::string& text, double& seconds)
{
  int year = 0, month = 0, day = 0, hour = 0, minute = 0;
  double second = 0.0;
  if (std::sscanf(text.c_str(), "%d-%d-%dT%d:%d:%lfZ", &year, &month, &day, &hour, &minute, &second) != 6)
    return false;
  seconds = static_cast<double>(acc::daysFromCivil(year, static_cast<unsigned>(month), static_cast<unsigned>(day))) *
                acc::kSecondsPerDay +
            hour * 3600.0 + minute * 60.0 + second;
  return true;
}

/// The sentence type of an echoed line: "GGA", "RMC", ..., or the proprietary address.
std::string sentenceType(const std::string& line)
{
  const std::size_t comma = line.find(',');
  const std::string address = line.substr(1, comma == std::string::npos ? std::string::npos : comma - 1);
  if (address.size() == 5 && address[0] != 'P')
    return address.substr(2);
  return address;
}

std::vector<Tpv> readChk(const std::string& path)
{
  std::vector<Tpv> tpvs;
  std::ifstream in(path);
  std::string line, last_sentence;
  std::vector<std::string> since_report;  // sentence types since the last TPV
  bool cycle_velocity = false;
  double cycle_time = NAN;
  while (std::getline(in, line))
  {
    if (!line.empty() && line.back() == '\r')
      line.pop_back();
    if (line.empty())
      continue;
    if (line[0] == '$' || line[0] == '!')
    {
      last_sentence = sentenceType(line);
      since_report.push_back(last_sentence);
      continue;
    }
    std::string kind;
    if (line[0] != '{' || !jsonValue(line, "class", kind) || kind != "TPV")
      continue;
    Tpv tpv;
    std::string time;
    tpv.has_time = jsonValue(line, "time", time) && isoTime(time, tpv.time_s);
    const double mode = jsonNumber(line, "mode");
    tpv.mode = std::isnan(mode) ? 0 : static_cast<int>(mode);
    tpv.lat = jsonNumber(line, "lat");
    tpv.lon = jsonNumber(line, "lon");
    tpv.alt = jsonNumber(line, "altMSL");
    if (std::isnan(tpv.alt))
      tpv.alt = jsonNumber(line, "alt");
    tpv.speed = jsonNumber(line, "speed");
    tpv.track = jsonNumber(line, "track");
    tpv.after = last_sentence;
    const bool velocity_sentence =
        std::any_of(since_report.begin(), since_report.end(), [](const std::string& t) { return t == "RMC" || t == "VTG"; });
    if (!(tpv.has_time && tpv.time_s == cycle_time))
      cycle_velocity = false;
    cycle_velocity = cycle_velocity || velocity_sentence;
    cycle_time = tpv.has_time ? tpv.time_s : NAN;
    tpv.velocity_reported = cycle_velocity;
    since_report.clear();
    tpvs.push_back(tpv);
  }
  return tpvs;
}

// ---------------------------------------------------------------- the driver's path

struct Decoded
{
  std::uint64_t input_lines = 0;  ///< non-empty lines of the file (split at \r and \n)
  std::uint64_t lines_out = 0;    ///< lines the decoder handed out (republished raw by the node)
  std::vector<GnssFix> fixes;
  std::vector<std::vector<std::string>> epoch_sentences;  ///< per fix: the sentences of its epoch
  acc::NmeaStatistics statistics;
  std::vector<std::string> rejected;  ///< bad checksum and malformed lines, with the reason
};

std::uint64_t countInputLines(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::uint64_t lines = 0;
  bool in_line = false;
  for (int c = in.get(); c != std::char_traits<char>::eof(); c = in.get())
  {
    if (c == '\r' || c == '\n')
      in_line = false;
    else if (!in_line)
    {
      in_line = true;
      ++lines;
    }
  }
  return lines;
}

/// What gps_driver_node does with source file://path?rate=0 (GpsDriverRos::run).
Decoded decodeLikeTheNode(const std::string& path)
{
  Decoded out;
  out.input_lines = countInputLines(path);
  // A fix completes when the first sentence of the next epoch arrives (after its line was
  // handed out) or at the end of the stream.
  std::vector<std::string> sentences;
  bool finishing = false;
  acc::NmeaDecoder decoder(
      [&](std::string_view line, acc::NmeaParseOutcome outcome) {
        ++out.lines_out;
        if (outcome == acc::NmeaParseOutcome::kOk)
          sentences.emplace_back(line);
        if (outcome == acc::NmeaParseOutcome::kBadChecksum || outcome == acc::NmeaParseOutcome::kMalformed)
          out.rejected.push_back(std::string(acc::toString(outcome)) + ": " + std::string(line));
      },
      [&](const GnssFix& fix) {
        out.fixes.push_back(fix);
        std::vector<std::string> next;
        if (!finishing && !sentences.empty())
        {
          next.push_back(sentences.back());
          sentences.pop_back();
        }
        out.epoch_sentences.push_back(sentences);
        sentences = next;
      });
  acc::FileSource source(path, 0.0);
  char buffer[4096];
  double receive_time_s = 1000.0;
  for (;;)
  {
    const acc::ReadResult result = source.read(buffer, sizeof buffer, 0.02);
    if (result.status == acc::ReadStatus::kEnd)
      break;
    if (result.status == acc::ReadStatus::kData)
      decoder.feed(buffer, result.size, receive_time_s += 0.01);
  }
  finishing = true;
  decoder.finish(receive_time_s);
  out.statistics = decoder.statistics();
  return out;
}

// ---------------------------------------------------------------- comparison

/// Half a unit of the last digit of a decimal field ("0.1" -> 0.05), 0 when empty.
double halfUnit(std::string_view field)
{
  if (field.empty())
    return 0.0;
  const std::size_t point = field.find('.');
  const int decimals = point == std::string_view::npos ? 0 : static_cast<int>(field.size() - point - 1);
  return 0.5 * std::pow(10.0, -decimals);
}

std::vector<std::string_view> splitFields(std::string_view line)
{
  const std::size_t star = line.find('*');
  line = line.substr(0, star);
  std::vector<std::string_view> fields;
  for (std::size_t start = 0;;)
  {
    const std::size_t comma = line.find(',', start);
    fields.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos : comma - start));
    if (comma == std::string_view::npos)
      return fields;
    start = comma + 1;
  }
}

/// Speed tolerance of an epoch: gpsd reads VTG's knots, the driver its km/h (the finer unit);
/// the receiver rounds each field on its own, so they may differ by half a unit of each.
double speedTolerance(const std::vector<std::string>& sentences)
{
  double tolerance = kSpeedTolerance_mps;
  for (const std::string& line : sentences)
  {
    const std::vector<std::string_view> f = splitFields(line);
    if (f[0].size() == 6 && f[0].substr(3) == "VTG" && f.size() > 7 && !f[5].empty() && !f[7].empty())
      tolerance = std::max(tolerance, kSpeedTolerance_mps + halfUnit(f[5]) * 1852.0 / 3600.0 + halfUnit(f[7]) / 3.6);
  }
  return tolerance;
}

struct Comparison
{
  std::string name;
  Decoded decoded;
  std::uint64_t fixes_with_position = 0;
  std::uint64_t repeated_epochs = 0;  ///< fixes with the time of an earlier fix
  std::uint64_t time_backwards = 0;   ///< fixes earlier than the fix before them
  std::uint64_t undated = 0;          ///< fixes with time of day only (no RMC/ZDA date yet)
  std::uint64_t same_time = 0;        ///< our dated fixes with a gpsd TPV of the same time
  std::uint64_t other_day = 0;        ///< our fixes whose time of day gpsd reports on another day
                                      ///< (compared with that TPV)
  std::uint64_t gpsd_silent = 0;      ///< our dated fixes whose time gpsd never reports
  std::uint64_t gpsd_silent_with_position = 0;
  std::uint64_t time_differs = 0;     ///< gpsd has a TPV a few ms from ours, not at our time
  std::uint64_t position_compared = 0, position_agree = 0;
  std::uint64_t altitude_compared = 0, altitude_agree = 0;
  std::uint64_t speed_compared = 0, speed_agree = 0;
  std::uint64_t course_compared = 0, course_agree = 0;
  std::uint64_t only_our_position = 0;   ///< we have a position, gpsd none (its own no-fix rules)
  std::uint64_t only_gpsd_position = 0;  ///< gpsd has a position at that time, we have none
  std::uint64_t gpsd_epochs_missing = 0; ///< gpsd positions at times we have no dated fix for
  std::vector<std::string> differences;  ///< one line per difference, for ACC_NMEA_CAPTURES_VERBOSE

  std::uint64_t disagreements() const
  {
    return time_differs + (position_compared - position_agree) + (altitude_compared - altitude_agree) +
           (speed_compared - speed_agree) + (course_compared - course_agree);
  }
};

std::int64_t millis(double seconds) { return std::llround(seconds * 1000.0); }

std::string timeText(double seconds)
{
  const std::int64_t ms = millis(seconds);
  const std::int64_t of_day = ms % 86400000;
  char text[64];
  std::snprintf(text, sizeof text, "day %lld %02lld:%02lld:%06.3f", static_cast<long long>(ms / 86400000),
                static_cast<long long>(of_day / 3600000), static_cast<long long>(of_day / 60000 % 60),
                static_cast<double>(of_day % 60000) / 1000.0);
  return text;
}

std::string number(double value, int decimals)
{
  char text[48];
  std::snprintf(text, sizeof text, "%.*f", decimals, value);
  return text;
}

double angleDifferenceDeg(double a, double b)
{
  const double d = std::fabs(a - b);
  return d > 180.0 ? 360.0 - d : d;
}

Comparison compareCapture(const std::string& directory, const std::string& name)
{
  Comparison c;
  c.name = name;
  c.decoded = decodeLikeTheNode(directory + "/" + name + ".nmea");

  const std::vector<Tpv> tpvs = readChk(directory + "/" + name + ".chk");
  std::map<std::int64_t, std::vector<const Tpv*>> by_time;
  std::map<std::int64_t, std::set<std::int64_t>> days_by_time_of_day;
  for (const Tpv& tpv : tpvs)
    if (tpv.has_time)
    {
      by_time[millis(tpv.time_s)].push_back(&tpv);
      days_by_time_of_day[millis(tpv.time_s) % 86400000].insert(millis(tpv.time_s) / 86400000);
    }

  std::set<std::int64_t> our_times;
  double previous_time = NAN;
  for (std::size_t i = 0; i < c.decoded.fixes.size(); ++i)
  {
    const GnssFix& fix = c.decoded.fixes[i];
    const bool has_position = fix.has(GnssFix::kValidPosition);
    c.fixes_with_position += has_position;
    c.time_backwards += fix.has_date && fix.gnss_time_s < previous_time;
    if (fix.has_date)
      previous_time = fix.gnss_time_s;
    if (!fix.has_date)
    {
      ++c.undated;
      continue;
    }
    const std::string when = timeText(fix.gnss_time_s);
    if (!our_times.insert(millis(fix.gnss_time_s)).second)
    {
      ++c.repeated_epochs;
      c.differences.push_back(when + ": a second fix of this time");
    }
    auto found = by_time.find(millis(fix.gnss_time_s));
    if (found == by_time.end())
    {
      // gpsd's date may differ (its week-rollover fix-up): the same time of day on one other
      // day is that epoch, compared as such and counted apart.
      const auto other = days_by_time_of_day.find(millis(fix.gnss_time_s) % 86400000);
      const auto near = by_time.lower_bound(millis(fix.gnss_time_s - kTimeWindow_s));
      if (near != by_time.end() && near->first <= millis(fix.gnss_time_s + kTimeWindow_s))
      {
        ++c.time_differs;
        c.differences.push_back(when + ": gpsd's nearest time is " + timeText(near->first / 1000.0));
        continue;
      }
      if (other == days_by_time_of_day.end() || other->second.size() != 1)
      {
        ++c.gpsd_silent;
        c.gpsd_silent_with_position += has_position;
        c.differences.push_back(when + ": no TPV of gpsd at this time" + (has_position ? " (we have a position)" : ""));
        continue;
      }
      ++c.other_day;
      const std::int64_t gpsd_time = *other->second.begin() * 86400000 + other->first;
      c.differences.push_back(when + ": gpsd reports this time of day on day " + std::to_string(*other->second.begin()));
      found = by_time.find(gpsd_time);
      our_times.insert(gpsd_time);
    }
    else
      ++c.same_time;

    // Position: the TPV of that time nearest to ours (gpsd reports after several sentences of
    // one epoch, each with the position of the last sentence that had one).
    const Tpv* nearest = nullptr;
    double position_error = INFINITY;
    for (const Tpv* tpv : found->second)
      if (!std::isnan(tpv->lat) && tpv->mode >= 2)
      {
        const double e = std::max(std::fabs(tpv->lat - fix.latitude_deg), std::fabs(tpv->lon - fix.longitude_deg));
        if (!nearest || e < position_error)
        {
          position_error = e;
          nearest = tpv;
        }
      }
    if (has_position && nearest)
    {
      ++c.position_compared;
      if (position_error <= kPositionTolerance_deg)
        ++c.position_agree;
      else
        c.differences.push_back(when + ": position " + number(fix.latitude_deg, 9) + " " + number(fix.longitude_deg, 9) +
                                ", gpsd " + number(nearest->lat, 9) + " " + number(nearest->lon, 9));
    }
    else if (has_position)
    {
      ++c.only_our_position;
      c.differences.push_back(when + ": position, gpsd has none at this time");
    }
    else if (nearest)
    {
      ++c.only_gpsd_position;
      c.differences.push_back(when + ": no position, gpsd has one (TPV after " + nearest->after + ")");
    }

    if (fix.has(GnssFix::kValidAltitude))
    {
      double best = INFINITY;
      for (const Tpv* tpv : found->second)
        if (!std::isnan(tpv->alt) && tpv->mode >= 3)
          best = std::min(best, std::fabs(tpv->alt - fix.altitude_m));
      if (std::isfinite(best))
      {
        ++c.altitude_compared;
        if (best <= kAltitudeTolerance_m)
          ++c.altitude_agree;
        else
          c.differences.push_back(when + ": altitude " + number(fix.altitude_m, 4) + " off by " + number(best, 4));
      }
    }

    // Speed and course: only TPVs whose cycle reported them (gpsd derives others from positions).
    if (fix.has(GnssFix::kValidSpeed))
    {
      double best = INFINITY;
      for (const Tpv* tpv : found->second)
        if (tpv->velocity_reported && !std::isnan(tpv->speed))
          best = std::min(best, std::fabs(tpv->speed - fix.speed_over_ground_mps));
      if (std::isfinite(best))
      {
        ++c.speed_compared;
        if (best <= speedTolerance(c.decoded.epoch_sentences[i]))
          ++c.speed_agree;
        else
          c.differences.push_back(when + ": speed " + number(fix.speed_over_ground_mps, 4) + " off by " + number(best, 4));
      }
    }
    if (fix.has(GnssFix::kValidCourse))
    {
      double best = INFINITY;
      const double ours = fix.course_rad * 180.0 / kPi;
      for (const Tpv* tpv : found->second)
        if (tpv->velocity_reported && !std::isnan(tpv->track))
          best = std::min(best, angleDifferenceDeg(tpv->track, ours));
      if (std::isfinite(best))
      {
        ++c.course_compared;
        if (best <= kCourseTolerance_deg)
          ++c.course_agree;
        else
          c.differences.push_back(when + ": course " + number(ours, 4) + " off by " + number(best, 4));
      }
    }
  }
  // gpsd positions at times we have no dated fix for.
  for (const auto& [time, list] : by_time)
  {
    const bool position =
        std::any_of(list.begin(), list.end(), [](const Tpv* t) { return t->mode >= 2 && !std::isnan(t->lat); });
    if (position && !our_times.count(time))
    {
      ++c.gpsd_epochs_missing;
      c.differences.push_back(timeText(static_cast<double>(time) / 1000.0) + ": gpsd has a position, we no dated fix");
    }
  }
  return c;
}

std::vector<std::string> captureNames(const std::string& directory)
{
  std::vector<std::string> names;
  if (DIR* dir = opendir(directory.c_str()))
  {
    while (const dirent* entry = readdir(dir))
    {
      const std::string file = entry->d_name;
      if (file.size() > 5 && file.compare(file.size() - 5, 5, ".nmea") == 0)
      {
        const std::string name = file.substr(0, file.size() - 5);
        if (std::ifstream(directory + "/" + name + ".chk"))
          names.push_back(name);
      }
    }
    closedir(dir);
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::string agreement(std::uint64_t agree, std::uint64_t compared)
{
  return compared == 0 ? "-" : std::to_string(agree) + "/" + std::to_string(compared);
}

const char* const kTableHeader =
    "| capture | lines | decoded | bad checksum | malformed | unsupported | stray lines | cut | overlong | fixes | "
    "with position | undated | time back | time | gpsd: other day | gpsd: no TPV (with position) | "
    "position | altitude | speed | course | position gpsd lacks | gpsd position we lack |\n"
    "|---|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|--:|\n";

std::string tableRow(const Comparison& c)
{
  const acc::NmeaStatistics& s = c.decoded.statistics;
  std::ostringstream row;
  row << "| " << c.name << " | " << c.decoded.input_lines << " | " << s.sentences_ok << " | " << s.bad_checksum
      << " | " << s.malformed << " | " << s.unsupported << " | " << s.stray_lines << " | " << s.cut_lines << " | "
      << s.overlong_lines << " | " << s.fixes << " | " << c.fixes_with_position << " | " << c.undated << " | "
      << c.time_backwards << " | " << agreement(c.same_time, c.same_time + c.time_differs) << " | "
      << c.other_day << " | " << c.gpsd_silent << " (" << c.gpsd_silent_with_position << ") | "
      << agreement(c.position_agree, c.position_compared) << " | " << agreement(c.altitude_agree, c.altitude_compared)
      << " | " << agreement(c.speed_agree, c.speed_compared) << " | " << agreement(c.course_agree, c.course_compared)
      << " | " << c.only_our_position << " | " << c.only_gpsd_position + c.gpsd_epochs_missing << " |\n";
  return row.str();
}

/// The invariants every capture must keep, whatever gpsd says.
void checkInvariants(const Comparison& c)
{
  const acc::NmeaStatistics& s = c.decoded.statistics;
  // Every input line accounted for: republished raw (and counted under one parse outcome),
  // or dropped before the parser and counted (stray, overlong).
  EXPECT_EQ(s.lines, c.decoded.lines_out);
  EXPECT_EQ(s.lines, s.sentences_ok + s.bad_checksum + s.malformed + s.unsupported);
  EXPECT_EQ(c.decoded.input_lines, s.inputLines());
  // At most one fix per epoch.
  EXPECT_EQ(c.repeated_epochs, 0u);
  EXPECT_EQ(s.fixes, c.decoded.fixes.size());
  // Where both decode the same epoch, they agree within the sentence's precision.
  EXPECT_EQ(c.disagreements(), 0u);
}

}  // namespace

TEST(GnssCaptures, EveryCaptureThroughTheDriverPath)
{
  const char* env = std::getenv("ACC_NMEA_CAPTURES_DIR");
  const std::string directory = env && *env ? env : ACC_GNSS_CAPTURE_DATA;
  const bool verbose = std::getenv("ACC_NMEA_CAPTURES_VERBOSE") != nullptr;
  const std::vector<std::string> names = captureNames(directory);
  ASSERT_FALSE(names.empty()) << "no X.nmea + X.chk in " << directory;
  std::string table = kTableHeader;
  for (const std::string& name : names)
  {
    SCOPED_TRACE(name);
    const Comparison c = compareCapture(directory, name);
    table += tableRow(c);
    if (verbose)
    {
      for (const std::string& line : c.decoded.rejected)
        std::printf("%s: %s\n", name.c_str(), line.c_str());
      for (const std::string& line : c.differences)
        std::printf("%s: %s\n", name.c_str(), line.c_str());
    }
    checkInvariants(c);
  }
  std::printf("%s", table.c_str());
  if (const char* report = std::getenv("ACC_NMEA_CAPTURES_REPORT"))
    std::ofstream(report) << table;
}

// ---- What each fix of docs/GNSS_RECEIVERS.md changes on the committed excerpts.

namespace
{
Comparison excerpt(const std::string& name) { return compareCapture(ACC_GNSS_CAPTURE_DATA, name); }
}  // namespace

TEST(GnssCaptures, StTeseoDoubledDollar)
{
  const Comparison c = excerpt("st-teseo-liv4f");
  EXPECT_EQ(c.decoded.statistics.malformed, 0u);     // no "$" line per "$$"
  EXPECT_EQ(c.decoded.statistics.bad_checksum, 1u);  // the GSV gpsd's log damaged on purpose
  EXPECT_EQ(c.decoded.statistics.lines, c.decoded.input_lines);
  EXPECT_EQ(c.position_agree, 1u);
}

TEST(GnssCaptures, AisLinesAreRepublished)
{
  for (const char* name : {"ais-nmea", "saab-r4"})
  {
    SCOPED_TRACE(name);
    const Comparison c = excerpt(name);
    EXPECT_EQ(c.decoded.statistics.stray_bytes, 0u);
    EXPECT_EQ(c.decoded.statistics.lines, c.decoded.input_lines);
  }
}

TEST(GnssCaptures, SaabGgaWithoutTrailingFields)
{
  const Comparison c = excerpt("saab-r4");
  EXPECT_EQ(c.decoded.statistics.malformed, 0u);
  ASSERT_EQ(c.decoded.fixes.size(), 3u);
  for (const GnssFix& fix : c.decoded.fixes)
    EXPECT_EQ(fix.fix_quality, 2);  // from GGA (DGPS); RMC alone would say 1
  EXPECT_EQ(c.position_agree, 3u);
}

TEST(GnssCaptures, MediatekColdStart)
{
  const Comparison c = excerpt("mtk-3301");
  EXPECT_EQ(c.decoded.statistics.malformed, 3u);  // only the three $POLYN lines without checksum
  ASSERT_EQ(c.decoded.fixes.size(), 8u);
  EXPECT_NEAR(c.decoded.fixes[0].gnss_time_s, acc::daysFromCivil(1980, 1, 5) * acc::kSecondsPerDay + 86386.005, 1e-6);
  EXPECT_FALSE(c.decoded.fixes[0].has(GnssFix::kValidPosition));
  EXPECT_TRUE(c.decoded.fixes.back().has(GnssFix::kValidPosition));  // 08:14:36, the first fix
}

TEST(GnssCaptures, GarminSimulatorModeIsNoFix)
{
  const Comparison c = excerpt("GPSmap-76S");
  ASSERT_EQ(c.decoded.fixes.size(), 2u);
  for (const GnssFix& fix : c.decoded.fixes)
  {
    EXPECT_FALSE(fix.has(GnssFix::kValidPosition));
    EXPECT_EQ(fix.fix_quality, 8);
  }
}

TEST(GnssCaptures, EricssonPositionFromGns)
{
  const Comparison c = excerpt("ericsson-gru04-02-70sec");
  ASSERT_EQ(c.decoded.fixes.size(), 2u);
  EXPECT_EQ(c.fixes_with_position, 2u);
  EXPECT_EQ(c.position_agree, 2u);
  EXPECT_EQ(c.altitude_agree, 2u);
  EXPECT_EQ(c.speed_agree, 2u);  // VTG: 0.1 km/h here, 0.0 knots in gpsd, within both roundings
}

TEST(GnssCaptures, CombinedTalkerSatellites)
{
  const Comparison telit = excerpt("telit-pls83-w");
  ASSERT_EQ(telit.decoded.fixes.size(), 2u);
  for (const GnssFix& fix : telit.decoded.fixes)
    EXPECT_EQ(fix.satellites_used, 14);  // GNGNS, not GPGGA's 5 or GAGGA's 1
  const Comparison quectel = excerpt("quectel-eg25-g");
  ASSERT_EQ(quectel.decoded.fixes.size(), 2u);
  EXPECT_EQ(quectel.decoded.fixes[0].satellites_used, 8);  // GNGNS, not GPGGA's 3
}

TEST(GnssCaptures, GpsdWeekRolloverIsGpsdsNotOurs)
{
  // neo-m8n (2015-03-18): gpsd, without a date in the log, adds 1024 weeks; the RMC says 2015.
  const Comparison c = excerpt("neo-m8n");
  EXPECT_EQ(c.other_day, 2u);
  EXPECT_EQ(c.position_agree, 2u);
  ASSERT_FALSE(c.decoded.fixes.empty());
  EXPECT_NEAR(c.decoded.fixes.back().gnss_time_s,
              acc::daysFromCivil(2015, 3, 18) * acc::kSecondsPerDay + 17 * 3600 + 19 * 60 + 27.0, 1e-6);
}
