// Benchmark of the sim-to-real gap diagnosis (Google Benchmark), through `make bench`: one whole
// diagnose of one 25-minute real run, the bundled OpenACC Casale part6 (Hyundai Nexo on ACC behind
// a SsangYong Rexton, 15,061 samples at 10 Hz, 1,506 s; data/openacc/casale.tar.xz, unpacked by
// the build): split in halves, the base fit and the six effect fits with their standard errors,
// the selection bootstrap (2,000 resamples of 10 s blocks), the residual breakdown, the
// string-stability test of the chosen model (side fit, 999 bootstrap replicates) and the forward
// selection, with the diagnose tool's defaults. Target (issue 15): at least 5x faster than the
// derivative-free fits before it (5.8 s wall on this machine). Threads: Arg(1) is one core, Arg(0)
// every core; the result is the same. And the final model's refitting bootstrap on short data.
#include <benchmark/benchmark.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "acc_identification/diagnosis/diagnosis.h"
#include "acc_identification/diagnosis/final_model_bootstrap.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/validation/withheld_effect_suite.h"

namespace
{
std::vector<acc::CarFollowingRun> casalePart6()
{
  std::vector<acc::CarFollowingRun> runs = acc::readRuns(std::string(ACC_CASALE_DIR) + "/part6.csv",
                                                         acc::RunPlausibilityBounds{}, acc::OpenAccPairSelector::first());
  if (runs.size() != 1 || runs.front().durationS() < 1500.0)
  {
    throw std::runtime_error("bench_diagnosis: Casale part6 should be one run of about 25 minutes");
  }
  return runs;
}

void BM_DiagnoseOneTwentyFiveMinuteRun(benchmark::State& state)
{
  const std::vector<acc::CarFollowingRun> runs = casalePart6();
  acc::DiagnosisOptions options;
  options.threads = static_cast<std::size_t>(state.range(0));
  acc::DiagnosisResult result;
  for (auto _ : state)
  {
    result = acc::diagnoseRuns(runs, options);
    benchmark::DoNotOptimize(result);
  }
  state.counters["samples"] = static_cast<double>(runs.front().size());
  state.counters["chain_length"] = static_cast<double>(result.selected_effects.size());
  state.SetLabel("dominant " + acc::effectName(result.selection.dominant));
}
BENCHMARK(BM_DiagnoseOneTwentyFiveMinuteRun)->Arg(1)->Arg(0)->Unit(benchmark::kMillisecond)->UseRealTime();

/// The final model's refitting bootstrap on short training data (199 replicates, each refitted as
/// the diagnosis fits: base cold, the effect warm, and a start at the model), for a model with an
/// actuation lag on a synthetic drive with a 0.8 s lag hidden. Arg: the drive's length [s].
void BM_DiagnosedModelBootstrap(benchmark::State& state)
{
  acc::WithheldCase c;
  c.truth = acc::EffectKind::actuation_lag;
  c.truth_values = {0.8};
  c.duration_s = static_cast<double>(state.range(0));
  const acc::CarFollowingRun run = acc::synthesizeWithheldRun(c);
  const acc::AugmentedCalibrationOptions calibration;
  const acc::AugmentedFit fit = acc::calibrateAugmentedSet({acc::EffectKind::actuation_lag}, {run}, calibration);
  acc::RefitBootstrapOptions options;
  options.threads = 1;
  acc::RefitBootstrap result;
  for (auto _ : state)
  {
    result = acc::bootstrapDiagnosedModel(fit, {run}, calibration, options);
    benchmark::DoNotOptimize(result);
  }
  state.counters["refitted"] = static_cast<double>(result.refitted);
}
BENCHMARK(BM_DiagnosedModelBootstrap)->Arg(60)->Arg(120)->Arg(300)->Unit(benchmark::kMillisecond);
}  // namespace

BENCHMARK_MAIN();
