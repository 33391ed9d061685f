#include "acc_identification/conversion/nmea_logs_to_csv.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

#include "acc_identification/gnss/nmea_log.h"
#include "acc_identification/io/csv_fields.h"
#include "acc_identification/io/output_files.h"
#include "acc_identification/io/run_plausibility.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/relative_state/gap_doppler_consistency.h"

namespace acc
{
namespace
{
/// The value with `decimals` decimals, or an empty cell when it is not known.
std::string cell(double value, int decimals)
{
  if (!std::isfinite(value))
    return "";
  std::ostringstream out;
  out << std::fixed << std::setprecision(decimals) << value;
  return out.str();
}

/// A log as the batch feeds it to the pairing.
struct ClockStretches
{
  /// Where each stretch on one clock ends: before the first fix of a new clock, where the pairing's
  /// own rule (ClockResetRule, on the fixes it would use) confirms a reset, so that the pairing,
  /// fed stretch by stretch, sees each reset where the stretches end.
  std::vector<std::size_t> ends;
  /// The time each fix is fed at: its own on the stream's clock; for a stray stamp, or a fix
  /// without a usable position, the time of the fix before it in its log, so that it goes in where
  /// it stands (the pairing counts it) and a stamp an hour ahead does not hold the other log back.
  std::vector<double> feed_time_s;
};

ClockStretches clockStretches(const std::vector<GnssFix>& fixes, const PairingSettings& pairing)
{
  ClockResetRule<std::size_t> clock(pairing.time_reset_s, pairing.time_reset_confirm_fixes);  // holds indices
  ClockStretches out;
  out.feed_time_s.assign(fixes.size(), std::numeric_limits<double>::quiet_NaN());
  double newest = std::numeric_limits<double>::quiet_NaN();  // the stream's newest time, as the pairing keeps it
  for (std::size_t i = 0; i < fixes.size(); ++i)
  {
    if (!hasUsablePosition(fixes[i]))
      continue;
    const double t = fixes[i].gnss_time_s;
    const ClockResetRule<std::size_t>::Step step = clock.next(i, t, newest);
    if (step.new_clock)
    {
      out.ends.push_back(step.released.front());
      newest = t;
    }
    for (const std::size_t j : step.released)  // they go on, on their clock
    {
      out.feed_time_s[j] = fixes[j].gnss_time_s;
      newest = std::max(newest, fixes[j].gnss_time_s);
    }
    if (step.released.empty() && !step.held)
    {
      out.feed_time_s[i] = t;
      newest = std::isfinite(newest) ? std::max(newest, t) : t;
    }
  }
  out.ends.push_back(fixes.size());
  double before = -std::numeric_limits<double>::infinity();
  for (double& time_s : out.feed_time_s)
    before = std::isnan(time_s) ? (time_s = before) : time_s;
  return out;
}

/// Feeds both logs' fixes in GNSS-time order (their feed times), the leader's first at equal
/// times, stretch by stretch of one clock: the k-th stretch of each log together (a log played
/// twice is two drives, not one whose times interleave), a log's stretches beyond the other's after
/// all of it (a clock that went back on one receiver only: the pairing then pairs nothing across
/// the two clocks).
void feedInTimeOrder(const std::vector<GnssFix>& leader, const std::vector<GnssFix>& follower,
                     RelativeStateEstimator& estimator, RelativeStateLogs& logs, const PairingSettings& pairing)
{
  const ClockStretches leader_log = clockStretches(leader, pairing), follower_log = clockStretches(follower, pairing);
  std::size_t l = 0, f = 0;
  for (std::size_t k = 0; k < std::max(leader_log.ends.size(), follower_log.ends.size()); ++k)
  {
    const std::size_t l_end = leader_log.ends[std::min(k, leader_log.ends.size() - 1)];
    const std::size_t f_end = follower_log.ends[std::min(k, follower_log.ends.size() - 1)];
    while (l < l_end || f < f_end)
    {
      const bool take_leader =
          f == f_end || (l < l_end && !(follower_log.feed_time_s[f] < leader_log.feed_time_s[l]));
      if (take_leader)
        estimator.addLeader(leader[l++]);
      else
        estimator.addFollower(follower[f++]);
      for (RelativeState& state : estimator.takeStates())
        logs.states.push_back(std::move(state));
    }
  }
}

nlohmann::json statisticsJson(const NmeaStatistics& s)
{
  return {{"lines", s.lines},
          {"sentences_ok", s.sentences_ok},
          {"bad_checksum", s.bad_checksum},
          {"malformed", s.malformed},
          {"without_checksum", s.without_checksum},
          {"unsupported", s.unsupported},
          {"stray_bytes", s.stray_bytes},
          {"stray_lines", s.stray_lines},
          {"cut_lines", s.cut_lines},
          {"overlong_lines", s.overlong_lines},
          {"fixes", s.fixes},
          {"epochs_without_time", s.epochs_without_time},
          {"date_lag_corrections", s.date_lag_corrections},
          {"late_sentences_merged", s.late_sentences_merged},
          {"late_sentences_after_fix", s.late_sentences_after_fix},
          {"repeated_sentences", s.repeated_sentences}};
}

nlohmann::json pairingJson(const PairingCounters& c)
{
  return {{"leader_fixes", c.leader_fixes},
          {"follower_fixes", c.follower_fixes},
          {"exact_pairs", c.exact_pairs},
          {"interpolated_pairs", c.interpolated_pairs},
          {"leader_invalid_fixes", c.leader_invalid_fixes},
          {"follower_invalid_fixes", c.follower_invalid_fixes},
          {"leader_duplicates", c.leader_duplicates},
          {"follower_duplicates", c.follower_duplicates},
          {"leader_out_of_order", c.leader_out_of_order},
          {"follower_out_of_order", c.follower_out_of_order},
          {"leader_too_late", c.leader_too_late},
          {"follower_too_late", c.follower_too_late},
          {"follower_unpaired", c.follower_unpaired},
          {"leader_dropouts", c.leader_dropouts},
          {"follower_dropouts", c.follower_dropouts},
          {"leader_time_resets", c.leader_time_resets},
          {"follower_time_resets", c.follower_time_resets},
          {"leader_stray_stamps", c.leader_stray_stamps},
          {"follower_stray_stamps", c.follower_stray_stamps},
          {"buffer_overflows", c.buffer_overflows}};
}

/// Refuses logs given the wrong way round (receiversLookSwapped over the whole drive): with the
/// logs swapped the gap grows where the relative speed says the cars close in.
std::string describeSwappedLogs(const std::vector<RelativeState>& states, const RelativeStateSettings& settings)
{
  std::vector<double> time_s, gap_m, relative_speed_mps;
  for (const RelativeState& s : states)
  {
    time_s.push_back(s.time_s);
    gap_m.push_back(s.valid ? s.space_gap_m : std::numeric_limits<double>::quiet_NaN());
    relative_speed_mps.push_back(s.relative_speed_mps);
  }
  const ConsistencySummary summary = gapDopplerConsistency(
      time_s, gap_m, relative_speed_mps, settings.consistency_window_s, settings.pairing.dropout_gap_s);
  if (!receiversLookSwapped(summary.gap_per_doppler_slope, summary.doppler_integral_rms_m, summary.windows))
    return "";
  return printfText("the gap grows where the speeds say the cars close in (its change against the relative speed's "
                    "integral over %zu windows of %g s: slope %.2f, where a leader ahead gives 1): the LEADER log is "
                    "of the car behind. Are the two logs swapped? Give the car ahead's log first",
                    summary.windows, settings.consistency_window_s, summary.gap_per_doppler_slope);
}
}  // namespace

RelativeStateLogs pairNmeaLogs(const std::string& leader_path, const std::string& follower_path,
                               const RelativeStateSettings& settings)
{
  RelativeStateLogs logs;
  if (sameFile(leader_path, follower_path))
  {
    // Paired with itself a log gives the antenna offset as a gap (negative), every state valid.
    logs.error = "LEADER and FOLLOWER are the same log (" + leader_path +
                 "): give the car ahead's receiver log first and the ACC car's second";
    return logs;
  }
  const NmeaLogResult leader = readNmeaLog(leader_path);
  const NmeaLogResult follower = readNmeaLog(follower_path);
  logs.error = !leader.error.empty() ? leader.error : follower.error;
  if (!logs.error.empty())
    return logs;
  logs.leader_log = leader.statistics;
  logs.follower_log = follower.statistics;
  RelativeStateEstimator estimator(settings);
  feedInTimeOrder(leader.fixes, follower.fixes, estimator, logs, settings.pairing);
  estimator.finish();
  for (RelativeState& state : estimator.takeStates())
    logs.states.push_back(std::move(state));
  for (const PairingEvent& event : estimator.takeEvents())
  {
    if (event.per_epoch)
      ++logs.epoch_events;
    else
      logs.stream_events.push_back(event.text);
  }
  logs.pairing = estimator.pairingCounters();
  logs.estimator = estimator.counters();
  logs.error = describeSwappedLogs(logs.states, settings);
  return logs;
}

std::string pairingSettingsFrom(const NmeaPairingOptions& options, RelativeStateSettings& settings,
                                std::string& unread_note)
{
  AntennaOffsets file_antennas;
  if (!options.params_path.empty())
  {
    const std::string error = loadRelativeStateParameterFile(options.params_path, settings, unread_note, file_antennas);
    if (!error.empty())
      return error;
  }
  // Options that place the antennas replace the file's place whole: one form, never a mix.
  const bool file_places = !options.antennas.anyGiven() && file_antennas.anyGiven();
  const std::string unplaced = geometryFromOffsets(file_places ? file_antennas : options.antennas, settings.geometry);
  if (!unplaced.empty())
  {
    if (file_places)
      return options.params_path + ": " + unplaced;
    return unplaced + (options.params_path.empty() || options.antennas.anyGiven() ? "" : "; the parameter file does not say it");
  }
  if (!options.gap_mode.empty() && !parseGapMode(options.gap_mode, settings.gap_mode))
    return "gap mode '" + options.gap_mode + "' is neither straight_line nor along_track";
  if (!std::isnan(options.dropout_gap_s))
  {
    if (!(options.dropout_gap_s > 0.0 && std::isfinite(options.dropout_gap_s)))
      return "the dropout gap must be a positive number of seconds";
    settings.pairing.dropout_gap_s = options.dropout_gap_s;
    if (const std::string problem = describePairingSettingsProblem(settings.pairing); !problem.empty())
      return "--dropout-gap-s " + printfText("%g", options.dropout_gap_s) + ": " + problem;
  }
  return "";
}

RelativeStateLogs pairNmeaLogsToCsv(const std::string& leader_path, const std::string& follower_path,
                                    const std::string& out_path, const RelativeStateSettings& settings)
{
  RelativeStateLogs logs = pairNmeaLogs(leader_path, follower_path, settings);
  // No state, no file: a header alone would read as a run file that holds nothing (noStateReason).
  if (logs.error.empty() && !logs.states.empty() && !writeRelativeStateCsv(out_path, logs.states, logs.error) &&
      logs.error.empty())
    logs.error = "cannot write " + out_path;
  return logs;
}

std::size_t implausibleGapStates(const RelativeStateLogs& logs)
{
  const RunPlausibilityBounds bounds;
  std::size_t count = 0;
  for (const RelativeState& s : logs.states)
    count += s.valid && !(s.space_gap_m >= bounds.min_space_gap_m && s.space_gap_m <= bounds.max_space_gap_m) ? 1 : 0;
  return count;
}

std::string describeImplausibleGaps(const RelativeStateLogs& logs)
{
  const std::size_t count = implausibleGapStates(logs);
  if (count == 0)
    return "";
  const RunPlausibilityBounds bounds;
  double least = std::numeric_limits<double>::infinity(), largest = -least;
  for (const RelativeState& s : logs.states)
    if (s.valid)
    {
      least = std::min(least, s.space_gap_m);
      largest = std::max(largest, s.space_gap_m);
    }
  return printfText("%zu of %zu valid states have a gap outside %g to %g m (from %.3g to %.3g m), which the run "
                    "readers reject as implausible: a bumper-to-bumper gap that negative means the antenna offsets "
                    "(or the logs) are wrong",
                    count, logs.states.size(), bounds.min_space_gap_m, bounds.max_space_gap_m, least, largest);
}

std::string noStateReason(const RelativeStateLogs& logs)
{
  if (!logs.states.empty())
    return "";
  const PairingCounters& p = logs.pairing;
  // A log whose every fix is unusable pairs nothing however the two overlap: say that, not overlap.
  const auto unusable = [](const std::string& car, std::uint64_t fixes, std::uint64_t invalid,
                           const NmeaStatistics& log) -> std::string {
    if (fixes == 0)
      return "the " + car + "'s log gave no fix: does it hold GGA or RMC sentences with a time?" +
             (log.without_checksum > 0 ? " " + std::to_string(log.without_checksum) + " of its " +
                                             std::to_string(log.lines) +
                                             " lines have no checksum *hh, which every sentence needs here"
                                       : std::string());
    if (invalid == fixes)
      return "none of the " + car + "'s " + std::to_string(fixes) +
             " fixes has a usable position and time (no fix: GGA quality 0 or RMC status V, as a receiver without "
             "satellites or in simulation mode reports; or a position off the Earth)";
    return "";
  };
  for (const std::string& reason :
       {unusable("leader", p.leader_fixes, p.leader_invalid_fixes, logs.leader_log),
        unusable("follower", p.follower_fixes, p.follower_invalid_fixes, logs.follower_log)})
    if (!reason.empty())
      return reason;
  return "no follower epoch could be paired with the leader (" + std::to_string(p.follower_fixes) + " follower and " +
         std::to_string(p.leader_fixes) +
         " leader fixes): do the two logs overlap in time, and do both carry the date (RMC) or neither?";
}

std::string fixAccount(const PairingCounters& p)
{
  std::ostringstream account;
  account << p.follower_fixes << " follower and " << p.leader_fixes << " leader fixes: " << p.exact_pairs
          << " paired exactly, " << p.interpolated_pairs << " interpolated, " << p.follower_unpaired
          << " follower epochs unpaired, " << p.follower_invalid_fixes << " follower and " << p.leader_invalid_fixes
          << " leader fixes without a usable position or time";
  if (p.follower_duplicates + p.leader_duplicates > 0)
    account << ", " << p.follower_duplicates << " follower and " << p.leader_duplicates << " leader duplicates";
  if (p.follower_too_late + p.leader_too_late > 0)
    account << ", " << p.follower_too_late << " follower and " << p.leader_too_late << " leader fixes too late";
  if (p.buffer_overflows > 0)
    account << ", " << p.buffer_overflows << " fixes discarded from full buffers";
  return account.str();
}

bool writeRelativeStateCsv(const std::string& path, const std::vector<RelativeState>& states, std::string& error)
{
  std::ofstream file(path);
  if (!file)
  {
    error = "cannot write " + path;
    return false;
  }
  file << "time_s,space_gap_m,follower_speed_mps,leader_speed_mps,relative_speed_mps,space_gap_sigma_m,"
          "epoch_skew_s,gap_doppler_residual_m,valid,invalid_reason\n";
  for (const RelativeState& s : states)
  {
    file << cell(s.time_s, 3) << ',' << cell(s.space_gap_m, 3) << ',' << cell(s.follower_speed_mps, 4) << ','
         << cell(s.leader_speed_mps, 4) << ',' << cell(s.relative_speed_mps, 4) << ',' << cell(s.space_gap_sigma_m, 3)
         << ',' << cell(s.epoch_skew_s, 3) << ',' << cell(s.gap_doppler_residual_m, 3) << ',' << (s.valid ? 1 : 0)
         << ',' << csvQuoted(s.invalid_reason) << '\n';
  }
  if (!file)
  {
    error = "error while writing " + path;
    return false;
  }
  return true;
}

nlohmann::json relativeStateLogsJson(const RelativeStateLogs& logs)
{
  std::size_t valid = 0;
  for (const RelativeState& s : logs.states)
    valid += s.valid ? 1 : 0;
  const RelativeStateCounters& e = logs.estimator;
  return {{"leader_log", statisticsJson(logs.leader_log)},
          {"follower_log", statisticsJson(logs.follower_log)},
          {"pairing", pairingJson(logs.pairing)},
          {"estimator",
           {{"states", e.states},
            {"invalid_states", e.invalid_states},
            {"jumps_rejected", e.jumps_rejected},
            {"missing_speed", e.missing_speed},
            {"held_positions", e.held_positions},
            {"along_track_fallbacks", e.along_track_fallbacks}}},
          {"states", logs.states.size()},
          {"valid_states", valid},
          {"implausible_gap_states", implausibleGapStates(logs)},
          {"stream_events", logs.stream_events},
          {"epoch_events", logs.epoch_events}};
}

}  // namespace acc
