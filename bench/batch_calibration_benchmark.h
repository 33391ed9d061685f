#pragma once
// The reference every cost in docs/PERFORMANCE.md is a ratio of: the batch calibration of the
// benchmarks' reference data (paperScaleRuns, nine runs of 480 s from Table II's minimum setting)
// with 100 starts. bench_calibration and bench_string_stability_verdict both register it, so that
// each measures its ratios against it in the same run, on the same machine state.
#include <benchmark/benchmark.h>

#include "acc_identification/calibration/multistart_calibrator.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/synthesis/synthetic_runs.h"

inline void BM_BatchCalibration100Starts(benchmark::State& state)
{
  const auto runs = acc::paperScaleRuns(acc::paperMinimumSetting());
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
  state.counters["rmse_mps"] = result.rmse_speed_mps;
  state.counters["k1"] = result.parameters.k1_per_s2;
}
