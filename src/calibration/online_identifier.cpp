#include "acc_identification/calibration/online_identifier.h"

#include <chrono>

namespace acc
{
namespace
{
double secondsSince(std::chrono::steady_clock::time_point start)
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}
}  // namespace

StabilityTestOptions OnlineIdentifierOptions::defaultStabilityOptions()
{
  StabilityTestOptions options;
  options.multistart.starts = 8;
  options.constrained.starts = 8;
  options.constrained.max_local_solves = 2;
  return options;
}

OnlineIdentifier::OnlineIdentifier(OnlineIdentifierOptions options) : options_(std::move(options)) {}

void OnlineIdentifier::resetDrive()
{
  drive_warm_start_.reset();
  last_stability_.reset();
  last_stability_samples_ = 0;
  last_euler_step_.reset();
}

Identification OnlineIdentifier::solveDrive(const std::vector<CarFollowingRun>& drive_segments,
                                            const Identification& window)
{
  IdentificationOptions drive_options = options_.window;
  std::vector<AccParameters> warm;
  if (drive_warm_start_)
  {
    // Continue the drive's own solve: no fresh starts, a bounded number of evaluations.
    drive_options.multistart.starts = 0;
    drive_options.multistart.max_evaluations_per_start = options_.drive_max_evaluations_per_start;
    warm.push_back(*drive_warm_start_);
  }
  if (window.solved && !window.calibration.diverged)
  {
    warm.push_back(window.calibration.parameters);
  }
  drive_options.multistart.progress = nullptr;
  return identifyAcc(drive_segments, drive_options, warm);
}

StabilityTestResult OnlineIdentifier::testDrive(const std::vector<CarFollowingRun>& drive_segments,
                                                const AccParameters& drive_fit) const
{
  StabilityTestOptions test_options = options_.stability;
  test_options.warm_starts = {drive_fit};
  return testStringStability(drive_segments, test_options);
}

std::optional<EulerStepBias> OnlineIdentifier::checkEulerStep(const std::vector<CarFollowingRun>& drive_segments,
                                                             const Identification& drive) const
{
  if (!drive.solved || drive.calibration.diverged || !(medianStepS(drive_segments) >= options_.euler_check_min_step_s))
    return std::nullopt;
  IdentificationOptions options = options_.window;
  options.multistart.progress = nullptr;
  return estimateEulerStepBias(drive, drive_segments, options);
}

OnlineUpdate OnlineIdentifier::update(const std::vector<CarFollowingRun>& window_segments,
                                      const std::vector<CarFollowingRun>& drive_segments)
{
  OnlineUpdate result;
  ++updates_;

  auto start = std::chrono::steady_clock::now();
  std::vector<AccParameters> warm;
  if (window_warm_start_)
    warm.push_back(*window_warm_start_);
  result.window = identifyAcc(window_segments, options_.window, warm);
  if (result.window.solved && !result.window.calibration.diverged)
  {
    window_warm_start_ = result.window.calibration.parameters;
    result.window_quantities = result.window.quantities;
  }
  result.window_cpu_s = secondsSince(start);

  start = std::chrono::steady_clock::now();
  result.drive_samples = sampleCount(drive_segments);
  result.drive = solveDrive(drive_segments, result.window);
  if (result.drive.solved && !result.drive.calibration.diverged)
  {
    drive_warm_start_ = result.drive.calibration.parameters;
    result.drive_quantities = result.drive.quantities;
  }
  result.drive_cpu_s = secondsSince(start);

  const std::size_t every = options_.stability_every_updates;
  if (every > 0 && (updates_ - 1) % every == 0 && result.drive.solved && !result.drive.calibration.diverged)
  {
    start = std::chrono::steady_clock::now();
    last_stability_ = testDrive(drive_segments, result.drive.calibration.parameters);
    last_stability_samples_ = result.drive_samples;
    last_euler_step_ = checkEulerStep(drive_segments, result.drive);
    result.stability_ran_now = true;
    result.stability_cpu_s = secondsSince(start);
  }
  result.stability = last_stability_;
  result.stability_drive_samples = last_stability_samples_;
  result.euler_step = last_euler_step_;
  return result;
}

}  // namespace acc
