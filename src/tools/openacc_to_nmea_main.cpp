// openacc_to_nmea: an OpenACC two-vehicle CSV (JRC, CC BY 4.0) to the NMEA logs the two cars'
// u-blox receivers would have written, so that the data goes through the drivers like a drive.
#include <iostream>
#include <string>

#include "acc_identification/command_line.h"
#include "acc_identification/conversion/openacc_to_nmea.h"


namespace
{
const char* kUsage =
    "usage: openacc_to_nmea [--talker GN] [--follower NAME|POSITION] INPUT.csv LEADER.nmea FOLLOWER.nmea\n"
    "  Writes GGA + RMC per row for a leader-follower pair of a two-vehicle or platoon file, GNSS\n"
    "  times from the file's Date line and Time column, at u-blox precision, with real checksums.\n"
    "  --follower  the follower by its Vehicle_order name (e.g. BMW_I3) or position (e.g. 3); its\n"
    "              leader is the car directly ahead. Default: the first pair the file holds.\n"
    "  Lat/Lon in radians (the database's notes) or degrees (ZalaZone files) are detected.\n"
    "  Data from the JRC OpenACC database are (c) European Union, CC BY 4.0: credit it and say\n"
    "  that these logs are a conversion of it when you share them.\n";
}  // namespace

int main(int argc, char** argv)
{
  acc::CommandLine cli({"talker", "follower"}, {"help"});
  if (!cli.parse(argc, argv) || cli.has("help") || cli.positional().size() != 3)
  {
    std::cerr << (cli.error().empty() ? "" : "error: " + cli.error() + "\n") << kUsage;
    return cli.has("help") ? 0 : 2;
  }
  const auto& files = cli.positional();
  const auto input = acc::readOpenAccTrajectories(files[0], {cli.value("follower").value_or("")});
  if (!input.error.empty())
  {
    std::cerr << "error: " << input.error << "\n";
    return 1;
  }
  for (const std::string& rejected : input.rejected_rows)
    std::cerr << "warning: " << files[0] << " " << rejected << " (row skipped)\n";
  const std::string talker = cli.value("talker").value_or("GN");
  for (int vehicle : {1, 2})
  {
    std::string error;
    if (!acc::writeNmeaLog(files[vehicle], acc::openAccFixes(input, vehicle), talker, error))
    {
      std::cerr << "error: " << error << "\n";
      return 1;
    }
  }
  std::cout << "openacc_to_nmea: " << input.pairName() << ": " << input.rows.size()
            << " epochs per vehicle written, " << input.rejected_rows.size() << " rows skipped; leader -> "
            << files[1] << ", follower -> " << files[2] << "\n"
            << "  " << input.angle_unit_note << "\n"
            << "source: JRC OpenACC database (c) European Union, CC BY 4.0; converted to NMEA\n";
  return 0;  // skipped rows were each reported above
}
