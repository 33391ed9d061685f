#include <acc_identification/relative_state/epoch_pairing.h>
#include <acc_identification/model/angles.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

namespace acc
{
namespace
{

double lerp(double a, double b, double w) { return a + (b - a) * w; }

/// The angle between a and b [rad] on the shorter turn, in [0, 2 pi).
double lerpAngle(double a, double b, double w)
{
  double turn = std::remainder(b - a, 2.0 * kPi);
  double angle = std::fmod(a + turn * w, 2.0 * kPi);
  return angle < 0.0 ? angle + 2.0 * kPi : angle;
}

double lerpLongitude(double a, double b, double w)
{
  double angle = a + std::remainder(b - a, 360.0) * w;
  return std::remainder(angle, 360.0);  // back into [-180, 180]
}

std::string seconds(double value)
{
  std::ostringstream out;
  out << std::fixed << std::setprecision(2) << value;
  return out.str();
}

bool earlier(const GnssFix& fix, double time_s) { return fix.gnss_time_s < time_s; }
}  // namespace

std::string describePairingSettingsProblem(const PairingSettings& settings)
{
  if (settings.time_reset_s > settings.dropout_gap_s)
    return "";
  std::ostringstream why;
  why << "~time_reset_s " << settings.time_reset_s << " must exceed ~dropout_gap_s " << settings.dropout_gap_s
      << ": a new clock's fixes must follow one another within time_reset_s to be taken for one (raise "
         "time_reset_s above the receiver's step and dropout_gap_s)";
  return why.str();
}

bool hasUsablePosition(const GnssFix& fix)
{
  return fix.fix_quality > 0 && fix.has(GnssFix::kValidPosition) && std::abs(fix.latitude_deg) <= 90.0 &&
         std::abs(fix.longitude_deg) <= 180.0 && std::isfinite(fix.gnss_time_s);
}

GnssFix interpolateFix(const GnssFix& a, const GnssFix& b, double time_s)
{
  double span = b.gnss_time_s - a.gnss_time_s;
  double w = span > 0.0 ? (time_s - a.gnss_time_s) / span : 0.0;
  GnssFix fix = a;
  fix.gnss_time_s = time_s;
  fix.receive_time_s = std::max(a.receive_time_s, b.receive_time_s);
  fix.latitude_deg = lerp(a.latitude_deg, b.latitude_deg, w);
  fix.longitude_deg = lerpLongitude(a.longitude_deg, b.longitude_deg, w);
  fix.altitude_m = lerp(a.altitude_m, b.altitude_m, w);
  fix.speed_over_ground_mps = lerp(a.speed_over_ground_mps, b.speed_over_ground_mps, w);
  fix.course_rad = lerpAngle(a.course_rad, b.course_rad, w);
  // Conservative: the worse of the two epochs' quality figures.
  fix.fix_quality = std::min(a.fix_quality, b.fix_quality);
  fix.satellites_used = std::min(a.satellites_used, b.satellites_used);
  fix.hdop = std::max(a.hdop, b.hdop);
  fix.latitude_sigma_m = std::max(a.latitude_sigma_m, b.latitude_sigma_m);
  fix.longitude_sigma_m = std::max(a.longitude_sigma_m, b.longitude_sigma_m);
  fix.altitude_sigma_m = std::max(a.altitude_sigma_m, b.altitude_sigma_m);
  fix.valid_fields = a.valid_fields & b.valid_fields;
  return fix;
}

EpochPairer::EpochPairer(PairingSettings settings)
  : settings_(settings),
    leader_clock_(settings.time_reset_s, settings.time_reset_confirm_fixes),
    follower_clock_(settings.time_reset_s, settings.time_reset_confirm_fixes)
{
}

void EpochPairer::addLeader(const GnssFix& fix)
{
  ++counters_.leader_fixes;
  addToStream(fix, true);
  resolvePending();
}

void EpochPairer::addFollower(const GnssFix& fix)
{
  ++counters_.follower_fixes;
  addToStream(fix, false);
  resolvePending();
}

void EpochPairer::addToStream(const GnssFix& fix, bool leader)
{
  (leader ? leader_dated_ : follower_dated_) = fix.has_date;
  if (hasUsablePosition(fix) && holdsFarOffStamp(fix, leader))
    return;
  if (acceptStream(fix, leader))
    leader ? insertLeader(fix) : insertFollower(fix);
}

bool EpochPairer::holdsFarOffStamp(const GnssFix& fix, bool leader)
{
  const ClockResetRule<GnssFix>::Step step = (leader ? leader_clock_ : follower_clock_)
                                                 .next(fix, fix.gnss_time_s, leader ? newest_leader_s_ : newest_follower_s_);
  if (!step.stray.empty())
    dropStrayStamps(step.stray, leader);
  for (const GnssFix& f : step.released)  // the first is the reset or the dropout (acceptStream), the rest follow it
    if (acceptStream(f, leader))
      leader ? insertLeader(f) : insertFollower(f);
  return step.held || !step.released.empty();
}

void EpochPairer::dropStrayStamps(const std::vector<GnssFix>& stray, bool leader)
{
  const char* name = leader ? "leader" : "follower";
  (leader ? counters_.leader_stray_stamps : counters_.follower_stray_stamps) += stray.size();
  event(std::to_string(stray.size()) + " " + name + " fix(es) stamped " + seconds(stray.front().gnss_time_s) +
            " s, far from the stream's " + seconds(leader ? newest_leader_s_ : newest_follower_s_) +
            " s, and fewer than " + std::to_string(settings_.time_reset_confirm_fixes) +
            " in a row: stray time stamps, not used (no reset)",
        false);
}

std::vector<PairedEpoch> EpochPairer::takePairs()
{
  std::vector<PairedEpoch> pairs;
  pairs.swap(ready_);
  return pairs;
}

std::vector<PairingEvent> EpochPairer::takeEvents()
{
  std::vector<PairingEvent> events;
  events.swap(events_);
  return events;
}

void EpochPairer::event(const std::string& text, bool per_epoch) { events_.push_back({per_epoch, text}); }

// Stream-level checks on one fix, in GNSS time: usable, time reset, dropout, order.
bool EpochPairer::acceptStream(const GnssFix& fix, bool leader)
{
  const char* name = leader ? "leader" : "follower";
  if (!hasUsablePosition(fix))
  {
    ++(leader ? counters_.leader_invalid_fixes : counters_.follower_invalid_fixes);
    event(std::string(name) + " fix without a usable position (quality " + std::to_string(fix.fix_quality) +
          ") ignored");
    return false;
  }
  double& newest = leader ? newest_leader_s_ : newest_follower_s_;
  double t = fix.gnss_time_s;
  if (std::isfinite(newest) && t < newest - settings_.time_reset_s)
  {
    ++(leader ? counters_.leader_time_resets : counters_.follower_time_resets);
    event(std::string(name) + " time went back from " + seconds(newest) + " s to " + seconds(t) +
          " s (looping bag or receiver reset): " + name + " state cleared", false);
    if (leader)
    {
      leader_.clear();
      leader_period_s_ = GnssFix::kNaN;
    }
    else
    {
      counters_.follower_unpaired += pending_follower_.size();
      pending_follower_.clear();
      last_output_s_ = GnssFix::kNaN;
      break_before_next_ = true;
    }
    // The leader still on the clock the follower left (not reset before it, as a looping log's
    // leader may be): the follower's new epochs are on another clock than the leader's.
    const bool leader_on_old_clock = !leader && newest_leader_s_ >= newest - settings_.time_reset_s;
    newest = t;
    arrived_out_of_order_ = false;
    noteTimeBases(leader_on_old_clock);
    return true;
  }
  const bool dropout = std::isfinite(newest) && t > newest + settings_.dropout_gap_s;
  if (dropout)
  {
    ++(leader ? counters_.leader_dropouts : counters_.follower_dropouts);
    noteDropout(name, newest, t, leader ? leader_dropouts_in_a_row_ : follower_dropouts_in_a_row_);
  }
  else if (std::isfinite(newest) && t > newest)
  {
    (leader ? leader_dropouts_in_a_row_ : follower_dropouts_in_a_row_) = 0;
  }
  arrived_out_of_order_ = std::isfinite(newest) && t < newest - settings_.exact_match_tolerance_s;
  newest = std::isfinite(newest) ? std::max(newest, t) : t;
  noteTimeBases(false);
  return true;
}

// A stream whose every step is a dropout is recorded more coarsely than dropout_gap_s (a receiver
// at 1 Hz against the default 0.5 s): after a few in a row that is said once, with what to do, and
// its further dropouts are reported throttled (still each counted).
void EpochPairer::noteDropout(const char* name, double from_s, double to_s, std::size_t& in_a_row)
{
  constexpr std::size_t kInARowForCoarse = 3;
  ++in_a_row;
  const std::string what = std::string(name) + " dropout: no epoch from " + seconds(from_s) + " s to " + seconds(to_s) + " s";
  if (in_a_row < kInARowForCoarse)
  {
    event(what, false);
    return;
  }
  if (in_a_row == kInARowForCoarse)
  {
    event(std::string(name) + ": " + std::to_string(kInARowForCoarse) + " dropouts in a row, the last " +
              seconds(to_s - from_s) + " s: the stream is recorded more coarsely than dropout_gap_s (" +
              seconds(settings_.dropout_gap_s) + " s), a receiver at 1 Hz? Raise dropout_gap_s above its step "
              "(nmea_to_csv --dropout-gap-s 2.5 at 1 Hz, and calibrate then --max-gap 2.5; live, the launch "
              "files' max_gap_s:=2.5 raises both)",
          false);
  }
  event(what, true);
}

// After a time reset of the follower (a looping bag, a receiver reset) the leader, still on the
// old time base far ahead, is about to follow it: until it does, how far its stream is past the
// follower's new epochs says nothing of what can still come for them, and its fixes are on another
// clock than theirs (tryPair pairs none). Over once the two streams' newest epochs are within
// time_reset_s again (the leader has reset too, or the follower's time came back). A follower
// merely arriving late, without a reset, is not this; nor is a follower resetting onto a clock the
// leader reset to before it (a looping log whose leader loops first).
void EpochPairer::noteTimeBases(bool follower_left_leaders_clock)
{
  bool leader_far_ahead = newest_leader_s_ > newest_follower_s_ + settings_.time_reset_s;
  leader_reset_awaited_ = leader_far_ahead && (leader_reset_awaited_ || follower_left_leaders_clock);
}

void EpochPairer::insertLeader(const GnssFix& fix)
{
  double t = fix.gnss_time_s;
  double tolerance = settings_.exact_match_tolerance_s;
  // (A fix from before a follower time reset, far older, belongs to another time base: kept.)
  bool same_time_base = t >= last_output_s_ - settings_.time_reset_s;
  if (std::isfinite(last_output_s_) && same_time_base && t < last_output_s_ - settings_.max_interpolation_skew_s)
  {
    ++counters_.leader_too_late;
    event("leader epoch " + seconds(t) + " s arrived after the follower epochs it could serve");
    return;
  }
  auto at = std::lower_bound(leader_.begin(), leader_.end(), t - tolerance, earlier);
  if (at != leader_.end() && std::abs(at->gnss_time_s - t) <= tolerance)
  {
    ++counters_.leader_duplicates;
    return;
  }
  if (arrived_out_of_order_)
    ++counters_.leader_out_of_order;
  at = leader_.insert(at, fix);
  for (auto neighbour : {at == leader_.begin() ? at : std::prev(at), std::next(at)})
  {
    double spacing = neighbour == leader_.end() ? 0.0 : std::abs(neighbour->gnss_time_s - t);
    if (spacing > tolerance && !(spacing >= leader_period_s_))
      leader_period_s_ = spacing;
  }
  if (leader_.size() > settings_.max_buffered_fixes)
  {
    ++counters_.buffer_overflows;
    leader_.pop_front();
  }
}

void EpochPairer::insertFollower(const GnssFix& fix)
{
  double t = fix.gnss_time_s;
  double tolerance = settings_.exact_match_tolerance_s;
  if (std::isfinite(last_output_s_) && t <= last_output_s_ + tolerance)
  {
    if (std::abs(t - last_output_s_) <= tolerance)
      ++counters_.follower_duplicates;
    else
    {
      ++counters_.follower_too_late;
      event("follower epoch " + seconds(t) + " s arrived after a later pair was output: not paired");
    }
    return;
  }
  auto at = std::lower_bound(pending_follower_.begin(), pending_follower_.end(), t - tolerance, earlier);
  if (at != pending_follower_.end() && std::abs(at->gnss_time_s - t) <= tolerance)
  {
    ++counters_.follower_duplicates;
    return;
  }
  if (arrived_out_of_order_)
    ++counters_.follower_out_of_order;
  pending_follower_.insert(at, fix);
  if (pending_follower_.size() > settings_.max_buffered_fixes)
  {
    ++counters_.buffer_overflows;
    ++counters_.follower_unpaired;
    pending_follower_.pop_front();
  }
}

// Follower epochs are resolved strictly in time order, so that the output never goes back.
void EpochPairer::resolvePending()
{
  while (!pending_follower_.empty())
  {
    const GnssFix& follower = pending_follower_.front();
    double t = follower.gnss_time_s;
    PairedEpoch pair;
    Resolution resolution = tryPair(follower, pair);
    bool timed_out = finishing_ || newest_follower_s_ - t > settings_.timeout_s;
    if ((resolution == Resolution::kWaiting || resolution == Resolution::kOtherClock) && !timed_out)
      break;
    if (resolution == Resolution::kInterpolable && !leaderIsPast(t) && !timed_out)
      break;
    if (resolution == Resolution::kPaired || resolution == Resolution::kInterpolable)
    {
      bool follower_gap = std::isfinite(last_output_s_) && t - last_output_s_ > settings_.dropout_gap_s;
      pair.continuity_break = break_before_next_ || follower_gap;
      break_before_next_ = false;
      ++(pair.interpolated ? counters_.interpolated_pairs : counters_.exact_pairs);
      ready_.push_back(pair);
    }
    else
      giveUp(t, resolution);
    last_output_s_ = t;
    pending_follower_.pop_front();
  }
  trimLeader();
}

void EpochPairer::finish()
{
  // Fewer fixes on a new clock than confirm a reset, at the end of the streams: counted as stray.
  for (const bool leader : {true, false})
    if (const std::vector<GnssFix> stray = (leader ? leader_clock_ : follower_clock_).endOfStream(); !stray.empty())
      dropStrayStamps(stray, leader);
  finishing_ = true;
  resolvePending();
  finishing_ = false;
}

void EpochPairer::giveUp(double time_s, Resolution resolution)
{
  ++counters_.follower_unpaired;
  break_before_next_ = true;
  std::string why = resolution == Resolution::kUnpairable ? "the leader's stream is past it (at " + seconds(newest_leader_s_) + " s)"
                    : resolution == Resolution::kOtherClock
                        ? "the follower's time went back and the leader's did not (its newest " +
                              seconds(newest_leader_s_) + " s): the two clocks now disagree, and the leader's fixes "
                              "would pair positions from another moment; pairing resumes when the leader's time goes "
                              "back too (a looping log) or the follower's comes back"
                    : finishing_ ? "and the streams ended"
                                 : "after waiting " + seconds(settings_.timeout_s) + " s";
  // A leader whose epochs are further apart than the skew leaves some follower epochs between two
  // of them unpaired every time: say what to set, not only that they are lost.
  const bool leader_coarser = leader_period_s_ > settings_.max_interpolation_skew_s + settings_.exact_match_tolerance_s;
  if (leader_dated_ && follower_dated_ && *leader_dated_ != *follower_dated_)
    why += std::string("; the ") + (*leader_dated_ ? "follower" : "leader") +
           "'s fixes carry no date (its receiver sends neither RMC nor ZDA): its times count from midnight, the "
           "other's from 1970, and none pair; enable RMC or ZDA on that receiver";
  event("follower epoch " + seconds(time_s) + " s unpaired: no leader epoch within " +
        seconds(settings_.max_interpolation_skew_s) + " s, " + why +
        (leader_coarser ? "; the leader's epochs are " + seconds(leader_period_s_) +
                              " s apart, more than max_interpolation_skew_s: set it to that period to pair "
                              "every follower epoch between two of them"
                        : ""));
}

// The leader's fixes arrive in GNSS-time order but for reordering within exact_wait_s: once its
// newest is further past time_s than that, no fix at or before time_s can come any more.
bool EpochPairer::leaderIsPast(double time_s) const
{
  return !leader_reset_awaited_ && newest_leader_s_ - time_s > settings_.exact_wait_s;
}

EpochPairer::Resolution EpochPairer::tryPair(const GnssFix& follower, PairedEpoch& pair) const
{
  double t = follower.gnss_time_s;
  // A loop's leader clears its old fixes when it resets too; a leader that never does runs on the
  // clock the follower left: a follower clock jumped back 20 s would pair its positions with the
  // leader's of 20 s before, a gap hundreds of metres off that every check after the break takes.
  if (leader_reset_awaited_)
    return Resolution::kOtherClock;
  double tolerance = settings_.exact_match_tolerance_s;
  auto after = std::lower_bound(leader_.begin(), leader_.end(), t - tolerance, earlier);
  pair.time_s = t;
  pair.follower = follower;
  if (after != leader_.end() && std::abs(after->gnss_time_s - t) <= tolerance)
  {
    pair.leader = *after;
    pair.leader.gnss_time_s = t;
    pair.epoch_skew_s = 0.0;
    pair.interpolated = false;
    return Resolution::kPaired;
  }
  // Interpolation needs a leader fix on each side within the skew. A missing one may still come
  // (the leader's stream has not reached it, or out of order) until the leader is past it: an
  // exact fix or one before t (so at t + tolerance at the latest), or one after (t + skew).
  // Within the exact tolerance of the skew too: a 5 Hz leader 50 ms off a 10 Hz follower puts
  // every other epoch at exactly 0.15 s, where the rounding of the times decided.
  double skew = settings_.max_interpolation_skew_s + tolerance;
  bool has_before = after != leader_.begin() && t - std::prev(after)->gnss_time_s <= skew;
  bool has_after = after != leader_.end() && after->gnss_time_s - t <= skew;
  if (!has_before || !has_after)
    return leaderIsPast(has_before ? t + skew : t + tolerance) ? Resolution::kUnpairable : Resolution::kWaiting;
  auto before = std::prev(after);
  double skew_before = t - before->gnss_time_s;
  double skew_after = after->gnss_time_s - t;
  pair.leader = interpolateFix(*before, *after, t);
  pair.epoch_skew_s = std::min(skew_before, skew_after);
  pair.interpolated = true;
  // Is a leader epoch expected right at t (the two streams share the epoch grid, one is missing)?
  double period = leader_period_s_;
  if (std::isfinite(period) && after->gnss_time_s - before->gnss_time_s > 1.5 * period)
  {
    double on_grid = before->gnss_time_s + std::round(skew_before / period) * period;
    if (std::abs(on_grid - t) <= tolerance)
      return Resolution::kInterpolable;
  }
  return Resolution::kPaired;
}

// Leader fixes older than any follower epoch still to come (less the skew) can serve no pair.
void EpochPairer::trimLeader()
{
  double reference = pending_follower_.empty() ? last_output_s_ : pending_follower_.front().gnss_time_s;
  if (!std::isfinite(reference))
    return;
  // After a leader time reset (leader_ was cleared) the leader runs on a new, earlier time base
  // while the follower is still on the old one: every leader fix is then far older than the
  // reference, yet each will serve once the follower resets too. Told apart from old fixes
  // before a hole in the data (an outage, runs laid end to end) by the leader's newest epoch:
  // behind the reference by more than time_reset_s only in the first case.
  if (newest_leader_s_ < reference - settings_.time_reset_s)
    return;
  double oldest_useful = reference - settings_.max_interpolation_skew_s - settings_.exact_match_tolerance_s;
  while (leader_.size() > 1 && leader_[1].gnss_time_s <= oldest_useful)
    leader_.pop_front();
}

}  // namespace acc
