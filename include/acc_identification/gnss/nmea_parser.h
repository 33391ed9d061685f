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

/// Parses one line ('$' ... '*hh', or '!' ... '*hh' for encapsulation sentences such as AIS,
/// which are valid but unsupported; line terminator optional; a line without checksum is
/// malformed). Any talker is accepted (GP, GN, GL, GA, GB, BD, GQ, ...); types: GGA, GNS, RMC,
/// GLL, VTG, GST, ZDA and u-blox PUBX,00. GGA, GNS and GLL may leave out the trailing fields
/// after the last one the driver reads (Saab R4 ends GGA after the fix quality). A sentence
/// that says it has no fix (GGA quality 0, RMC/GLL status V, GNS modes all N) keeps its time and
/// date even when its position fields hold a placeholder out of range (MediaTek at cold start:
/// 8960.000000,N); a position is never reported for it, nor for GGA quality 7 (manual input) or
/// 8 (simulator). Never throws, never allocates. On kOk, sentence is filled; otherwise its
/// content is unspecified.
NmeaParseOutcome parseNmeaSentence(std::string_view line, NmeaSentence& sentence);

/// Whether a line that starts as a sentence ('$' or '!') has no checksum field at all ("*hh"):
/// what a malformed line most often lacks in logs written by hand or by tools that drop it, said
/// apart so that a whole log of them is explained.
bool lacksChecksumField(std::string_view line);

/// The UTC time of day a line carries, if it is one of the timed types and its time field is
/// readable (no checksum check): used to pace the replay of logs.
bool nmeaLineTimeOfDay(std::string_view line, double& time_of_day_s);

}  // namespace acc
