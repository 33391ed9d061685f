#pragma once

#include <acc_identification/gnss/gnss_fix.h>
#include <acc_identification/relative_state/epoch_pairing.h>
#include <acc_identification/relative_state/gap_doppler_consistency.h>
#include <acc_identification/relative_state/gap_step_check.h>
#include <acc_identification/relative_state/relative_state.h>
#include <acc_identification/relative_state/vehicle_geometry.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace acc
{
enum class GapMode
{
  kStraightLine,  ///< chord between the antennas (the paper, OpenACC)
  kAlongTrack,    ///< along the leader's recent path: longer than the chord on curves
};

struct RelativeStateSettings
{
  PairingSettings pairing;
  VehicleGeometry geometry;
  GapMode gap_mode = GapMode::kStraightLine;
  /// Along-track path: point spacing, length kept, and how far off it the follower may be.
  double track_min_spacing_m = 2.0;
  double track_max_length_m = 500.0;
  double track_max_lateral_offset_m = 5.0;
  /// time_gap is NaN below this follower speed (it diverges at standstill).
  double min_speed_for_time_gap_mps = 1.0;
  /// Physically impossible jumps between successive pairs: the gap cannot change faster than
  /// this (it changes at the relative speed), nor either car's speed faster than the
  /// acceleration bound. Checked against the last accepted pair when it is at most
  /// jump_reference_max_age_s old, so that a real step (e.g. RTK fixing) costs that long at most,
  /// or one step of the stream (pairing.dropout_gap_s, for receivers at 1 Hz or slower).
  double max_gap_rate_mps = 30.0;
  double max_acceleration_mps2 = 15.0;
  double jump_reference_max_age_s = 1.0;
  /// A gap further than this from where the Doppler speeds carry the last valid one, across the
  /// samples held since, is held invalid (GapStepCheck): a step that outlasts the jump check.
  double max_unexplained_gap_step_m = 5.0;
  /// Gap-versus-Doppler consistency window (see GapDopplerConsistency).
  double consistency_window_s = 10.0;
  /// A receiver whose position is the same as in its previous paired epoch while its speed says
  /// it moved more than this holds its position between updates (OpenACC ZalaZone run 26: the
  /// follower's position updated every third or fourth epoch, so the gap grew by its speed each
  /// epoch and jumped back, steps the jump bound allows). Such a sample is invalid.
  double min_held_position_move_m = 0.5;
};

/// Counters of the estimator itself (the pairing has its own, PairingCounters).
struct RelativeStateCounters
{
  std::uint64_t states = 0;
  std::uint64_t invalid_states = 0;
  std::uint64_t jumps_rejected = 0;
  std::uint64_t missing_speed = 0;
  std::uint64_t along_track_fallbacks = 0;  ///< straight line used instead (reason logged)
  std::uint64_t held_positions = 0;         ///< samples with a held position (min_held_position_move_m)
};

/// From the two receivers' fixes to RelativeState samples: pairing by GNSS epoch, geometry,
/// the jump bound and the gap-versus-Doppler consistency. ROS-free.
class RelativeStateEstimator
{
public:
  explicit RelativeStateEstimator(RelativeStateSettings settings = {});

  void addLeader(const GnssFix& fix);
  void addFollower(const GnssFix& fix);

  /// The end of both streams (EpochPairer::finish): the epochs still waiting become states or
  /// are counted as unpaired.
  void finish();

  /// States completed since the last call, in increasing GNSS time (valid or not, with reason).
  std::vector<RelativeState> takeStates();
  /// Reports of dropouts, resets, rejected jumps since the last call, for the log.
  std::vector<PairingEvent> takeEvents();

  const PairingCounters& pairingCounters() const { return pairer_.counters(); }
  std::size_t followerEpochsWaiting() const { return pairer_.followerEpochsWaiting(); }
  /// The most states one addLeader or addFollower can complete (one per pair).
  std::size_t mostStatesAtOnce() const { return pairer_.mostPairsAtOnce(); }
  const RelativeStateCounters& counters() const { return counters_; }
  /// The gap-versus-Doppler check of the recent valid states (for the diagnostics).
  const GapDopplerConsistency& consistency() const { return consistency_; }
  const RelativeStateSettings& settings() const { return settings_; }

private:
  void process(const PairedEpoch& pair);
  double gap(const PairedEpoch& pair);
  /// Why the sample's gap or a speed jumped from the last valid sample's beyond what a car does
  /// ("" when neither did); speed_jumped says whether a speed did, whatever the gap did.
  std::string jumpReason(const RelativeState& state, bool* speed_jumped) const;
  /// Why the pair's positions cannot be used ("" when they can), and the fixes remembered.
  std::string heldPositionReason(const PairedEpoch& pair);

  RelativeStateSettings settings_;
  EpochPairer pairer_;
  LeaderTrack track_;
  GapDopplerConsistency consistency_;
  GapStepCheck step_check_;
  RelativeStateCounters counters_;
  std::vector<RelativeState> states_;
  std::vector<PairingEvent> events_;
  std::uint64_t leader_resets_seen_ = 0;
  GnssFix last_leader_, last_follower_;  // of the previous pair (none yet: NaN), for the held-position check
  bool has_reference_ = false;
  RelativeState reference_;  // last accepted state, for the jump bound
};

const char* gapModeName(GapMode mode);
/// "straight_line" or "along_track"; false when neither.
bool parseGapMode(const std::string& name, GapMode& mode);

}  // namespace acc
