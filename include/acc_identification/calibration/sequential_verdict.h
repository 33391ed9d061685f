#pragma once

#include <cstddef>
#include <deque>
#include <iosfwd>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/calibration/betting_e_process.h"
#include "acc_identification/calibration/calibration_objective.h"
#include "acc_identification/calibration/side_fits.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/string_stability.h"

namespace acc
{
/// The string-stability verdict of a drive as it grows, valid however often it is looked at: an
/// error over the whole drive at most alpha, and a decision, once taken, kept (derivation and
/// measurements in docs/SEQUENTIAL_VERDICT.md).
///
/// Method (prequential e-processes, testing by betting):
///  1. At each look (data time t), the two side fits of the stability test (fitBothSides: the
///     unconstrained optimum and the best fit on the other side of m = 0) are refitted on all the
///     drive up to t, warm-started from the previous look's fits.
///  2. The drive after the first fits is cut into consecutive blocks of L seconds of data time;
///     L is chosen once, at the first fits, from the correlation of their training speed residual
///     (one correlation time, clamped to [min, max]_block_length_s), then kept. Validity does not
///     depend on L (the null is conditional on the past); L trades the number of bets against what
///     each carries, and a drive of minutes needs about ten bets to reach 1/alpha = 20.
///  3. A block [s, s + L) is scored once the data reach s + L, with the latest fits made at or
///     before s (never with data of the block or after it): each fit simulated (heldOutErrors)
///     from the measured state warm_up_s before the block (or the start of its segment, if later)
///     so that at s it runs on its own state, as in training, not on one noisy measured start;
///     d_b = mean over the block's samples of e_stable^2 - e_unstable^2. x_b = clip(d_b / c_b, -1, 1), c_b = scale_multiple times
///     the RMS of the past d's and of the fits' training mean squared error (one pseudo-block),
///     at least min_scale: predictable.
///  4. Two e-processes (BettingEProcess): E_unstable bets on x_b > 0, against H0_stable
///     "E[x_b | past] <= 0 for every block" (the best stable model predicts each next block at
///     least as well); E_stable bets on x_b < 0, against H0_unstable. Ville: under H0,
///     P(sup_t E_t >= 1/alpha) <= alpha over the whole drive.
///  5. Verdict "unstable" once E_unstable >= 1/alpha, "stable" once E_stable >= 1/alpha, kept from
///     then on; p-values min(1, 1 / max_s E_s) never grow. Should the other e-process later cross
///     too, the verdict becomes the other one and `reversed` says so (evidence meeting the same
///     standard), with both e-values: never withdrawn silently.
///
/// Deterministic given the data and the look times. lookUpTo() makes the looks at the fixed data
/// times drive start + k * look_period_s, so a look delayed (a busy thread) is made late, never
/// lost, and the identifier node and `calibrate --verdict-every` give the same sequence.
struct SequentialVerdictOptions
{
  double alpha = 0.05;
  /// Data time between scheduled looks (lookUpTo) [s].
  double look_period_s = 10.0;
  ParameterBounds bounds;
  /// The first side fits: fresh starts (the online identifier's test defaults).
  MultistartOptions first_multistart = defaultFirstMultistart();
  ConstrainedFitOptions first_constrained = defaultFirstConstrained();
  /// Later looks: from the previous look's fits only, bounded evaluations (the cost of a look
  /// then grows only with the pass over the data).
  MultistartOptions refit_multistart = defaultRefitMultistart();
  ConstrainedFitOptions refit_constrained = defaultRefitConstrained();

  /// Fixed block length [s]; 0: correlation_times correlation times of the first unconstrained
  /// fit's training speed residual, clamped to [min_block_length_s, max_block_length_s].
  double block_length_s = 0.0;
  double correlation_times = 1.0;
  double min_block_length_s = 10.0;
  double max_block_length_s = 60.0;
  /// Each block's simulation starts this long before it [s] (within its segment): started at the
  /// block's own measured start, a 0.4 m gap error makes a sluggish model look better on short
  /// blocks than the model the training (simulations over whole segments) prefers.
  double warm_up_s = 120.0;
  /// A block with fewer scored samples than this fraction of a full block (holes) is skipped:
  /// it neither bets nor counts.
  double min_block_coverage = 0.5;

  /// c_b = scale_multiple * RMS(past d's, training MSE), at least min_scale_m2ps2 [m^2/s^2].
  double scale_multiple = 2.0;
  double min_scale_m2ps2 = 1e-4;
  /// Largest betting fraction of either e-process.
  double max_bet = 0.5;

  /// No fits (and so no blocks) before the drive has this many samples and speed changes.
  std::size_t min_training_samples = 300;
  double min_training_speed_std_mps = 0.1;

  static MultistartOptions defaultFirstMultistart();
  static ConstrainedFitOptions defaultFirstConstrained();
  static MultistartOptions defaultRefitMultistart();
  static ConstrainedFitOptions defaultRefitConstrained();
};

/// What one look says.
struct SequentialLook
{
  double time_s = 0.0;               ///< data time of the look (the drive's own clock)
  std::size_t samples = 0;           ///< drive samples up to time_s
  std::size_t blocks_scored = 0;     ///< blocks that have bet so far
  std::size_t blocks_skipped = 0;    ///< blocks left out (holes, no fits on one side)
  double block_length_s = 0.0;       ///< L (0 before the first fits)
  StabilityVerdict verdict = StabilityVerdict::Undecided;
  /// The verdict's anytime-valid p-value (for "undecided" the smaller of the two).
  double p_value = 1.0;
  double p_value_stable_rejected = 1.0;    ///< H0_stable: 1 / max E_unstable (capped at 1)
  double p_value_unstable_rejected = 1.0;  ///< H0_unstable: 1 / max E_stable
  double e_value_unstable = 1.0;     ///< E_unstable now: evidence against string stability
  double e_value_stable = 1.0;       ///< E_stable now: evidence against string instability
  double alpha = 0.05;
  /// Data time of the end of the block that decided (NaN while undecided).
  double decided_at_s = std::numeric_limits<double>::quiet_NaN();
  /// The other e-process crossed 1/alpha later: verdict is the later side, first_verdict the
  /// earlier one, reversed_at_s when.
  bool reversed = false;
  StabilityVerdict first_verdict = StabilityVerdict::Undecided;
  double reversed_at_s = std::numeric_limits<double>::quiet_NaN();
  /// Margins of the side fits made at this look (NaN when none exists yet).
  double stable_fit_margin = std::numeric_limits<double>::quiet_NaN();
  double unstable_fit_margin = std::numeric_limits<double>::quiet_NaN();
  std::string reason;                ///< why this verdict, in words
  double solve_time_s = 0.0;         ///< wall time of this look
  std::size_t evaluations = 0;       ///< objective passes of this look's side fits
};

class SequentialVerdict
{
public:
  explicit SequentialVerdict(SequentialVerdictOptions options = {});

  /// One look at data time now_s: scores every block complete by now_s (with the fits made before
  /// each began), then refits the side fits on the drive up to now_s. drive_so_far: the drive's
  /// segments (samples after now_s are ignored). A look earlier than the previous one changes
  /// nothing and says so. Never throws on data problems.
  SequentialLook look(const std::vector<CarFollowingRun>& drive_so_far, double now_s);

  /// Every scheduled look (drive start + k * look_period_s) up to last_s not made yet, in order.
  std::vector<SequentialLook> lookUpTo(const std::vector<CarFollowingRun>& drive_so_far, double last_s);

  /// What the identifier node does with the drive so far whenever it can: lookUpTo(its latest
  /// sample), and when the data have stopped (end of a replay, a pause) one more look at that
  /// sample, so that the last verdict judges every sample. Returns the looks made, in order.
  std::vector<SequentialLook> lookLive(const std::vector<CarFollowingRun>& drive_so_far, bool data_stopped);

  /// Forget the drive (a new drive or a time reset).
  void reset();

  const SequentialVerdictOptions& options() const { return options_; }
  /// The latest look (none before the first).
  const std::optional<SequentialLook>& latest() const { return latest_; }

private:
  struct FitsAt
  {
    double trained_until_s = 0.0;
    SideFits fits;
    double training_mse_m2ps2 = 0.0;  ///< of the unconstrained fit, the scale's pseudo-block
  };

  void scoreCompleteBlocks(const std::vector<CarFollowingRun>& segments, double now_s);
  void scoreBlock(const std::vector<CarFollowingRun>& segments, double start_s, const FitsAt& fits);
  /// Returns the objective passes it made.
  std::size_t refit(const std::vector<CarFollowingRun>& segments, double now_s, std::string& note);
  SequentialLook summarize(double now_s, std::size_t samples, const std::string& note) const;

  SequentialVerdictOptions options_;
  std::optional<double> drive_start_s_;
  std::optional<double> last_look_s_;
  std::size_t scheduled_looks_made_ = 0;
  std::deque<FitsAt> fits_;  ///< oldest first; only those a pending block may still need
  double block_length_s_ = 0.0;
  double mean_step_s_ = 0.1;
  std::optional<double> next_block_start_s_;
  std::size_t blocks_scored_ = 0;
  std::size_t blocks_skipped_ = 0;
  double sum_squared_d_ = 0.0;
  /// On x_b = clipped, scaled e_stable^2 - e_unstable^2: positive = unstable.
  SignDecision decision_;
  std::optional<SequentialLook> latest_;
};

/// calibrate --verdict-every: the looks the identifier node makes on a drive (lookLive of the whole
/// drive, the data stopped): every options.look_period_s of data time and one more at the drive's
/// last sample. A new SequentialVerdict for the drive.
std::vector<SequentialLook> replaySequentialVerdict(const std::vector<CarFollowingRun>& drive,
                                                    const SequentialVerdictOptions& options);

/// {time_s, samples, verdict, p_value, e_value_unstable, e_value_stable} (one entry of
/// verdict_sequence).
nlohmann::json toSequenceEntryJson(const SequentialLook& look);
/// Everything of the look: the entry's fields and p_value_stable_rejected,
/// p_value_unstable_rejected, alpha, blocks_scored, blocks_skipped, block_length_s, decided_at_s,
/// reversed, first_verdict, reversed_at_s, stable_fit_margin, unstable_fit_margin, reason,
/// solve_time_s, evaluations (NaN as null).
nlohmann::json toJson(const SequentialLook& look);

/// One line per look: time, samples, blocks scored, both e-values, verdict, its anytime-valid
/// p-value (and REVERSED when it was).
void printVerdictSequence(const std::vector<SequentialLook>& looks, std::ostream& out);

}  // namespace acc
