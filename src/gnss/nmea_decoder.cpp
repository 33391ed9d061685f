#include "acc_identification/gnss/nmea_decoder.h"

#include <utility>

namespace acc
{
NmeaDecoder::NmeaDecoder(LineHandler on_line, FixHandler on_fix)
  : on_line_(std::move(on_line)), on_fix_(std::move(on_fix))
{
}

void NmeaDecoder::feed(const char* data, std::size_t size, double receive_time_s)
{
  lines_.feed(data, size, [&](std::string_view line) { handleLine(line, receive_time_s); });
}

void NmeaDecoder::handleLine(std::string_view line, double receive_time_s)
{
  NmeaSentence sentence;
  const NmeaParseOutcome outcome = parseNmeaSentence(line, sentence);
  counts_.count(outcome);
  if (outcome == NmeaParseOutcome::kMalformed && lacksChecksumField(line))
    ++counts_.without_checksum;
  if (on_line_)
    on_line_(line, outcome);
  if (outcome == NmeaParseOutcome::kOk)
    emit(epochs_.add(sentence, receive_time_s));
}

void NmeaDecoder::emit(const std::vector<GnssFix>& fixes)
{
  for (const GnssFix& fix : fixes)
  {
    ++counts_.fixes;
    if (on_fix_)
      on_fix_(fix);
  }
}

void NmeaDecoder::flushIfIdle(double now_s, double idle_s)
{
  if (epochs_.hasPending() && now_s - epochs_.lastReceiveTime() >= idle_s)
    emit(epochs_.flushIdle(now_s));
}

void NmeaDecoder::flushEpoch(double now_s) { emit(epochs_.flushIdle(now_s)); }

void NmeaDecoder::flushAll() { emit(epochs_.flush()); }

void NmeaDecoder::finish(double receive_time_s)
{
  lines_.finish([&](std::string_view line) { handleLine(line, receive_time_s); });
  emit(epochs_.flush());
}

NmeaStatistics NmeaDecoder::statistics() const
{
  NmeaStatistics statistics = counts_;
  statistics.stray_bytes = lines_.strayBytes();
  statistics.stray_lines = lines_.strayLines();
  statistics.cut_lines = lines_.cutLines();
  statistics.overlong_lines = lines_.overlongLines();
  statistics.epochs_without_time = epochs_.epochsWithoutTime();
  statistics.date_lag_corrections = epochs_.dateLagCorrections();
  statistics.late_sentences_merged = epochs_.lateSentencesMerged();
  statistics.late_sentences_after_fix = epochs_.lateSentencesAfterFix();
  statistics.repeated_sentences = epochs_.repeatedSentences();
  return statistics;
}

}  // namespace acc
