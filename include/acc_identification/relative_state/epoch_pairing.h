#pragma once

#include <acc_identification/gnss/gnss_fix.h>
#include <acc_identification/relative_state/clock_reset_rule.h>

#include <cstddef>
#include <cstdint>
#include <deque>
#include <optional>
#include <string>
#include <vector>

namespace acc
{
/// How the two vehicles' fixes are paired by GNSS epoch (never by arrival time: the leader's
/// fixes may come over a wireless link, late and in bursts). All times are GNSS times [s].
struct PairingSettings
{
  /// Leader and follower epochs closer than this are the same epoch (no interpolation).
  double exact_match_tolerance_s = 0.005;
  /// Interpolation only between two leader epochs each within this of the follower's epoch, so
  /// that a leader gap is never bridged (at 10 Hz, 0.15 s allows one epoch of phase offset).
  double max_interpolation_skew_s = 0.15;
  /// How far out of order the leader's fixes may arrive (leader GNSS time behind its newest).
  /// When the leader's epochs fall on the follower's and the one at the follower's epoch is
  /// missing, it may still come: wait until the leader's stream is this far past it before
  /// interpolating across it. An exact epoch beats an interpolated one; out-of-order arrivals
  /// within this span are paired exactly. And a follower epoch whose missing leader fixes the
  /// leader's stream is further past than this can never be paired: it is given up at once, not
  /// after timeout_s. (The leader's epoch period is learnt as the smallest spacing seen so far.)
  double exact_wait_s = 0.5;
  /// A follower epoch waits at most this long, measured on the follower's GNSS clock, for leader
  /// data that can still arrive (the leader's stream has not yet reached it, or is past it by
  /// less than exact_wait_s); then it is counted as unpaired. The latency budget of the radio link.
  double timeout_s = 2.0;
  /// Successive epochs of one stream further apart than this are a dropout (counted, logged).
  double dropout_gap_s = 0.5;
  /// A stream going back in time by more than this is a time reset (a looping bag, a receiver
  /// reset): its state is cleared. A smaller step back is an out-of-order arrival.
  double time_reset_s = 5.0;
  /// A time reset is taken once this many fixes in a row run on the new clock (they are then
  /// paired as usual, a few epochs late); fewer, after which the stream is back on its clock, are
  /// stray time stamps (a glitched or corrupted time): counted, not used, and nothing is cleared.
  /// A fix more than time_reset_s AHEAD of the stream waits for as many too (after a dropout that
  /// long, the first few epochs are paired a little late), so that one stamp an hour ahead is a
  /// stray stamp and not a clock the stream then seems to fall back from (ClockResetRule).
  std::size_t time_reset_confirm_fixes = 5;
  /// Bound on the fixes held per stream, against a stream that never pairs.
  std::size_t max_buffered_fixes = 2000;
};

/// Why these settings cannot pair a stream, or "" when they can: time_reset_s must exceed
/// dropout_gap_s. The fixes of a new clock are held until time_reset_confirm_fixes follow one
/// another within time_reset_s (ClockResetRule): a time_reset_s below the stream's step, which a
/// working dropout_gap_s exceeds, would take every new clock for stray stamps.
std::string describePairingSettingsProblem(const PairingSettings& settings);

/// Why fixes were not paired, and how the pairs were made. Every fix is counted once in
/// *_fixes and at most once in one of the rejection counters: nothing is dropped silently.
struct PairingCounters
{
  std::uint64_t leader_fixes = 0;
  std::uint64_t follower_fixes = 0;
  std::uint64_t exact_pairs = 0;
  std::uint64_t interpolated_pairs = 0;
  std::uint64_t leader_invalid_fixes = 0;    ///< no usable position (quality 0, no GGA, off the Earth) or no time: not used
  std::uint64_t follower_invalid_fixes = 0;
  std::uint64_t leader_duplicates = 0;       ///< same epoch received twice: the second ignored
  std::uint64_t follower_duplicates = 0;
  std::uint64_t leader_out_of_order = 0;     ///< arrived after a later epoch (still used)
  std::uint64_t follower_out_of_order = 0;   ///< arrived after a later epoch (used if in time)
  std::uint64_t follower_too_late = 0;       ///< arrived after a later pair was already output
  std::uint64_t leader_too_late = 0;         ///< older than every follower epoch still waiting
  std::uint64_t follower_unpaired = 0;       ///< no leader data within the skew: the leader's
                                             ///< stream passed it, or it timed out
  std::uint64_t leader_dropouts = 0;         ///< gaps longer than dropout_gap_s in the stream
  std::uint64_t follower_dropouts = 0;
  std::uint64_t leader_time_resets = 0;      ///< time went back more than time_reset_s (confirmed)
  std::uint64_t follower_time_resets = 0;
  std::uint64_t leader_stray_stamps = 0;     ///< fixes stamped far back or ahead, the stream then back on its clock: not used
  std::uint64_t follower_stray_stamps = 0;
  std::uint64_t buffer_overflows = 0;        ///< oldest fixes discarded at max_buffered_fixes
};

/// A report for the log. Stream events (dropouts, time resets) are rare and each one is worth a
/// line; per-epoch events (an unpaired or late epoch, an invalid sample) can come ten a second.
struct PairingEvent
{
  bool per_epoch = false;
  std::string text;
};

/// One follower epoch with the leader at that same GNSS time.
struct PairedEpoch
{
  double time_s = GnssFix::kNaN;  ///< the follower's epoch
  GnssFix leader;                 ///< at time_s: a received epoch, or interpolated
  GnssFix follower;
  double epoch_skew_s = 0.0;      ///< to the nearest received leader epoch; 0 when exact
  bool interpolated = false;
  /// True when the previous output pair is not the previous follower epoch (first pair, after
  /// a dropout, an unpaired epoch or a time reset): differences across it are not physical.
  bool continuity_break = true;
};

/// Pairs follower epochs with the leader's position at the same GNSS time. Output is driven by
/// the follower's epochs, in increasing GNSS time; a follower epoch waits (up to timeout_s) for
/// leader data around it that can still arrive, so late and out-of-order leader fixes are still
/// used, and an epoch that can no longer be paired holds back none behind it.
class EpochPairer
{
public:
  explicit EpochPairer(PairingSettings settings = {});

  void addLeader(const GnssFix& fix);
  void addFollower(const GnssFix& fix);

  /// The end of both streams (the end of two logs read in batch): nothing more can arrive, so
  /// every follower epoch still waiting is paired with the leader data there are, or counted as
  /// unpaired. Fixes added after it are paired as before.
  void finish();

  /// Pairs completed since the last call, in increasing GNSS time.
  std::vector<PairedEpoch> takePairs();
  /// Human-readable reports of dropouts, resets, late fixes since the last call (for the log).
  std::vector<PairingEvent> takeEvents();

  const PairingCounters& counters() const { return counters_; }
  /// Follower epochs waiting for a leader epoch, neither paired nor given up yet: with the
  /// counters, every follower fix is accounted for at any moment (a node stopped now loses these).
  std::size_t followerEpochsWaiting() const { return pending_follower_.size(); }
  const PairingSettings& settings() const { return settings_; }
  /// The most pairs one addLeader or addFollower can complete: every follower epoch buffered.
  std::size_t mostPairsAtOnce() const { return settings_.max_buffered_fixes; }

private:
  // kInterpolable: an interpolation is ready, but the leader's own epoch is expected.
  // kWaiting: a leader fix it needs can still arrive. kUnpairable: none can any more.
  /// kOtherClock: the follower's time went back and the leader's has not (leader_reset_awaited_):
  /// the leader's fixes are on another clock than the follower's new epochs, pairing them would
  /// pair positions that many seconds apart; it waits as kWaiting does, and is given up as such.
  enum class Resolution { kPaired, kInterpolable, kWaiting, kUnpairable, kOtherClock };

  /// Routes a fix of one stream: held while a jump back in time awaits confirmation, else checked
  /// (acceptStream) and buffered.
  void addToStream(const GnssFix& fix, bool leader);
  /// Whether the stream's ClockResetRule takes the fix (stamped more than time_reset_s back or
  /// ahead): held awaiting time_reset_confirm_fixes on its clock, or, at the last of them, every
  /// held fix gone on in order (a reset, or the stream's clock after a long dropout). False when the
  /// fix is on the stream's clock: the fixes held before it are then counted as stray stamps.
  bool holdsFarOffStamp(const GnssFix& fix, bool leader);
  /// These held fixes were stray stamps: counted, said, let go of.
  void dropStrayStamps(const std::vector<GnssFix>& stray, bool leader);
  bool acceptStream(const GnssFix& fix, bool leader);
  void noteTimeBases(bool follower_left_leaders_clock);
  void noteDropout(const char* name, double from_s, double to_s, std::size_t& in_a_row);
  void insertLeader(const GnssFix& fix);
  void insertFollower(const GnssFix& fix);
  void resolvePending();
  Resolution tryPair(const GnssFix& follower, PairedEpoch& pair) const;
  bool leaderIsPast(double time_s) const;
  void giveUp(double time_s, Resolution resolution);
  void trimLeader();
  void event(const std::string& text, bool per_epoch = true);

  PairingSettings settings_;
  PairingCounters counters_;
  std::deque<GnssFix> leader_;            // sorted by gnss_time_s
  std::deque<GnssFix> pending_follower_;  // sorted by gnss_time_s
  /// Each stream's fixes stamped far back or ahead, held until their clock is confirmed.
  ClockResetRule<GnssFix> leader_clock_, follower_clock_;
  std::vector<PairedEpoch> ready_;
  std::vector<PairingEvent> events_;
  double newest_leader_s_ = GnssFix::kNaN;
  double leader_period_s_ = GnssFix::kNaN;  // smallest spacing of the leader's epochs seen
  double newest_follower_s_ = GnssFix::kNaN;
  double last_output_s_ = GnssFix::kNaN;  // newest follower epoch resolved (paired or not)
  bool break_before_next_ = true;
  bool arrived_out_of_order_ = false;  // of the fix being added, counted once it is kept
  bool leader_reset_awaited_ = false;  // the follower's time went back, the leader's not yet
  bool finishing_ = false;             // inside finish(): no fix can still arrive
  /// Whether each stream's latest fix carried a date: a stream without one (a receiver sending
  /// neither RMC nor ZDA) is timed from midnight, the other from 1970, and nothing pairs.
  std::optional<bool> leader_dated_, follower_dated_;
  std::size_t leader_dropouts_in_a_row_ = 0;  // consecutive steps of the stream that were dropouts
  std::size_t follower_dropouts_in_a_row_ = 0;
};

/// The fix between a and b at time_s, linear in every field (course by the shorter turn).
GnssFix interpolateFix(const GnssFix& a, const GnssFix& b, double time_s);

/// True when the fix carries a usable position: fix quality above 0, a position on the Earth
/// (latitude within +-90 deg, longitude within +-180 deg; a fix from another driver or a corrupted
/// link may hold anything, and a latitude beyond the pole has no geodesic) and a GNSS time.
bool hasUsablePosition(const GnssFix& fix);

}  // namespace acc
