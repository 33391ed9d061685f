// Benchmark of the string-stability test (Google Benchmark), on one core through `make bench`:
//  - Batch calibration: the paper's scale (nine runs of 480 s, 4,320 s of 10 Hz data), 100
//    starts, as the calibrate tool solves it (the same case as bench_calibration).
//  - Stability test: the same data with default options (first halves train, second halves held
//    out; unconstrained fit with 100 starts, the other side's constrained fit, the margin profile
//    over 26 margins, 999 bootstrap replicates; the identifiability of the quantities included).
//    Target (issue "The verdict on real drives"): at most twice the batch calibration.
//  - The same for a string-stable truth (Fig. 2, tau_e = 3.2 s), whose fits sit elsewhere.
//  - Sequential verdict (sequential_verdict.h), as calibrate --verdict-every 10: each of the nine
//    runs replayed as a drive, a look every 10 s (target: at most twice the batch calibration).
//  - One look of the sequential verdict at the end of a long drive (what the node's stability
//    thread does each stability_period_s): the look at 3 h, after looks up to 3 h - 10 s, on the
//    hour the node keeps (36,000 samples) and on all three hours (108,000).
#include <benchmark/benchmark.h>

#include "batch_calibration_benchmark.h"

#include <vector>

#include "acc_identification/calibration/multistart_calibrator.h"
#include "acc_identification/calibration/sequential_verdict.h"
#include "acc_identification/calibration/string_stability_verdict.h"
#include "acc_identification/synthesis/synthetic_runs.h"
#include "acc_identification/model/paper_settings.h"

namespace
{
BENCHMARK(BM_BatchCalibration100Starts)->Unit(benchmark::kMillisecond);

void stabilityTest(benchmark::State& state, const acc::AccParameters& truth)
{
  const auto runs = acc::paperScaleRuns(truth);
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
void BM_SequentialReplayEvery10s(benchmark::State& state)
{
  const auto runs = acc::paperScaleRuns(acc::paperMinimumSetting());
  acc::SequentialVerdictOptions options;
  options.look_period_s = 10.0;
  std::size_t looks = 0, decided = 0;
  for (auto _ : state)
  {
    looks = decided = 0;
    for (const acc::CarFollowingRun& run : runs)
    {
      const auto sequence = acc::replaySequentialVerdict({run}, options);
      looks += sequence.size();
      decided += !sequence.empty() && sequence.back().verdict == acc::StabilityVerdict::Unstable;
    }
    benchmark::DoNotOptimize(looks);
  }
  state.counters["looks"] = static_cast<double>(looks);
  state.counters["drives_decided_unstable"] = static_cast<double>(decided);
}
BENCHMARK(BM_SequentialReplayEvery10s)->Unit(benchmark::kMillisecond);

/// The look at the end of a drive of `seconds` (the last `kept_s` of it, as the node's bound
/// keeps), after every look up to 10 s before: the cost of one stability period late in a drive.
void sequentialLastLook(benchmark::State& state, double seconds, double kept_s)
{
  acc::CarFollowingRun drive = acc::synthesizeRun(acc::paperMinimumSetting(), seconds, 0.1, 20.0, 3);
  const std::size_t first = drive.size() - static_cast<std::size_t>(kept_s / 0.1);
  for (auto* column : {&drive.time_s, &drive.space_gap_m, &drive.follower_speed_mps, &drive.leader_speed_mps})
  {
    column->erase(column->begin(), column->begin() + static_cast<std::ptrdiff_t>(first));
  }
  acc::SequentialVerdictOptions options;
  options.look_period_s = 10.0;
  const double end_s = drive.time_s.back();
  // Looks up to the one before the last, on the data then (every 600 s, to keep the setup short:
  // the look measured refits from the previous look's fits either way).
  acc::SequentialVerdict before(options);
  for (double t = drive.time_s.front() + 600.0; t < end_s - 10.0; t += 600.0)
  {
    before.look({drive}, t);
  }
  before.look({drive}, end_s - 10.0);
  acc::SequentialLook look;
  for (auto _ : state)
  {
    state.PauseTiming();
    acc::SequentialVerdict verdict = before;
    state.ResumeTiming();
    look = verdict.look({drive}, end_s);
    benchmark::DoNotOptimize(look);
  }
  state.counters["samples"] = static_cast<double>(look.samples);
  state.counters["blocks_scored"] = static_cast<double>(look.blocks_scored);
}

void BM_SequentialLookKeptHourOf3h(benchmark::State& state)
{
  sequentialLastLook(state, 10800.0, 3600.0);
}
BENCHMARK(BM_SequentialLookKeptHourOf3h)->Unit(benchmark::kMillisecond);

void BM_SequentialLookAll3h(benchmark::State& state)
{
  sequentialLastLook(state, 10800.0, 10800.0 - 1.0);
}
BENCHMARK(BM_SequentialLookAll3h)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
