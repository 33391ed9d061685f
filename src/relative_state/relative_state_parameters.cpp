#include "acc_identification/relative_state/relative_state_parameters.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/parameters/yaml_parameter_source.h"

#include <algorithm>
#include <cmath>
#include <string>

namespace acc
{
namespace
{
/// The largest ~exact_match_tolerance_s: half the epoch step of a 50 Hz receiver.
constexpr double kMaxExactMatchToleranceS = 0.01;

/// One offset, NaN when unset; a NaN set on purpose (.nan) is refused, not taken for "unset".
bool readOffset(ParameterReader& r, const std::string& name, double& offset_m)
{
  return r.read(name, offset_m) && r.require(!r.has(name) || !std::isnan(offset_m), "parameter ~" + name + " is NaN");
}

/// The antennas' place as the parameters give it, their types checked; geometryFromOffsets judges it.
bool readAntennaOffsets(ParameterReader& r, AntennaOffsets& offsets)
{
  return readOffset(r, "antenna_offset_m", offsets.combined_m) &&
         readOffset(r, "leader_antenna_to_rear_bumper_m", offsets.leader_antenna_to_rear_bumper_m) &&
         readOffset(r, "follower_antenna_to_front_bumper_m", offsets.follower_antenna_to_front_bumper_m);
}

bool placeAntennas(ParameterReader& r, const AntennaOffsets& offsets, VehicleGeometry& geometry)
{
  const std::string unplaced = geometryFromOffsets(offsets, geometry);
  return r.require(unplaced.empty(), "parameters ~antenna_offset_m or ~leader_antenna_to_rear_bumper_m with "
                                     "~follower_antenna_to_front_bumper_m: " + unplaced);
}

bool readPairing(ParameterReader& r, PairingSettings& q)
{
  int max_buffered = static_cast<int>(q.max_buffered_fixes);
  int reset_confirm = static_cast<int>(q.time_reset_confirm_fixes);
  const bool ok = r.readAtLeast("max_buffered_fixes", max_buffered, 1) &&
                  r.readAtLeast("time_reset_confirm_fixes", reset_confirm, 1) &&
                  r.readAtLeast("exact_match_tolerance_s", q.exact_match_tolerance_s, 0.0) &&
                  // GNSS epochs carry exact times: a tolerance near a receiver's step (0.02 s at
                  // 50 Hz) takes neighbouring epochs for one, pairing them one epoch off with a
                  // skew of 0 and dropping the rest as duplicates (0.1 s at 10 Hz: gaps off by 2 m).
                  r.require(q.exact_match_tolerance_s <= kMaxExactMatchToleranceS,
                            "parameter ~exact_match_tolerance_s " + printfText("%g", q.exact_match_tolerance_s) +
                                " must be at most " + printfText("%g", kMaxExactMatchToleranceS) +
                                " s: epochs this close are taken for the same epoch (GNSS times are exact)") &&
                  r.readAtLeast("max_interpolation_skew_s", q.max_interpolation_skew_s, 0.0) &&
                  r.readAtLeast("exact_wait_s", q.exact_wait_s, 0.0) && r.readAbove("timeout_s", q.timeout_s, 0.0) &&
                  r.readAbove("dropout_gap_s", q.dropout_gap_s, 0.0) && r.readAbove("time_reset_s", q.time_reset_s, 0.0) &&
                  r.require(describePairingSettingsProblem(q).empty(), "parameter " + describePairingSettingsProblem(q));
  q.max_buffered_fixes = static_cast<std::size_t>(std::max(1, max_buffered));
  q.time_reset_confirm_fixes = static_cast<std::size_t>(std::max(1, reset_confirm));
  return ok;
}

/// The along-track gap and the plausibility and consistency checks.
bool readChecks(ParameterReader& r, RelativeStateSettings& s)
{
  return r.readAbove("track_min_spacing_m", s.track_min_spacing_m, 0.0) &&
         r.readAbove("track_max_length_m", s.track_max_length_m, 0.0) &&
         r.readAbove("track_max_lateral_offset_m", s.track_max_lateral_offset_m, 0.0) &&
         r.readAtLeast("min_speed_for_time_gap_mps", s.min_speed_for_time_gap_mps, 0.0) &&
         r.readAbove("max_gap_rate_mps", s.max_gap_rate_mps, 0.0) &&
         r.readAbove("max_acceleration_mps2", s.max_acceleration_mps2, 0.0) &&
         r.readAtLeast("jump_reference_max_age_s", s.jump_reference_max_age_s, 0.0) &&
         r.readAbove("max_unexplained_gap_step_m", s.max_unexplained_gap_step_m, 0.0) &&
         r.readAbove("consistency_window_s", s.consistency_window_s, 0.0) &&
         r.readAbove("min_held_position_move_m", s.min_held_position_move_m, 0.0);
}
/// Everything but the antennas' place.
bool loadPairingAndGapSettings(ParameterReader& reader, RelativeStateSettings& s)
{
  std::string mode = gapModeName(s.gap_mode);
  return reader.read("gap_mode", mode) &&
         reader.require(parseGapMode(mode, s.gap_mode),
                        "parameter ~gap_mode '" + mode + "' is neither straight_line nor along_track") &&
         readPairing(reader, s.pairing) && readChecks(reader, s);
}
}  // namespace

bool loadRelativeStateSettings(ParameterReader& reader, RelativeStateSettings& s)
{
  AntennaOffsets offsets;
  return readAntennaOffsets(reader, offsets) && loadPairingAndGapSettings(reader, s) &&
         placeAntennas(reader, offsets, s.geometry);
}

bool loadRelativeStateNodeSettings(ParameterReader& reader, RelativeStateNodeSettings& s)
{
  return reader.readAbove("stale_after_s", s.stale_after_s, 0.0) &&
         reader.readAbove("consistency_warn_m", s.consistency_warn_m, 0.0) &&
         reader.readAbove("diagnostic_period_s", s.diagnostic_period_s, 0.0) &&
         reader.read("publish_invalid", s.publish_invalid) && reader.readAtLeast("queue_size", s.queue_size, 1);
}

std::string loadRelativeStateParameterFile(const std::string& path, RelativeStateSettings& settings,
                                           std::string& unread_note, AntennaOffsets& antennas)
{
  const YamlParameterSource source = YamlParameterSource::fromFile(path);
  if (!source.ok())
    return source.error();
  ParameterReader reader(source);
  RelativeStateNodeSettings node_only;
  if (!readAntennaOffsets(reader, antennas) || !loadPairingAndGapSettings(reader, settings) ||
      !loadRelativeStateNodeSettings(reader, node_only))
    return path + ": " + reader.error();
  unread_note = reader.unreadNote();
  const std::string repeated = source.repeatedKeysNote();
  if (!repeated.empty())
    unread_note += (unread_note.empty() ? "" : "; ") + repeated;
  return "";
}

}  // namespace acc
