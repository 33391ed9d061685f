#pragma once

#include <string_view>

#include "acc_identification/gnss/nmea_sentence.h"

namespace acc
{
/// Why a line did or did not become a sentence. Every rejected line has exactly one reason.
enum class NmeaParseOutcome
{
  kOk,
  kBadChecksum,  ///< the checksum does not match the body
  kMalformed,    ///< no '$', no checksum, too few fields, a field of the wrong form
  kUnsupported,  ///< valid NMEA of a type the driver does not use (GSV, GSA, TXT, ...)
};

const char* toString(NmeaParseOutcome outcome);

/// Parses one line ('$' ... '*hh', line terminator optional). Any talker is accepted (GP, GN,
/// GL, GA, GB, BD, GQ, ...); types: GGA, RMC, VTG, GST, ZDA and u-blox PUBX,00. Never throws,
/// never allocates. On kOk, sentence is filled; otherwise its content is unspecified.
NmeaParseOutcome parseNmeaSentence(std::string_view line, NmeaSentence& sentence);

/// The UTC time of day a line carries, if it is one of the timed types and its time field is
/// readable (no checksum check): used to pace the replay of logs.
bool nmeaLineTimeOfDay(std::string_view line, double& time_of_day_s);

}  // namespace acc
