#include "acc_identification/gnss/nmea_statistics.h"

#include <sstream>

namespace acc
{
void NmeaStatistics::count(NmeaParseOutcome outcome)
{
  ++lines;
  switch (outcome)
  {
    case NmeaParseOutcome::kOk: ++sentences_ok; break;
    case NmeaParseOutcome::kBadChecksum: ++bad_checksum; break;
    case NmeaParseOutcome::kMalformed: ++malformed; break;
    case NmeaParseOutcome::kUnsupported: ++unsupported; break;
  }
}

std::string NmeaStatistics::summary() const
{
  std::ostringstream out;
  out << lines << " lines: " << sentences_ok << " ok, " << bad_checksum << " bad checksum, " << malformed
      << " malformed";
  if (without_checksum > 0)
    out << " (" << without_checksum << " without a checksum *hh, which every sentence needs here)";
  out << ", " << unsupported << " unsupported; " << stray_bytes << " stray bytes, " << stray_lines
      << " stray lines, " << cut_lines << " cut lines, " << overlong_lines << " overlong lines; " << fixes
      << " fixes, " << epochs_without_time << " epochs without time, " << date_lag_corrections
      << " date lag corrections";
  if (late_sentences_merged > 0 || late_sentences_after_fix > 0)
  {
    out << "; " << late_sentences_merged << " late sentences merged, " << late_sentences_after_fix
        << " after their epoch's fix";
  }
  if (repeated_sentences > 0)
    out << "; " << repeated_sentences << " repeated sentences (a second of one type and talker in an epoch: the first "
                                         "kept)";
  return out.str();
}

}  // namespace acc
