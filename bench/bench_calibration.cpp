// Benchmarks of the calibration (Google Benchmark), on one core through `make bench`:
//  - Batch: one following setting at the paper's scale (nine runs, about 4,300 s of 10 Hz data
//    together), 100 starts, as the calibrate tool solves it. Target: under 0.5 s.
//  - Live: one recalibration of a 120 s window, warm-started from the previous window's fit, as
//    the identifier node does every second. Target: under 5 ms.
//  - One objective pass with gradient over the batch data, the unit everything else is made of.
//  - The refitting bootstrap calibrate makes on short data (199 replicates, one thread) of a 60 s,
//    a 120 s and a 300 s drive.
#include <benchmark/benchmark.h>

#include "batch_calibration_benchmark.h"

#include <vector>

#include "acc_identification/calibration/identification.h"
#include "acc_identification/calibration/refit_bootstrap.h"
#include "acc_identification/synthesis/synthetic_runs.h"
#include "acc_identification/model/paper_settings.h"

namespace
{
BENCHMARK(BM_BatchCalibration100Starts)->Unit(benchmark::kMillisecond);

void BM_LiveWindowRecalibration(benchmark::State& state)
{
  // The node's configuration: a 120 s window, warm start from the previous fit, a few fresh starts.
  const auto run = acc::synthesizeRun(acc::paperMinimumSetting(), 120.0, 0.1, 25.0, 42);
  acc::IdentificationOptions options;
  options.multistart.starts = static_cast<std::size_t>(state.range(0));
  const std::vector<acc::AccParameters> warm{acc::AccParameters{0.075, 0.45, 0.5, 8.0}};
  acc::Identification result;
  for (auto _ : state)
  {
    result = acc::identifyAcc({run}, options, warm);
    benchmark::DoNotOptimize(result);
  }
  state.counters["evaluations"] = static_cast<double>(result.calibration.evaluations);
  state.counters["identifiable"] = result.identifiable ? 1.0 : 0.0;
}
// Arg: fresh starts besides the warm start (the node default is 8).
BENCHMARK(BM_LiveWindowRecalibration)->Arg(0)->Arg(8)->Arg(32)->Unit(benchmark::kMillisecond);

void BM_ObjectivePassWithGradient(benchmark::State& state)
{
  const acc::CalibrationObjective objective(acc::paperScaleRuns(acc::paperMinimumSetting()));
  for (auto _ : state)
  {
    benchmark::DoNotOptimize(objective.evaluate(0.08, 0.44, 0.52, state.range(0) != 0));
  }
  state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * objective.sampleCount()));
}
BENCHMARK(BM_ObjectivePassWithGradient)->Arg(0)->Arg(1)->Unit(benchmark::kMicrosecond);
}  // namespace

void BM_RefitBootstrap(benchmark::State& state)
{
  const auto run = acc::synthesizeRun(acc::paperMinimumSetting(), static_cast<double>(state.range(0)), 0.1, 20.0, 1);
  const acc::AccParameters fit = acc::identifyAcc({run}, {}).calibration.parameters;
  acc::RefitBootstrapOptions options;
  options.threads = 1;
  acc::RefitBootstrap result;
  for (auto _ : state)
  {
    result = acc::bootstrapRefits(fit, {run}, options);
    benchmark::DoNotOptimize(result);
  }
  state.counters["refitted"] = static_cast<double>(result.refitted);
}
// Arg: the drive's length [s].
BENCHMARK(BM_RefitBootstrap)->Arg(60)->Arg(120)->Arg(300)->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
