#include <acc_identification/relative_state/relative_state_estimator.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace acc
{
namespace
{
std::string number(double value, int decimals = 2)
{
  std::ostringstream out;
  out << std::fixed << std::setprecision(decimals) << value;
  return out.str();
}

/// How far the receiver's speeds say it moved from `before` to `now` when its position did not
/// change at all (the same latitude and longitude, as read); 0 when it changed or cannot say (also
/// against the default fix before the first pair, whose NaN position equals nothing).
double movedWhileStill(const GnssFix& before, const GnssFix& now)
{
  if (now.latitude_deg != before.latitude_deg || now.longitude_deg != before.longitude_deg ||
      !before.has(GnssFix::kValidSpeed) || !now.has(GnssFix::kValidSpeed) || !(now.gnss_time_s > before.gnss_time_s))
    return 0.0;
  return 0.5 * (before.speed_over_ground_mps + now.speed_over_ground_mps) * (now.gnss_time_s - before.gnss_time_s);
}
}  // namespace

const char* gapModeName(GapMode mode) { return mode == GapMode::kAlongTrack ? "along_track" : "straight_line"; }

bool parseGapMode(const std::string& name, GapMode& mode)
{
  if (name == "straight_line")
    mode = GapMode::kStraightLine;
  else if (name == "along_track")
    mode = GapMode::kAlongTrack;
  else
    return false;
  return true;
}

RelativeStateEstimator::RelativeStateEstimator(RelativeStateSettings settings)
  : settings_(settings)
  , pairer_(settings.pairing)
  , track_(settings.track_min_spacing_m, settings.track_max_length_m, settings.track_max_lateral_offset_m,
           settings.pairing.dropout_gap_s)
  , consistency_(settings.consistency_window_s, settings.pairing.dropout_gap_s)
  , step_check_(settings.max_unexplained_gap_step_m, settings.pairing.dropout_gap_s)
{
}

void RelativeStateEstimator::addLeader(const GnssFix& fix)
{
  pairer_.addLeader(fix);
  if (pairer_.counters().leader_time_resets != leader_resets_seen_)
  {
    leader_resets_seen_ = pairer_.counters().leader_time_resets;
    track_.clear();
  }
  // The path only needs the leader's usable epochs, in time order (late ones are skipped).
  if (settings_.gap_mode == GapMode::kAlongTrack && hasUsablePosition(fix))
    track_.add(fix);
  for (const PairedEpoch& pair : pairer_.takePairs())
    process(pair);
}

void RelativeStateEstimator::addFollower(const GnssFix& fix)
{
  pairer_.addFollower(fix);
  for (const PairedEpoch& pair : pairer_.takePairs())
    process(pair);
}

void RelativeStateEstimator::finish()
{
  pairer_.finish();
  for (const PairedEpoch& pair : pairer_.takePairs())
    process(pair);
}

std::vector<RelativeState> RelativeStateEstimator::takeStates()
{
  std::vector<RelativeState> states;
  states.swap(states_);
  return states;
}

std::vector<PairingEvent> RelativeStateEstimator::takeEvents()
{
  std::vector<PairingEvent> events = pairer_.takeEvents();
  events.insert(events.end(), events_.begin(), events_.end());
  events_.clear();
  return events;
}

double RelativeStateEstimator::gap(const PairedEpoch& pair)
{
  if (settings_.gap_mode == GapMode::kAlongTrack)
  {
    std::string why_not;
    auto along_m = track_.alongTrackDistance(pair.leader, pair.follower, &why_not);
    if (along_m)
      return *along_m - settings_.geometry.combinedOffset();
    ++counters_.along_track_fallbacks;
    events_.push_back({true, "along-track gap unavailable at " + number(pair.time_s) + " s (" + why_not +
                                 "): straight line used"});
  }
  return straightLineGap(pair.leader, pair.follower, settings_.geometry);
}

std::string RelativeStateEstimator::jumpReason(const RelativeState& state, bool* speed_jumped) const
{
  *speed_jumped = false;
  if (!has_reference_)
    return "";
  double dt = state.time_s - reference_.time_s;
  // At least one step of the stream back: a receiver at 1 Hz or slower (dropout_gap_s raised
  // above its step) is checked against its previous epoch too.
  if (dt <= 0.0 || dt > std::max(settings_.jump_reference_max_age_s, settings_.pairing.dropout_gap_s))
    return "";
  // The speeds are judged whatever the gap did: a sample whose position and speed both glitch must
  // keep its speed out of the Doppler integral too.
  double leader_accel = std::abs(state.leader_speed_mps - reference_.leader_speed_mps) / dt;
  double follower_accel = std::abs(state.follower_speed_mps - reference_.follower_speed_mps) / dt;
  *speed_jumped = std::max(leader_accel, follower_accel) > settings_.max_acceleration_mps2;
  double gap_rate = std::abs(state.space_gap_m - reference_.space_gap_m) / dt;
  if (gap_rate > settings_.max_gap_rate_mps)
    return "gap jump of " + number(state.space_gap_m - reference_.space_gap_m) + " m in " + number(dt) +
           " s exceeds max_gap_rate " + number(settings_.max_gap_rate_mps, 1) + " m/s";
  if (*speed_jumped)
    return std::string(leader_accel > follower_accel ? "leader" : "follower") + " speed jump of " +
           number(std::max(leader_accel, follower_accel) * dt) + " m/s in " + number(dt) +
           " s exceeds max_acceleration " + number(settings_.max_acceleration_mps2, 1) + " m/s^2";
  return "";
}

std::string RelativeStateEstimator::heldPositionReason(const PairedEpoch& pair)
{
  const double leader_m = movedWhileStill(last_leader_, pair.leader);
  const double follower_m = movedWhileStill(last_follower_, pair.follower);
  const double since_s = (leader_m >= follower_m ? last_leader_ : last_follower_).gnss_time_s;
  last_leader_ = pair.leader;
  last_follower_ = pair.follower;
  if (std::max(leader_m, follower_m) <= settings_.min_held_position_move_m)
    return "";
  return std::string(leader_m >= follower_m ? "leader" : "follower") + " position held: the same as at " +
         number(since_s) + " s while its speed says it moved " + number(std::max(leader_m, follower_m)) +
         " m (a receiver that repeats its position between updates)";
}

void RelativeStateEstimator::process(const PairedEpoch& pair)
{
  RelativeState state;
  state.time_s = pair.time_s;
  state.has_date = pair.follower.has_date;
  state.epoch_skew_s = pair.epoch_skew_s;
  state.space_gap_m = gap(pair);
  state.space_gap_sigma_m = gapSigma(pair.leader, pair.follower);
  state.leader_speed_mps = pair.leader.has(GnssFix::kValidSpeed) ? pair.leader.speed_over_ground_mps : RelativeState::kNaN;
  state.follower_speed_mps =
      pair.follower.has(GnssFix::kValidSpeed) ? pair.follower.speed_over_ground_mps : RelativeState::kNaN;
  state.relative_speed_mps = state.leader_speed_mps - state.follower_speed_mps;
  if (state.follower_speed_mps >= settings_.min_speed_for_time_gap_mps)
    state.time_gap_s = state.space_gap_m / state.follower_speed_mps;
  if (pair.continuity_break)
  {
    consistency_.reset();
    step_check_.reset();
  }

  const std::string held = heldPositionReason(pair);
  if (!std::isfinite(state.leader_speed_mps) || !std::isfinite(state.follower_speed_mps))
  {
    ++counters_.missing_speed;
    state.invalid_reason = std::string(std::isfinite(state.leader_speed_mps) ? "follower" : "leader") +
                           " speed missing (no RMC/VTG in the epoch)";
  }
  else if (!std::isfinite(state.space_gap_m) || !std::isfinite(state.relative_speed_mps))
  {
    // Speeds that are numbers but no car's (a corrupted field, 1e308) overflow their difference.
    state.invalid_reason = "gap or relative speed not a finite number (a fix's position or speed is no car's)";
  }
  else if (!held.empty())
  {
    ++counters_.held_positions;
    state.invalid_reason = held;
  }
  bool speed_jumped = false;
  if (state.invalid_reason.empty())
    state.invalid_reason = jumpReason(state, &speed_jumped);
  // Every sample whose speeds are the cars' carries the relative speed's integral from the last
  // valid one on; a step the jump check no longer sees (it outlasted jump_reference_max_age_s) is
  // caught here. A rejected speed stays out of it: one Doppler spike of 80 m/s carried the gap 8 m
  // off, and every later sample was rejected as a gap jump the speeds did not explain.
  const std::string unexplained =
      speed_jumped ? "" : step_check_.check(state.time_s, state.space_gap_m, state.relative_speed_mps);
  if (state.invalid_reason.empty())
    state.invalid_reason = unexplained;

  state.valid = state.invalid_reason.empty();
  if (state.valid)
  {
    consistency_.add(state.time_s, state.space_gap_m, state.relative_speed_mps);
    step_check_.anchor(state.time_s, state.space_gap_m, state.relative_speed_mps);
    reference_ = state;
    has_reference_ = true;
  }
  else
  {
    ++counters_.invalid_states;
    if (state.invalid_reason.find("jump") != std::string::npos)
      ++counters_.jumps_rejected;
    events_.push_back({true, "sample at " + number(state.time_s) + " s invalid: " + state.invalid_reason});
  }
  state.gap_doppler_residual_m = consistency_.recentRms();
  ++counters_.states;
  states_.push_back(state);
}

}  // namespace acc
