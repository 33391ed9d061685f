#include "acc_identification/gnss/gnss_epoch_assembler.h"

#include <cmath>

namespace acc
{
namespace
{
/// Two times of day belong to the same epoch when they agree to a millisecond (NMEA sends
/// centiseconds or milliseconds; epochs are at least 10 ms apart).
bool sameTime(double a_s, double b_s) { return std::fabs(a_s - b_s) < 1e-3; }

/// Rank of a sentence type as the source of a field group; higher wins, 0 = does not carry it.
struct Ranks
{
  int position, altitude, velocity, sigma, quality;
};

Ranks ranksOf(NmeaSentenceType type)
{
  switch (type)
  {
    case NmeaSentenceType::kGga: return {3, 2, 0, 0, 3};
    case NmeaSentenceType::kGns: return {3, 2, 0, 0, 3};
    case NmeaSentenceType::kPubx00: return {2, 1, 1, 1, 2};
    case NmeaSentenceType::kRmc: return {1, 0, 2, 0, 1};
    case NmeaSentenceType::kGll: return {1, 0, 0, 0, 1};
    case NmeaSentenceType::kVtg: return {0, 0, 2, 0, 0};
    case NmeaSentenceType::kGst: return {0, 0, 0, 2, 0};
    case NmeaSentenceType::kZda: return {0, 0, 0, 0, 0};
  }
  return {0, 0, 0, 0, 0};
}

/// Between sentences of equal rank, the combined solution (talker GN) outranks a single
/// constellation's (GP, GL, GA, GB/BD, GQ, ...): receivers that send one GGA per constellation
/// count only that constellation's satellites in it (Telit PLS83: GPGGA 5, GAGGA 1, GNGNS 14).
Ranks talkerRanks(const NmeaSentence& s)
{
  const int combined = s.talker[0] == 'G' && s.talker[1] == 'N' ? 1 : 0;
  const auto scale = [combined](int rank) { return rank == 0 ? 0 : 2 * rank + combined; };
  const Ranks r = ranksOf(s.type);
  return {scale(r.position), scale(r.altitude), scale(r.velocity), scale(r.sigma), scale(r.quality)};
}

/// A field group is taken from a sentence that ranks strictly higher than the one it came from,
/// so that the first of two equal sources (RMC and VTG) is kept.
bool takes(int rank, int& current)
{
  if (rank == 0 || rank <= current)
    return false;
  current = rank;
  return true;
}
}  // namespace

std::optional<GnssFix> GnssEpochAssembler::add(const NmeaSentence& sentence, double receive_time_s)
{
  std::optional<GnssFix> completed;
  const bool timed = !std::isnan(sentence.time_of_day_s);
  if (pending_ && timed && !std::isnan(time_of_day_s_) && !sameTime(time_of_day_s_, sentence.time_of_day_s))
    completed = flush();
  if (!pending_)
    start(receive_time_s);
  if (timed && std::isnan(time_of_day_s_))
    time_of_day_s_ = sentence.time_of_day_s;
  if (sentence.day)
    sentence_day_ = sentence.day;
  merge(sentence);
  last_receive_time_s_ = receive_time_s;
  return completed;
}

void GnssEpochAssembler::start(double receive_time_s)
{
  pending_ = true;
  fix_ = GnssFix();
  time_of_day_s_ = GnssFix::kNaN;
  sentence_day_.reset();
  position_rank_ = altitude_rank_ = velocity_rank_ = sigma_rank_ = quality_rank_ = 0;
  last_receive_time_s_ = receive_time_s;
}

void GnssEpochAssembler::merge(const NmeaSentence& s)
{
  const Ranks rank = talkerRanks(s);
  if (s.fix_quality >= 0 && takes(rank.quality, quality_rank_))
    fix_.fix_quality = static_cast<std::uint8_t>(s.fix_quality);
  if (!std::isnan(s.latitude_deg) && takes(rank.position, position_rank_))
  {
    fix_.latitude_deg = s.latitude_deg;
    fix_.longitude_deg = s.longitude_deg;
    fix_.valid_fields |= GnssFix::kValidPosition;
  }
  if (takes(rank.altitude, altitude_rank_))
  {
    if (!std::isnan(s.altitude_m))
    {
      fix_.altitude_m = s.altitude_m;
      fix_.geoid_separation_m = s.geoid_separation_m;
      fix_.valid_fields |= GnssFix::kValidAltitude;
    }
    if (s.satellites >= 0)
    {
      fix_.satellites_used = static_cast<std::uint16_t>(s.satellites);
      fix_.valid_fields |= GnssFix::kValidSatellites;
    }
    if (!std::isnan(s.hdop))
    {
      fix_.hdop = s.hdop;
      fix_.valid_fields |= GnssFix::kValidHdop;
    }
  }
  if (!std::isnan(s.speed_mps) && takes(rank.velocity, velocity_rank_))
  {
    fix_.speed_over_ground_mps = s.speed_mps;
    fix_.valid_fields |= GnssFix::kValidSpeed;
    fix_.course_rad = s.course_rad;  // empty at standstill on many receivers
    if (!std::isnan(s.course_rad))
      fix_.valid_fields |= GnssFix::kValidCourse;
    else
      fix_.valid_fields &= ~GnssFix::kValidCourse;
  }
  if (!std::isnan(s.latitude_sigma_m) && takes(rank.sigma, sigma_rank_))
  {
    fix_.latitude_sigma_m = s.latitude_sigma_m;
    fix_.longitude_sigma_m = s.longitude_sigma_m;
    fix_.altitude_sigma_m = s.altitude_sigma_m;
    fix_.valid_fields |= GnssFix::kValidPositionSigma;
  }
}

std::optional<GnssFix> GnssEpochAssembler::flush()
{
  if (!pending_)
    return std::nullopt;
  pending_ = false;
  if (std::isnan(time_of_day_s_))
  {
    ++epochs_without_time_;
    return std::nullopt;
  }
  GnssFix fix = fix_;
  if (fix.fix_quality == 7 || fix.fix_quality == 8)  // manual input, simulator: not a measurement,
    fix.valid_fields &= ~(GnssFix::kValidPosition | GnssFix::kValidAltitude);  // whatever RMC said
  fix.receive_time_s = last_receive_time_s_;
  const std::optional<std::int64_t> day = dates_.dayOf(time_of_day_s_, sentence_day_);
  fix.has_date = day.has_value();
  fix.gnss_time_s = day ? static_cast<double>(*day) * kSecondsPerDay + time_of_day_s_ : time_of_day_s_;
  if (fix.has_date)
    fix.valid_fields |= GnssFix::kValidDate;
  return fix;
}

}  // namespace acc
