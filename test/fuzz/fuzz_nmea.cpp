// libFuzzer target for the NMEA receive path: the sentence parser on the raw input, and the
// whole decoder (line assembly, parsing, epoch assembly, dates) on the input cut into reads.
// Built and run by scripts/test_hooks/fuzz_nmea.sh with -fsanitize=fuzzer,address,undefined.
// Besides crashes it checks invariants: every line is counted under exactly one reason, and
// every fix the decoder emits can be written as GGA and RMC and parsed back.
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <string_view>

#include "acc_identification/gnss/gnss_velocity.h"
#include "acc_identification/gnss/nmea_decoder.h"
#include "acc_identification/gnss/nmea_parser.h"
#include "acc_identification/gnss/nmea_writer.h"

#include "fuzz_support.h"

namespace
{
using fuzz_support::check;

void checkFix(const acc::GnssFix& fix)
{
  acc::NmeaSentence back;
  check(acc::parseNmeaSentence(acc::formatGga(fix), back) == acc::NmeaParseOutcome::kOk, "written GGA parses");
  check(acc::parseNmeaSentence(acc::formatRmc(fix), back) == acc::NmeaParseOutcome::kOk, "written RMC parses");
  acc::EnuVelocity velocity;
  acc::enuVelocity(fix, velocity);
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  const std::string_view input(reinterpret_cast<const char*>(data), size);
  acc::NmeaSentence sentence;
  acc::parseNmeaSentence(input, sentence);
  double time_of_day_s = 0.0;
  acc::nmeaLineTimeOfDay(input, time_of_day_s);

  std::uint64_t lines = 0;
  acc::NmeaDecoder decoder([&](std::string_view, acc::NmeaParseOutcome) { ++lines; }, checkFix);
  // The first byte chooses the read size, so that lines are split across reads in every way.
  const std::size_t chunk = size > 0 ? 1 + data[0] % 64 : 1;
  // ...and whether epochs wait for late sentences (the reorder wait of a driver over a radio link).
  decoder.setReorderWait(size > 0 && (data[0] & 0x40) ? 0.3 : 0.0);
  double receive_time_s = 0.0;
  for (std::size_t at = 0; at < size; at += chunk, receive_time_s += 0.01)
  {
    decoder.feed(input.data() + at, std::min(chunk, size - at), receive_time_s);
    if (data[at] == 0x7f)
      decoder.flushEpoch(receive_time_s);
  }
  decoder.finish(receive_time_s);
  const acc::NmeaStatistics s = decoder.statistics();
  check(s.lines == lines, "every line reported");
  check(s.lines == s.sentences_ok + s.bad_checksum + s.malformed + s.unsupported, "one reason per line");
  return 0;
}
