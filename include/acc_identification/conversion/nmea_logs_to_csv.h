#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/gnss/nmea_statistics.h"
#include "acc_identification/relative_state/relative_state_estimator.h"
#include "acc_identification/relative_state/relative_state_parameters.h"

namespace acc
{
/// Two receivers' NMEA logs paired in batch: what relative_state_node makes of them live, for
/// receivers that logged to files on their own (no ROS in the car).
struct RelativeStateLogs
{
  std::vector<RelativeState> states;  ///< every paired epoch, valid or not, in GNSS-time order
  NmeaStatistics leader_log;          ///< what the leader's log gave the driver's decoder
  NmeaStatistics follower_log;
  PairingCounters pairing;            ///< every fix counted once, and why one was not paired
  RelativeStateCounters estimator;    ///< invalid states, rejected jumps, held positions
  std::vector<std::string> stream_events;  ///< dropouts and time resets, one line each
  /// Per-epoch reports (an unpaired epoch, a late fix, an along-track fallback): too many to list
  /// on a long drive; each is in the counters, an invalid state's reason in its row.
  std::size_t epoch_events = 0;
  std::string error;  ///< a log that cannot be read: nothing else is set
};

/// Reads both logs with the driver's decoder (readNmeaLog) and pairs their fixes with the node's
/// estimator (RelativeStateEstimator, the same settings as ~relative_state_node), fed in GNSS-time
/// order as they were on the air (at one time the leader's first); at the end of the logs the
/// epochs still waiting for leader data are paired or counted unpaired (finish()). Logs given the
/// wrong way round (the leader's log of the car behind, told by the gap growing where the Doppler
/// speeds say the cars close in) set error with the states kept, so that nothing is written.
RelativeStateLogs pairNmeaLogs(const std::string& leader_path, const std::string& follower_path,
                               const RelativeStateSettings& settings);

/// The valid states whose gap lies outside the run readers' plausibility bounds (RunPlausibilityBounds:
/// below -2 m, above 1000 m), which calibrate and diagnose would reject; and a warning that says
/// how many and what it usually means ("" when none).
std::size_t implausibleGapStates(const RelativeStateLogs& logs);
std::string describeImplausibleGaps(const RelativeStateLogs& logs);

/// What a user gives nmea_to_csv (or Python's pair_nmea_logs): relative_state_node's parameter
/// file, and options that override it; NaN or empty is "not given".
struct NmeaPairingOptions
{
  std::string params_path;
  AntennaOffsets antennas;
  std::string gap_mode;
  double dropout_gap_s = RelativeState::kNaN;
};

/// The pairing's settings: the node's defaults, then the parameter file's values, then the
/// options'. The antennas' place must come from one of the two by geometryFromOffsets' rule, the
/// options' whole when they give any (the file's is then not read). "" when set, else the error;
/// unread_note: the file's keys never read (misspelt?).
std::string pairingSettingsFrom(const NmeaPairingOptions& options, RelativeStateSettings& settings,
                                std::string& unread_note);

/// nmea_to_csv's job: pairNmeaLogs, then every state written to out_path (writeRelativeStateCsv).
/// error set when a log cannot be read or the CSV cannot be written.
RelativeStateLogs pairNmeaLogsToCsv(const std::string& leader_path, const std::string& follower_path,
                                    const std::string& out_path, const RelativeStateSettings& settings);

/// Empty when the logs gave a state; otherwise why none could be made, for the user: a log without
/// a fix, a log whose every fix is unusable, or logs that do not meet in time.
std::string noStateReason(const RelativeStateLogs& logs);

/// Where every fix went, in one line: paired, unpaired, unusable, and (when any) duplicated, too
/// late or discarded from a full buffer; the follower's add up to its fixes.
std::string fixAccount(const PairingCounters& pairing);

/// The states as a canonical run CSV that keeps the pairing's verdict: time_s, space_gap_m,
/// follower_speed_mps, leader_speed_mps, relative_speed_mps, space_gap_sigma_m, epoch_skew_s,
/// gap_doppler_residual_m, valid (1 or 0), invalid_reason (quoted). Time to the millisecond,
/// distances to the millimetre, speeds to 0.1 mm/s; a value not known is an empty cell. The run
/// readers use the four first and split runs at rows whose valid is 0 (readRunFile), as
/// identifier_node splits its window at an invalid sample. false, with error set, when the file
/// cannot be written.
bool writeRelativeStateCsv(const std::string& path, const std::vector<RelativeState>& states, std::string& error);

/// The counts as JSON: {leader_log, follower_log (NmeaStatistics), pairing (PairingCounters),
/// estimator (RelativeStateCounters: why states are invalid), states, valid_states,
/// implausible_gap_states, stream_events (the lines), epoch_events}.
nlohmann::json relativeStateLogsJson(const RelativeStateLogs& logs);

}  // namespace acc
