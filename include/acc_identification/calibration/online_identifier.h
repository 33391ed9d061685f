#pragma once

#include <cstddef>
#include <optional>
#include <vector>

#include "acc_identification/calibration/euler_step_bias.h"
#include "acc_identification/calibration/identification.h"
#include "acc_identification/calibration/quantity_identifiability.h"
#include "acc_identification/calibration/sequential_verdict.h"
#include "acc_identification/calibration/string_stability_verdict.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// How the identifier works live, period after period.
struct OnlineIdentifierOptions
{
  /// The sliding window's solve: multistart from fresh Halton points plus the previous fit.
  IdentificationOptions window;
  /// The drive so far is refitted every period from the previous drive fit and the window's fit
  /// (warm starts only), with at most this many objective evaluations per warm start: the cost of
  /// a period then grows only with the pass over the data (about 1 microsecond a sample), never
  /// with fresh multistarts. The very first drive solve is the window's.
  int drive_max_evaluations_per_start = 40;
  /// update() runs the string-stability test of the drive so far on every this-many-th update
  /// (0: never; the node runs testDrive() on a thread of its own instead, because on a 3-hour
  /// drive the test takes about 1.5 s while a period takes about 10 ms). Between runs the last
  /// result is carried over (and said to be so).
  std::size_t stability_every_updates = 10;
  /// The test's options. Its unconstrained fit starts from the drive fit and these fresh starts.
  StabilityTestOptions stability = defaultStabilityOptions();
  /// The drive fit's Euler step check (calibration/euler_step_bias.h) runs with each test of the
  /// drive when the data's median step is at least this [s]; infinity: never. At 10 Hz the step
  /// moves k1 by 3 % and the margin by 0.014, under what real drives pin, and the check (one more
  /// calibration) is skipped; at 1 Hz it moves them by a quarter and 0.13, towards "stable".
  double euler_check_min_step_s = 0.15;

  /// StabilityTestOptions with 8 fresh starts for the unconstrained fit and 8 Halton starts with
  /// at most 2 local solves for the other side: enough on a warm-started drive, a third of the
  /// batch cost.
  static StabilityTestOptions defaultStabilityOptions();
};

/// What one update gives: the window's identification, the drive's, and the verdict.
struct OnlineUpdate
{
  Identification window;
  std::optional<IdentifiableQuantities> window_quantities;  ///< when the window was solved
  Identification drive;
  std::optional<IdentifiableQuantities> drive_quantities;   ///< when the drive was solved
  std::size_t drive_samples = 0;
  /// The latest string-stability test of the drive so far (none before the first one ran).
  std::optional<StabilityTestResult> stability;
  bool stability_ran_now = false;  ///< false: carried over from an earlier update
  std::size_t stability_drive_samples = 0;  ///< samples of the drive when that test ran
  /// The latest look of the sequential verdict (the identifier node's, which runs it on its own
  /// thread; when set, it is the published verdict instead of `stability`).
  std::optional<SequentialLook> sequential;
  /// The latest Euler step check of the drive fit (checkEulerStep; the node runs it on its
  /// stability thread): none before one ran, or when the data's step is fine enough to skip it.
  std::optional<EulerStepBias> euler_step;
  double window_cpu_s = 0.0;     ///< wall time of each stage of this update
  double drive_cpu_s = 0.0;
  double stability_cpu_s = 0.0;
};

/// The live identifier's computation, ROS-free: the sliding window (what the ACC does lately) and
/// the drive so far (evidence accumulated as the drive covers more speeds and manoeuvres). The
/// drive's estimate converges to a batch calibration of the whole drive because it IS that
/// calibration, warm-started and continued period after period; the verdict is the batch
/// calibrate tool's string-stability test on the same samples.
class OnlineIdentifier
{
public:
  explicit OnlineIdentifier(OnlineIdentifierOptions options = {});

  /// One period: window_segments and drive_segments as the two windows give them (each simulated
  /// from its own measured start). Never throws on data problems (see Identification::note).
  OnlineUpdate update(const std::vector<CarFollowingRun>& window_segments,
                      const std::vector<CarFollowingRun>& drive_segments);

  /// Forget the drive (a time reset or a new drive).
  void resetDrive();

  /// The string-stability test of drive segments, warm-started from the drive's fit: the batch
  /// calibrate tool's test with options().stability. Uses no state of the identifier: safe to run
  /// on another thread while update() runs.
  StabilityTestResult testDrive(const std::vector<CarFollowingRun>& drive_segments, const AccParameters& drive_fit) const;

  /// The Euler step check of the drive fit on its segments, with the window's identification
  /// options; none when the data's median step is below options().euler_check_min_step_s (or the
  /// drive is not solved). Uses no state of the identifier: safe on another thread, as testDrive.
  std::optional<EulerStepBias> checkEulerStep(const std::vector<CarFollowingRun>& drive_segments,
                                              const Identification& drive) const;

  const OnlineIdentifierOptions& options() const { return options_; }

private:
  Identification solveDrive(const std::vector<CarFollowingRun>& drive_segments, const Identification& window);

  OnlineIdentifierOptions options_;
  std::optional<AccParameters> window_warm_start_;
  std::optional<AccParameters> drive_warm_start_;
  std::optional<StabilityTestResult> last_stability_;
  std::size_t last_stability_samples_ = 0;
  std::optional<EulerStepBias> last_euler_step_;
  std::size_t updates_ = 0;
};

}  // namespace acc
