#pragma once

#include <string>

#include "acc_identification/parameters/parameter_reader.h"
#include "acc_identification/relative_state/relative_state_estimator.h"

namespace acc
{
/// The pairing's and the gap's parameters (config/relative_state.yaml documents each) into
/// settings: false and reader.error() on a bad value (type or range) or on antennas not placed by
/// geometryFromOffsets' rule. One loader for relative_state_node and for nmea_to_csv --params, so
/// that batch and live pair alike.
bool loadRelativeStateSettings(ParameterReader& reader, RelativeStateSettings& settings);

/// The parameters only the live node uses: its health report and its queues.
struct RelativeStateNodeSettings
{
  double stale_after_s = 2.0;
  double consistency_warn_m = 1.0;
  double diagnostic_period_s = 1.0;
  bool publish_invalid = true;
  /// Bursts of late leader fixes come together: queues deep enough for several seconds at 10 Hz.
  int queue_size = 200;
};

/// Reads them (false and reader.error() on a bad value). nmea_to_csv reads them too, and uses
/// none: a file written for the node is then read whole, and only a misspelt key is warned of.
bool loadRelativeStateNodeSettings(ParameterReader& reader, RelativeStateNodeSettings& settings);

/// relative_state_node's parameter file (config/relative_state.yaml's keys) read onto settings as
/// the node reads it (its own keys read too, and unused): "" when read, else why not (the file, or
/// a value's type or range, named as the node names it). unread_note: the keys set and never read
/// (misspelt?), for a warning; antennas: the antennas' place as the file gives it, for the caller
/// to judge with geometryFromOffsets once options that override it are known.
std::string loadRelativeStateParameterFile(const std::string& path, RelativeStateSettings& settings,
                                           std::string& unread_note, AntennaOffsets& antennas);

}  // namespace acc
