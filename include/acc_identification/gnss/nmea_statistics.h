#pragma once

#include <cstdint>
#include <string>

#include "acc_identification/gnss/nmea_parser.h"

namespace acc
{
/// Counts of everything the decoder saw, so that no input is dropped without a trace.
struct NmeaStatistics
{
  std::uint64_t lines = 0;          ///< complete lines handed to the parser
  std::uint64_t sentences_ok = 0;
  std::uint64_t bad_checksum = 0;
  std::uint64_t malformed = 0;
  std::uint64_t without_checksum = 0;  ///< of the malformed: sentences with no "*hh" at all
  std::uint64_t unsupported = 0;
  std::uint64_t stray_bytes = 0;    ///< bytes outside any '$' line (noise, binary UBX, ...)
  std::uint64_t stray_lines = 0;    ///< input lines of stray bytes only, dropped
  std::uint64_t cut_lines = 0;      ///< lines begun by a '$' inside another line (see NmeaLineAssembler)
  std::uint64_t overlong_lines = 0; ///< lines longer than the assembler's limit, discarded
  std::uint64_t fixes = 0;          ///< epochs completed
  std::uint64_t epochs_without_time = 0;  ///< epochs of untimed sentences only, discarded
  std::uint64_t date_lag_corrections = 0; ///< see UtcDateTracker
  std::uint64_t late_sentences_merged = 0;     ///< reached their epoch while it waited (reorder wait)
  std::uint64_t late_sentences_after_fix = 0;  ///< came after their epoch's fix: in no fix (raw line kept)
  std::uint64_t repeated_sentences = 0;  ///< a second of one type and talker in an epoch: the first kept

  void count(NmeaParseOutcome outcome);
  std::uint64_t rejected() const { return bad_checksum + malformed + unsupported; }
  /// Non-empty input lines these counts account for: every line handed to the parser, less the
  /// extra pieces of cut lines, plus the input lines dropped before the parser.
  std::uint64_t inputLines() const { return lines - cut_lines + stray_lines + overlong_lines; }
  /// One line, e.g. for a log at the end of a replay.
  std::string summary() const;
};

}  // namespace acc
