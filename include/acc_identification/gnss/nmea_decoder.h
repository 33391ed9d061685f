#pragma once

#include <cstddef>
#include <functional>
#include <optional>
#include <vector>
#include <string_view>

#include "acc_identification/gnss/gnss_epoch_assembler.h"
#include "acc_identification/gnss/gnss_fix.h"
#include "acc_identification/gnss/nmea_line_assembler.h"
#include "acc_identification/gnss/nmea_parser.h"
#include "acc_identification/gnss/nmea_statistics.h"

namespace acc
{
/// The whole receive path of one receiver: bytes -> lines -> sentences -> one fix per epoch,
/// with statistics. Used by the driver node and by readNmeaLog, so a log and a live receiver
/// go through exactly the same code.
class NmeaDecoder
{
public:
  using LineHandler = std::function<void(std::string_view line, NmeaParseOutcome outcome)>;
  using FixHandler = std::function<void(const GnssFix& fix)>;

  NmeaDecoder(LineHandler on_line, FixHandler on_fix);

  /// Feeds received bytes; handlers are called for every completed line and epoch.
  void feed(const char* data, std::size_t size, double receive_time_s);
  /// Completes the pending epoch when no sentence arrived for idle_s (live sources), unless it
  /// waits for late sentences (setReorderWait).
  void flushIfIdle(double now_s, double idle_s);
  /// The caller saw a pause in the byte stream at now_s: completes the pending epoch, unless it
  /// waits for late sentences.
  void flushEpoch(double now_s);
  /// Completes every pending epoch, waiting or not (a long silence).
  void flushAll();
  /// See GnssEpochAssembler::setReorderWait (0: an epoch never waits for late sentences).
  void setReorderWait(double wait_s) { epochs_.setReorderWait(wait_s); }
  /// End of stream: hands out a last unterminated line and the pending epoch.
  void finish(double receive_time_s);

  NmeaStatistics statistics() const;

private:
  void handleLine(std::string_view line, double receive_time_s);
  void emit(const std::vector<GnssFix>& fixes);

  LineHandler on_line_;
  FixHandler on_fix_;
  NmeaLineAssembler lines_;
  GnssEpochAssembler epochs_;
  NmeaStatistics counts_;
};

}  // namespace acc
