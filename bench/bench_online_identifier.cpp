// One live period of the identifier on a 3-hour drive (the target: under 50 ms), and the
// string-stability test of that drive, which runs on every tenth period by default.
#include <benchmark/benchmark.h>

#include "acc_identification/calibration/drive_record.h"
#include "acc_identification/calibration/online_identifier.h"
#include "acc_identification/calibration/sliding_window.h"
#include "acc_identification/synthesis/synthetic_runs.h"
#include "acc_identification/model/paper_settings.h"

namespace
{
constexpr double kDriveS = 3.0 * 3600.0;

struct Drive
{
  std::vector<acc::CarFollowingRun> window;
  std::vector<acc::CarFollowingRun> whole;
};

/// Three hours of 10 Hz, kept as the node keeps the drive so far with ~drive_max_samples
/// max_samples (0: every sample).
Drive threeHourDrive(std::size_t max_samples)
{
  static const acc::CarFollowingRun run = acc::synthesizeRun(acc::paperMinimumSetting(), kDriveS, 0.1, 25.0, 3);
  acc::DriveBound bound;
  bound.max_samples = max_samples;
  acc::SlidingWindow window(120.0, 0.5, 20);
  acc::DriveRecord whole(0.5, 20, 30.0, 5, bound);
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    const acc::WindowSample sample{run.time_s[k], run.space_gap_m[k], run.follower_speed_mps[k],
                                   run.leader_speed_mps[k], true};
    window.add(sample);
    whole.add(sample);
  }
  return Drive{window.segments(), whole.segments()};
}

std::size_t samplesIn(const std::vector<acc::CarFollowingRun>& segments)
{
  std::size_t n = 0;
  for (const auto& segment : segments) n += segment.size();
  return n;
}

/// A period at the end of a 3-hour drive: the window's solve and the drive's continued solve
/// (warm: the identifier has run before), without the stability test. Argument: the drive's
/// bound (36,000: the node's default; 0: every sample kept).
void BM_PeriodOnThreeHourDrive(benchmark::State& state)
{
  const Drive drive = threeHourDrive(static_cast<std::size_t>(state.range(0)));
  acc::OnlineIdentifierOptions options;
  options.window.multistart.starts = 8;  // config/identifier.yaml
  options.stability_every_updates = 0;
  acc::OnlineIdentifier identifier(options);
  identifier.update(drive.window, drive.whole);  // warm up: the first drive solve is a cold one
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(identifier.update(drive.window, drive.whole));
  }
  state.counters["drive_samples"] = static_cast<double>(samplesIn(drive.whole));
}
BENCHMARK(BM_PeriodOnThreeHourDrive)->Arg(36000)->Arg(0)->Unit(benchmark::kMillisecond);

/// The string-stability test of the 3-hour drive as kept, with the online options.
void BM_StabilityTestOnThreeHourDrive(benchmark::State& state)
{
  const Drive drive = threeHourDrive(static_cast<std::size_t>(state.range(0)));
  acc::StabilityTestOptions options = acc::OnlineIdentifierOptions::defaultStabilityOptions();
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(acc::testStringStability(drive.whole, options));
  }
}
BENCHMARK(BM_StabilityTestOnThreeHourDrive)->Arg(36000)->Arg(0)->Unit(benchmark::kMillisecond)->Iterations(3);
}  // namespace

BENCHMARK_MAIN();
