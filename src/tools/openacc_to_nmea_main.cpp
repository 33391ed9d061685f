// openacc_to_nmea: a leader-follower pair of an OpenACC CSV (JRC, CC BY 4.0) to the NMEA logs the
// two cars' u-blox receivers would have written, so that the data goes through the drivers like a drive.
#include <cctype>
#include <filesystem>
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "acc_identification/conversion/openacc_to_nmea.h"
#include "acc_identification/io/output_files.h"
#include "acc_identification/tools/number_checks.h"

namespace
{
/// The rows of the pair not written, one warning each, then why none can be when so: true when the
/// pair can be written.
bool reportTrack(const acc::OpenAccPairTrack& track)
{
  for (const std::string& skipped : track.skipped_rows)
    std::cerr << "warning: " << skipped << " (row skipped)\n";
  if (!track.error.empty())
    std::cerr << "error: " << track.error << "\n";
  return track.error.empty();
}

/// Writes one pair's two logs and says what was written; false (and a message) when it cannot.
bool writePair(acc::OpenAccPairTrack track, const std::string& leader_path, const std::string& follower_path,
               const std::string& talker, double time_shift_s)
{
  for (acc::OpenAccRow& row : track.rows)
    row.time_of_day_s += time_shift_s;
  for (const auto& [vehicle, path] : {std::pair<int, std::string>{1, leader_path}, {2, follower_path}})
  {
    std::string error;
    if (!acc::writeNmeaLog(path, acc::openAccFixes(track, vehicle), talker, error))
    {
      std::cerr << "error: " << error << "\n";
      return false;
    }
  }
  std::cout << "openacc_to_nmea: " << track.pairName() << ": " << track.rows.size()
            << " epochs per vehicle written, " << track.skipped_rows.size() << " rows skipped; leader -> "
            << leader_path << ", follower -> " << follower_path << "\n"
            << "  " << track.angle_unit_note << "\n"
            << (time_shift_s != 0.0 ? "  times shifted by " + std::to_string(time_shift_s) + " s\n" : std::string());
  return true;
}

/// Every available pair of the file into DIR/<file>_<position>_<FOLLOWER>_{leader,follower}.nmea.
int writeAllPairs(const std::string& input_path, const std::string& dir, const std::string& talker,
                  double time_shift_s)
{
  const acc::OpenAccFile file = acc::readOpenAccFile(input_path);
  if (!file.error.empty())
  {
    std::cerr << "error: " << file.error << "\n";
    return 1;
  }
  for (const std::string& note : file.notes)
    std::cerr << "note: " << note << "\n";
  const std::vector<acc::OpenAccPair> pairs = acc::availablePairs(file);
  if (pairs.empty())
  {
    std::cerr << "error: " << input_path << ": no leader-follower pair with data in this file\n";
    return 1;
  }
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  for (const acc::OpenAccPair& pair : pairs)
  {
    const acc::OpenAccPairTrack track = acc::openAccPairTrack(file, pair);
    if (!reportTrack(track))
      return 1;
    const std::string stem =
        dir + "/" + file.name + "_" + std::to_string(pair.follower_position) + "_" + pair.follower_name;
    if (!writePair(track, stem + "_leader.nmea", stem + "_follower.nmea", talker, time_shift_s))
      return 1;
  }
  return 0;
}
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Writes GGA + RMC per row for a leader-follower pair of a two-vehicle or platoon OpenACC CSV, "
               "GNSS times from the file's Date line and Time column, at u-blox precision, with real checksums. "
               "Lat/Lon in radians (the database's notes) or degrees (ZalaZone files) are detected. Data from the "
               "JRC OpenACC database are (c) European Union, CC BY 4.0: credit it and say that these logs are a "
               "conversion of it when you share them."};
  std::string input_path, leader_path, follower_path, talker = "GN", follower, all_pairs_dir;
  double time_shift_s = 0.0;
  // Two capital letters, as every receiver's talker: '' wrote $GGA, 'X*,' a sentence no parser reads.
  const CLI::Validator two_capitals(
      [](std::string& written) {
        const bool ok = written.size() == 2 && std::isupper(static_cast<unsigned char>(written[0])) &&
                        std::isupper(static_cast<unsigned char>(written[1]));
        return ok ? std::string() : "must be two capital letters (GN, GP, GL, ...), not '" + written + "'";
      },
      "TALKER");
  app.add_option("--talker", talker, "NMEA talker of the sentences")->check(two_capitals)->capture_default_str();
  auto* follower_option = app.add_option(
      "--follower", follower,
      "the follower by its Vehicle_order name (e.g. BMW_I3) or position (e.g. 3); its leader is the car directly "
      "ahead (default: the first pair the file holds)");
  auto* all_pairs_option =
      app.add_option("--all-pairs", all_pairs_dir,
                     "every pair of the file into this folder, as FILE_POSITION_FOLLOWER_{leader,follower}.nmea "
                     "(instead of LEADER and FOLLOWER)")
          ->excludes(follower_option);
  app.add_option("--time-shift-s", time_shift_s,
                 "seconds added to every time of the file, e.g. to lay several runs of one day end to end as one "
                 "session (a change to the data: say so when you share the result)")
      ->capture_default_str()
      ->check(acc::closedInterval(-86400.0, 86400.0, "SECONDS"));
  app.add_option("INPUT", input_path, "OpenACC CSV")->required()->check(CLI::ExistingFile);
  auto* leader_option = app.add_option("LEADER", leader_path, "leader's NMEA log to write")->excludes(all_pairs_option);
  auto* follower_log_option =
      app.add_option("FOLLOWER", follower_path, "follower's NMEA log to write")->excludes(all_pairs_option);
  CLI11_PARSE(app, argc, argv);
  if (!acc::outputsLeaveInputsAlone({input_path}, {leader_path, follower_path}, std::cerr))
    return 2;

  int status = 0;
  if (!all_pairs_dir.empty())
  {
    status = writeAllPairs(input_path, all_pairs_dir, talker, time_shift_s);
  }
  else if (leader_option->count() == 0 || follower_log_option->count() == 0)
  {
    std::cerr << "error: LEADER and FOLLOWER logs are needed (or --all-pairs DIR); see --help\n";
    return 2;
  }
  else
  {
    const acc::OpenAccPairTrack track = acc::readOpenAccPairTrack(
        input_path, follower.empty() ? acc::OpenAccPairSelector::first() : acc::OpenAccPairSelector::byFollower(follower));
    for (const std::string& note : track.notes)
      std::cerr << "note: " << note << "\n";
    status = reportTrack(track) && writePair(track, leader_path, follower_path, talker, time_shift_s) ? 0 : 1;
  }
  if (status == 0)
    std::cout << "source: JRC OpenACC database (c) European Union, CC BY 4.0; converted to NMEA\n";
  return status;  // skipped rows were each reported above
}
