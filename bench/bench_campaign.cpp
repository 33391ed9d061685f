// The whole shipped ZalaZone dynamic-platform set (9 runs; JRC OpenACC, CC BY 4.0, see
// data/openacc/README.md) through the campaign: every (vehicle, setting) group identified with
// 100 starts and the string-stability test, and every platoon predicted with leave-one-run-out
// models, on 2 threads: the base models only (target: under 20 s of wall time on a 2-core
// machine), and with the platoon diagnosis (every candidate model of every car, the platoons
// predicted with each, the rule, the link evidence; target: under 60 s).
#include <benchmark/benchmark.h>

#include "acc_identification/campaign/campaign.h"

namespace
{
void BM_CampaignZalaZone(benchmark::State& state)
{
  const acc::CampaignInputs inputs = acc::loadCampaign({ACC_ZALAZONE_DYNAMIC_DIR});
  acc::CampaignOptions options;
  options.group.starts = 100;
  options.threads = static_cast<std::size_t>(state.range(0));
  options.platoon_diagnosis = state.range(1) != 0;
  std::size_t fits = 0;
  for (auto _ : state)
  {
    const acc::CampaignResult result = acc::runCampaign(inputs, options);
    benchmark::DoNotOptimize(result.groups.data());
    fits = result.groups.size();
  }
  state.counters["groups"] = static_cast<double>(fits);
  state.counters["files"] = static_cast<double>(inputs.files.size());
}
BENCHMARK(BM_CampaignZalaZone)
    ->ArgNames({"threads", "diagnosis"})
    ->Args({2, 0})
    ->Args({2, 1})
    ->Unit(benchmark::kSecond)
    ->UseRealTime()
    ->Iterations(1);
}  // namespace

BENCHMARK_MAIN();
