// NMEA parser throughput (issue 3 target: >= 2 million GGA + RMC sentences per second, one core).
// Run: make bench (pinned to core 0), or devel/lib/acc_identification/bench_nmea.
#include <benchmark/benchmark.h>

#include <string>

#include "acc_identification/gnss/nmea_decoder.h"
#include "acc_identification/gnss/nmea_parser.h"
#include "acc_identification/gnss/nmea_writer.h"


namespace
{
// As a u-blox F9 sends them at 10 Hz (talker GN, NMEA 4.11).
const std::string kGga = "$GNGGA,101530.00,4507.80000,N,00827.00000,E,1,12,0.80,150.0,M,47.3,M,,*48";
const std::string kRmc = "$GNRMC,101530.30,A,4507.80115,N,00827.00163,E,19.732,45.00,271020,,,A,V*04";

/// parseNmeaSentence alone on alternating GGA and RMC lines (checksum, split, fields).
void BM_ParseGgaRmc(benchmark::State& state)
{
  acc::NmeaSentence sentence;
  std::size_t ok = 0;
  for (auto _ : state)
  {
    ok += acc::parseNmeaSentence(kGga, sentence) == acc::NmeaParseOutcome::kOk;
    benchmark::DoNotOptimize(sentence);
    ok += acc::parseNmeaSentence(kRmc, sentence) == acc::NmeaParseOutcome::kOk;
    benchmark::DoNotOptimize(sentence);
  }
  if (ok != 2 * static_cast<std::size_t>(state.iterations()))
    state.SkipWithError("a benchmark sentence did not parse");
  state.SetItemsProcessed(2 * state.iterations());
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(kGga.size() + kRmc.size() + 4));
}
BENCHMARK(BM_ParseGgaRmc);

/// The whole receive path: a byte stream of GGA + RMC epochs through line assembly, parsing and
/// epoch assembly into fixes (what the node does per read).
void BM_DecodeGgaRmcStream(benchmark::State& state)
{
  // 1000 epochs 0.1 s apart, written by the NMEA writer (u-blox precision and field layout).
  std::string stream;
  constexpr int kEpochs = 1000;
  acc::GnssFix fix;
  fix.has_date = true;
  fix.fix_quality = 1;
  fix.satellites_used = 12;
  fix.hdop = 0.8;
  fix.altitude_m = 150.0;
  fix.geoid_separation_m = 47.3;
  fix.course_rad = 0.785;
  fix.valid_fields = 255;
  for (int i = 0; i < kEpochs; ++i)
  {
    fix.gnss_time_s = 1603793730.0 + 0.1 * i;
    fix.latitude_deg = 45.13 + 1e-6 * i;
    fix.longitude_deg = 8.45 + 1e-6 * i;
    fix.speed_over_ground_mps = 10.0 + 0.01 * i;
    stream += acc::formatGga(fix) + "\r\n" + acc::formatRmc(fix) + "\r\n";
  }
  std::size_t fixes = 0;
  acc::NmeaDecoder decoder(nullptr, [&](const acc::GnssFix&) { ++fixes; });
  for (auto _ : state)
    decoder.feed(stream.data(), stream.size(), 0.0);
  benchmark::DoNotOptimize(fixes);
  if (decoder.statistics().sentences_ok != static_cast<std::uint64_t>(2 * kEpochs * state.iterations()))
    state.SkipWithError("a benchmark sentence did not parse");
  state.SetItemsProcessed(2 * kEpochs * state.iterations());
  state.SetBytesProcessed(state.iterations() * static_cast<std::int64_t>(stream.size()));
}
BENCHMARK(BM_DecodeGgaRmcStream);
}  // namespace

BENCHMARK_MAIN();
