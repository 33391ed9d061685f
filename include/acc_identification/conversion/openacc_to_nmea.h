#pragma once

#include <acc_identification/conversion/openacc_trajectories.h>
#include <acc_identification/gnss/gnss_fix.h>

#include <cstddef>
#include <string>
#include <vector>

namespace acc
{
/// The fixes a receiver on one OpenACC vehicle (1 = leader, 2 = follower) would have sent:
/// - time: the file's Date plus its Time column (the common clock of both vehicles);
/// - position: Lat/Lon (radians in the file) in degrees, altitude where the file has one;
/// - speed: the Doppler speed column;
/// - course: the geodesic azimuth between the neighbouring rows' Lat/Lon (central difference,
///   one-sided at the ends of a contiguous stretch). Lat/Lon rather than the file's E/N, since
///   the ENU plane's north drifts from true north away from its centre (0.2 deg 20 km east of
///   it at 45 deg N). Below 0.5 m/s, or under 5 cm of motion, no course is sent, as the
///   direction of motion is noise there;
/// - quality: 1 (autonomous GNSS): the file does not say; satellites, HDOP and sigmas unknown,
///   so not sent.
std::vector<GnssFix> openAccFixes(const OpenAccTrajectories& file, int vehicle);

/// Writes GGA + RMC per fix, CR LF terminated, at u-blox precision (see nmea_writer.h).
/// Returns false and sets error when the file cannot be written.
bool writeNmeaLog(const std::string& path, const std::vector<GnssFix>& fixes, const std::string& talker,
                  std::string& error);

}  // namespace acc
