// nmea_to_csv: the two receivers' NMEA logs paired by GNSS time, as relative_state_node pairs them
// live, into a run CSV that calibrate, diagnose and the Python API read: for receivers that logged
// to files on their own.
#include <cmath>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "acc_identification/conversion/nmea_logs_to_csv.h"
#include "acc_identification/io/output_files.h"
#include "acc_identification/tools/number_checks.h"

namespace
{
/// What the logs gave, on stdout; the stream events on stderr. false when no state was made.
bool report(const acc::RelativeStateLogs& logs, const std::string& out_path)
{
  for (const std::string& event : logs.stream_events)
    std::cerr << "note: " << event << "\n";
  const acc::RelativeStateCounters& e = logs.estimator;
  const std::string no_state = acc::noStateReason(logs);  // then no file was written
  std::cout << "nmea_to_csv: leader log: " << logs.leader_log.summary() << "\n"
            << "nmea_to_csv: follower log: " << logs.follower_log.summary() << "\n"
            << "nmea_to_csv: " << acc::fixAccount(logs.pairing) << "; " << e.invalid_states << " of " << e.states << " states invalid ("
            << e.jumps_rejected << " jumps, " << e.held_positions << " held positions, " << e.missing_speed
            << " without a speed: the reason in each row, split points for the readers)"
            << (no_state.empty() ? " -> " + out_path : ": nothing written") << "\n";
  const std::string implausible = acc::describeImplausibleGaps(logs);
  if (!implausible.empty())
    std::cerr << "warning: " << implausible << "\n";
  if (!no_state.empty())
    std::cerr << "error: " << no_state << "\n";
  return no_state.empty();
}
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Pairs a leader's and a follower's NMEA logs by GNSS time with relative_state_node's own code "
               "and writes every paired epoch, valid or not, as a run CSV: time_s, space_gap_m, follower_speed_mps, "
               "leader_speed_mps, ..., valid, invalid_reason. Settings: the node's defaults, its parameter file "
               "(--params, config/relative_state.yaml documents each key), then these options."};
  acc::NmeaPairingOptions options;
  std::string leader_path, follower_path, out_path, json_path;
  app.add_option("--params", options.params_path,
                 "relative_state_node's parameter file (its keys, as config/relative_state.yaml): pair as the node "
                 "would with it")
      ->check(CLI::ExistingFile);
  // The antennas' place and the dropout gap are judged by the library's rule (pairingSettingsFrom),
  // the same for this tool, Python and the node; NaN, its "not given", is refused here.
  app.add_option("--antenna-offset-m", options.antennas.combined_m,
                 "antenna to antenna minus bumper to bumper on a straight road [m]")
      ->check(acc::finiteNumber("METRES"));
  app.add_option("--leader-antenna-to-rear-bumper-m", options.antennas.leader_antenna_to_rear_bumper_m, "[m]")
      ->check(acc::finiteNumber("METRES"));
  app.add_option("--follower-antenna-to-front-bumper-m", options.antennas.follower_antenna_to_front_bumper_m, "[m]")
      ->check(acc::finiteNumber("METRES"));
  app.add_option("--gap-mode", options.gap_mode, "straight_line or along_track (default: the file's, else straight_line)")
      ->check(CLI::IsMember({"straight_line", "along_track"}));
  app.add_option("--dropout-gap-s", options.dropout_gap_s,
                 "a longer step is a dropout; above the receivers' step (1 Hz: 2.5) [s] (default: the file's, else "
                 "0.5)")
      ->check(acc::finiteNumber("SECONDS"));
  app.add_option("--json", json_path, "the counts: what each log gave, the pairing, why states are invalid");
  app.add_option("LEADER", leader_path, "leader's NMEA log")->required()->check(CLI::ExistingFile);
  app.add_option("FOLLOWER", follower_path, "follower's NMEA log")->required()->check(CLI::ExistingFile);
  app.add_option("OUT", out_path, "run CSV to write")->required();
  CLI11_PARSE(app, argc, argv);
  if (!acc::outputsLeaveInputsAlone({leader_path, follower_path, options.params_path}, {out_path, json_path},
                                    std::cerr))
    return 2;
  acc::RelativeStateSettings settings;
  std::string unread_note;
  const std::string refused = acc::pairingSettingsFrom(options, settings, unread_note);
  if (!refused.empty())
  {
    std::cerr << "error: " << refused;
    if (refused.find("antenna") != std::string::npos)  // where to say it, in this tool's words
      std::cerr << "; the options: --antenna-offset-m M, or --leader-antenna-to-rear-bumper-m A with "
                   "--follower-antenna-to-front-bumper-m B, or a --params file that places them";
    std::cerr << "\n";
    return 2;
  }
  if (!unread_note.empty())
    std::cerr << "warning: " << options.params_path << ": " << unread_note << "\n";

  const acc::RelativeStateLogs logs = acc::pairNmeaLogsToCsv(leader_path, follower_path, out_path, settings);
  if (!logs.error.empty())
  {
    std::cerr << "error: " << logs.error << "\n";
    return 1;
  }
  const bool paired = report(logs, out_path);
  if (!json_path.empty() && !acc::writeJsonFile(acc::relativeStateLogsJson(logs), json_path, std::cerr))
    return 1;
  return paired ? 0 : 2;
}
