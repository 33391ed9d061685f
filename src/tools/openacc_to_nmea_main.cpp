// openacc_to_nmea: a leader-follower pair of an OpenACC CSV (JRC, CC BY 4.0) to the NMEA logs the
// two cars' u-blox receivers would have written, so that the data goes through the drivers like a drive.
#include <iostream>
#include <string>

#include <CLI/CLI.hpp>

#include "acc_identification/conversion/openacc_to_nmea.h"

int main(int argc, char** argv)
{
  CLI::App app{"Writes GGA + RMC per row for a leader-follower pair of a two-vehicle or platoon OpenACC CSV, "
               "GNSS times from the file's Date line and Time column, at u-blox precision, with real checksums. "
               "Lat/Lon in radians (the database's notes) or degrees (ZalaZone files) are detected. Data from the "
               "JRC OpenACC database are (c) European Union, CC BY 4.0: credit it and say that these logs are a "
               "conversion of it when you share them."};
  std::string input_path, leader_path, follower_path, talker = "GN";
  double time_shift_s = 0.0;
  std::string follower;
  app.add_option("--talker", talker, "NMEA talker of the sentences")->capture_default_str();
  app.add_option("--follower", follower,
                 "the follower by its Vehicle_order name (e.g. BMW_I3) or position (e.g. 3); its leader is the "
                 "car directly ahead (default: the first pair the file holds)");
  app.add_option("--time-shift-s", time_shift_s,
                 "seconds added to every time of the file, e.g. to lay several runs of one day end to end as one "
                 "session (a change to the data: say so when you share the result)")
      ->capture_default_str()
      ->check(CLI::Range(-86400.0, 86400.0));
  app.add_option("INPUT", input_path, "OpenACC CSV")->required()->check(CLI::ExistingFile);
  app.add_option("LEADER", leader_path, "leader's NMEA log to write")->required();
  app.add_option("FOLLOWER", follower_path, "follower's NMEA log to write")->required();
  CLI11_PARSE(app, argc, argv);

  auto input = acc::readOpenAccPairTrack(
      input_path, follower.empty() ? acc::OpenAccPairSelector::first() : acc::OpenAccPairSelector::byFollower(follower));
  if (!input.error.empty())
  {
    std::cerr << "error: " << input.error << "\n";
    return 1;
  }
  for (const std::string& note : input.notes)
    std::cerr << "note: " << note << "\n";
  for (const std::string& skipped : input.skipped_rows)
    std::cerr << "warning: " << skipped << " (row skipped)\n";
  for (acc::OpenAccRow& row : input.rows)
    row.time_of_day_s += time_shift_s;
  for (const auto& [vehicle, path] : {std::pair<int, std::string>{1, leader_path}, {2, follower_path}})
  {
    std::string error;
    if (!acc::writeNmeaLog(path, acc::openAccFixes(input, vehicle), talker, error))
    {
      std::cerr << "error: " << error << "\n";
      return 1;
    }
  }
  std::cout << "openacc_to_nmea: " << input.pairName() << ": " << input.rows.size()
            << " epochs per vehicle written, " << input.skipped_rows.size() << " rows skipped; leader -> "
            << leader_path << ", follower -> " << follower_path << "\n"
            << "  " << input.angle_unit_note << "\n"
            << (time_shift_s != 0.0 ? "  times shifted by " + std::to_string(time_shift_s) + " s\n" : std::string())
            << "source: JRC OpenACC database (c) European Union, CC BY 4.0; converted to NMEA\n";
  return 0;  // skipped rows were each reported above
}
