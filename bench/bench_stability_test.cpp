// Benchmark of the string-stability test (Google Benchmark), on one core through `make bench`:
//  - Batch calibration: the paper's scale (nine runs of 480 s, 4,320 s of 10 Hz data), 100
//    starts, as the calibrate tool solves it (the same case as bench_calibration).
//  - Stability test: the same data with default options (first halves train, second halves held
//    out; unconstrained fit with 100 starts, the other side's constrained fit, the margin profile
//    over 26 margins, 999 bootstrap replicates; the identifiability of the quantities included).
//    Target (issue "The verdict on real drives"): at most twice the batch calibration.
//  - The same for a string-stable truth (Fig. 2, tau_e = 3.2 s), whose fits sit elsewhere.
#include <benchmark/benchmark.h>

#include <vector>

#include "acc_identification/calibration/multistart_calibrator.h"
#include "acc_identification/calibration/stability_test.h"
#include "acc_identification/calibration/synthetic_runs.h"
#include "acc_identification/model/paper_settings.h"

namespace
{
std::vector<acc::CarFollowingRun> paperScaleRuns(const acc::AccParameters& truth)
{
  std::vector<acc::CarFollowingRun> runs;
  for (std::uint32_t seed = 1; seed <= 9; ++seed)
  {
    runs.push_back(acc::synthesizeRun(truth, 480.0, 0.1, 12.0 + 2.0 * seed, seed));
  }
  return runs;
}

void BM_BatchCalibration100Starts(benchmark::State& state)
{
  const auto runs = paperScaleRuns(acc::paperMinimumSetting());
  const acc::CalibrationObjective objective(runs);
  acc::MultistartOptions options;
  options.starts = 100;
  acc::MultistartResult result;
  for (auto _ : state)
  {
    result = acc::calibrateMultistart(objective, options);
    benchmark::DoNotOptimize(result);
  }
  state.counters["samples"] = static_cast<double>(objective.sampleCount());
  state.counters["evaluations"] = static_cast<double>(result.evaluations);
}
BENCHMARK(BM_BatchCalibration100Starts)->Unit(benchmark::kMillisecond);

void stabilityTest(benchmark::State& state, const acc::AccParameters& truth)
{
  const auto runs = paperScaleRuns(truth);
  const acc::StabilityTestOptions options;
  acc::StabilityTestResult result;
  for (auto _ : state)
  {
    result = acc::testStringStability(runs, options);
    benchmark::DoNotOptimize(result);
  }
  state.counters["held_out_samples"] = static_cast<double>(result.held_out_samples);
  state.counters["verdict_unstable"] = result.verdict == acc::StabilityVerdict::Unstable ? 1.0 : 0.0;
  state.counters["verdict_stable"] = result.verdict == acc::StabilityVerdict::Stable ? 1.0 : 0.0;
  state.counters["profile_points"] = static_cast<double>(result.margin_profile.size());
  state.counters["evals_unconstrained"] = static_cast<double>(result.unconstrained_evaluations);
  state.counters["evals_constrained"] = static_cast<double>(result.constrained_evaluations);
  state.counters["evals_profile"] = static_cast<double>(result.profile_evaluations);
}

void BM_StabilityTestUnstableTruth(benchmark::State& state)
{
  stabilityTest(state, acc::paperMinimumSetting());
}
BENCHMARK(BM_StabilityTestUnstableTruth)->Unit(benchmark::kMillisecond);

void BM_StabilityTestStableTruth(benchmark::State& state)
{
  stabilityTest(state, acc::paperFigure2Setting(3.2));
}
BENCHMARK(BM_StabilityTestStableTruth)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
