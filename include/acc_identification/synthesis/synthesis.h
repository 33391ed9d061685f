#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/follower_effects.h"
#include "acc_identification/gnss/gnss_fix.h"
#include "acc_identification/relative_state/vehicle_geometry.h"
#include "acc_identification/synthesis/drive_truth.h"
#include "acc_identification/synthesis/gnss_error_model.h"

namespace acc
{
/// Everything a synthetic drive depends on. The defaults describe a plausible test drive.
struct SynthesisOptions
{
  char profile = 'F';  ///< lead profile of Section III (lead_profiles.h)
  AccParameters parameters;
  EffectSettings effects;  ///< all off: the paper's model
  std::uint64_t seed = 1;
  double epoch_step_s = 0.1;  ///< 10 Hz, as the paper's u-blox receivers
  /// Keep only the first duration_s of the profile (0: the whole profile) [s].
  double duration_s = 0.0;
  /// GNSS (UTC) time of the first epoch [s since the Unix epoch]; default 2026-05-12 10:00:00.
  double start_time_unix_s = 1778580000.0;
  double start_latitude_deg = 45.1300;  ///< where the road starts (the Po plain near Casale)
  double start_longitude_deg = 8.4500;
  double start_altitude_m = 120.0;      ///< road altitude above mean sea level [m]
  double start_heading_rad = 1.0;       ///< initial direction of the road, clockwise from north
  /// Antenna offsets. Their sum is 5.60 m, that of the OpenACC Casale cars, so the relative-state
  /// node's default antenna_offset_m fits the synthetic bags too.
  VehicleGeometry geometry{2.6, 3.0};
  GnssErrorSettings errors;
  /// Nominal receiver status written to GGA (not modelled: constant).
  int satellites_used = 12;
  double hdop = 0.8;
};

/// A synthetic drive: the truth and the fixes each receiver would have sent.
struct SynthesizedDrive
{
  DriveTruth truth;
  std::vector<GnssFix> leader_fixes;
  std::vector<GnssFix> follower_fixes;
  /// Antenna-to-antenna straight-line distance minus the geometry, without GNSS errors, per
  /// epoch: the truth gap as a straight line (a chord of the road on arcs, a few cm shorter).
  std::vector<double> straight_line_gap_m;
};

/// Simulates the drive and places both receivers on the road with their errors. Deterministic:
/// the same options give the same numbers bit for bit. Throws std::invalid_argument for an
/// unknown profile, a step that is not positive or a duration shorter than two epochs.
SynthesizedDrive synthesizeDrive(const SynthesisOptions& options);

/// "2026-05-12T10:00:00" or with a trailing 'Z' or fractional seconds -> Unix seconds; false when
/// not a valid UTC date and time.
bool parseUtcTime(const std::string& text, double* unix_s);

/// Whether a Unix time lies in the years an NMEA log's two-digit year can hold (kNmeaFirstYear
/// to kNmeaFirstYear + 99): outside, its logs would be read back a century off.
bool fitsNmeaYears(double unix_s);

/// synthesize's --start-time: parseUtcTime within the NMEA years into unix_s; "" when read, else
/// why not (the tool's message).
std::string readStartTime(const std::string& text, double* unix_s);

}  // namespace acc
