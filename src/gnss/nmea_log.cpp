#include "acc_identification/gnss/nmea_log.h"

#include <cmath>
#include <fstream>

#include "acc_identification/gnss/nmea_decoder.h"

namespace acc
{
NmeaLogResult readNmeaLog(const std::string& path)
{
  NmeaLogResult result;
  std::ifstream in(path, std::ios::binary);
  if (!in)
  {
    result.error = "cannot open NMEA log " + path;
    return result;
  }
  NmeaDecoder decoder(nullptr, [&](const GnssFix& fix) {
    result.fixes.push_back(fix);
    result.fixes.back().receive_time_s = fix.gnss_time_s;  // no host clock in a log
  });
  char chunk[65536];
  while (in)
  {
    in.read(chunk, sizeof chunk);
    decoder.feed(chunk, static_cast<std::size_t>(in.gcount()), std::nan(""));
  }
  if (in.bad())
    result.error = "read error in NMEA log " + path;
  decoder.finish(std::nan(""));
  result.statistics = decoder.statistics();
  return result;
}

}  // namespace acc
