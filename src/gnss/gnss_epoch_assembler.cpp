#include "acc_identification/gnss/gnss_epoch_assembler.h"

#include <algorithm>
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

/// A sentence's type and talker in one number: two sentences of one epoch with the same are a repeat.
std::uint32_t sourceOf(const NmeaSentence& s)
{
  return (static_cast<std::uint32_t>(s.type) << 16) | (static_cast<std::uint32_t>(static_cast<unsigned char>(s.talker[0])) << 8) |
         static_cast<unsigned char>(s.talker[1]);
}

/// The field groups whose absence makes an epoch wait for late sentences (with a reorder wait),
/// learned from this many of the last epochs.
constexpr std::uint32_t kGroups = GnssFix::kValidPosition | GnssFix::kValidSpeed;
constexpr std::size_t kRecentEpochs = 3;
}  // namespace

std::vector<GnssFix> GnssEpochAssembler::add(const NmeaSentence& sentence, double receive_time_s)
{
  std::vector<GnssFix> completed;
  const bool timed = !std::isnan(sentence.time_of_day_s);
  if (timed && waiting_.pending && sameTime(waiting_.time_of_day_s, sentence.time_of_day_s))
  {
    ++late_merged_;  // the late sentence this epoch waited for
    addTo(waiting_, sentence, receive_time_s);
    if (missingGroups(waiting_) == 0)
      complete(waiting_, completed);
    return completed;
  }
  const bool new_time = timed && current_.pending && !std::isnan(current_.time_of_day_s) &&
                        !sameTime(current_.time_of_day_s, sentence.time_of_day_s);
  if (timed && (new_time || !current_.pending) && recentlyCompleted(sentence.time_of_day_s))
  {
    // Its epoch is out already (completed by the next epoch or by an idle flush, with or without
    // a reorder wait): a second fix of that time would give the pairing two follower samples of
    // one instant. Counted; its raw line is published like every other.
    ++late_after_fix_;
    return completed;
  }
  if (new_time)
  {
    if (waiting_.pending)
      complete(waiting_, completed);  // two epochs old: its late sentences had their chance
    if (reorder_wait_s_ > 0.0 && missingGroups(current_) != 0)
    {
      waiting_ = current_;
      current_.pending = false;
    }
    else
    {
      complete(current_, completed);
    }
  }
  if (!current_.pending)
    start(current_, receive_time_s);
  addTo(current_, sentence, receive_time_s);
  return completed;
}

void GnssEpochAssembler::addTo(Epoch& epoch, const NmeaSentence& sentence, double receive_time_s)
{
  const std::uint32_t source = sourceOf(sentence);
  if (std::find(epoch.sources.begin(), epoch.sources.end(), source) != epoch.sources.end())
  {
    ++repeated_;  // the first of the two is kept, as the ranks keep the first of equal sources
    return;
  }
  epoch.sources.push_back(source);
  if (!std::isnan(sentence.time_of_day_s) && std::isnan(epoch.time_of_day_s))
    epoch.time_of_day_s = sentence.time_of_day_s;
  if (sentence.day)
    epoch.sentence_day = sentence.day;
  merge(epoch, sentence);
  epoch.last_receive_time_s = receive_time_s;
}

void GnssEpochAssembler::start(Epoch& epoch, double receive_time_s)
{
  epoch = Epoch();
  epoch.pending = true;
  epoch.first_receive_time_s = receive_time_s;
  epoch.last_receive_time_s = receive_time_s;
}

std::uint32_t GnssEpochAssembler::missingGroups(const Epoch& epoch) const
{
  if (recent_groups_.size() < kRecentEpochs)
    return 0;  // nothing learned yet: complete as without a reorder wait
  std::uint32_t usual = kGroups;
  for (std::uint32_t groups : recent_groups_)
    usual &= groups;
  return usual & ~epoch.fix.valid_fields;
}

bool GnssEpochAssembler::recentlyCompleted(double time_of_day_s) const
{
  return std::any_of(recent_times_.begin(), recent_times_.end(),
                     [time_of_day_s](double t) { return sameTime(t, time_of_day_s); });
}

void GnssEpochAssembler::merge(Epoch& epoch, const NmeaSentence& s)
{
  const Ranks rank = talkerRanks(s);
  if (s.fix_quality >= 0 && takes(rank.quality, epoch.quality_rank))
    epoch.fix.fix_quality = static_cast<std::uint8_t>(s.fix_quality);
  if (!std::isnan(s.latitude_deg) && takes(rank.position, epoch.position_rank))
  {
    epoch.fix.latitude_deg = s.latitude_deg;
    epoch.fix.longitude_deg = s.longitude_deg;
    epoch.fix.valid_fields |= GnssFix::kValidPosition;
  }
  if (takes(rank.altitude, epoch.altitude_rank))
  {
    if (!std::isnan(s.altitude_m))
    {
      epoch.fix.altitude_m = s.altitude_m;
      epoch.fix.geoid_separation_m = s.geoid_separation_m;
      epoch.fix.valid_fields |= GnssFix::kValidAltitude;
    }
    if (s.satellites >= 0)
    {
      epoch.fix.satellites_used = static_cast<std::uint16_t>(s.satellites);
      epoch.fix.valid_fields |= GnssFix::kValidSatellites;
    }
    if (!std::isnan(s.hdop))
    {
      epoch.fix.hdop = s.hdop;
      epoch.fix.valid_fields |= GnssFix::kValidHdop;
    }
  }
  if (!std::isnan(s.speed_mps) && takes(rank.velocity, epoch.velocity_rank))
  {
    epoch.fix.speed_over_ground_mps = s.speed_mps;
    epoch.fix.valid_fields |= GnssFix::kValidSpeed;
    epoch.fix.course_rad = s.course_rad;  // empty at standstill on many receivers
    if (!std::isnan(s.course_rad))
      epoch.fix.valid_fields |= GnssFix::kValidCourse;
    else
      epoch.fix.valid_fields &= ~GnssFix::kValidCourse;
  }
  if (!std::isnan(s.latitude_sigma_m) && takes(rank.sigma, epoch.sigma_rank))
  {
    epoch.fix.latitude_sigma_m = s.latitude_sigma_m;
    epoch.fix.longitude_sigma_m = s.longitude_sigma_m;
    epoch.fix.altitude_sigma_m = s.altitude_sigma_m;
    epoch.fix.valid_fields |= GnssFix::kValidPositionSigma;
  }
}

void GnssEpochAssembler::complete(Epoch& epoch, std::vector<GnssFix>& out)
{
  if (!epoch.pending)
    return;
  epoch.pending = false;
  if (std::isnan(epoch.time_of_day_s))
  {
    ++epochs_without_time_;
    return;
  }
  GnssFix fix = epoch.fix;
  if (fix.fix_quality == 7 || fix.fix_quality == 8)  // manual input, simulator: not a measurement,
    fix.valid_fields &= ~(GnssFix::kValidPosition | GnssFix::kValidAltitude);  // whatever RMC said
  fix.receive_time_s = epoch.last_receive_time_s;
  const std::optional<std::int64_t> day = dates_.dayOf(epoch.time_of_day_s, epoch.sentence_day);
  fix.has_date = day.has_value();
  fix.gnss_time_s = day ? static_cast<double>(*day) * kSecondsPerDay + epoch.time_of_day_s
                        : dates_.undatedTimeS(epoch.time_of_day_s);
  if (fix.has_date)
    fix.valid_fields |= GnssFix::kValidDate;
  recent_groups_.push_back(epoch.fix.valid_fields & kGroups);
  recent_times_.push_back(epoch.time_of_day_s);
  while (recent_groups_.size() > kRecentEpochs)
    recent_groups_.pop_front();
  while (recent_times_.size() > kRecentEpochs)
    recent_times_.pop_front();
  out.push_back(fix);
}

std::vector<GnssFix> GnssEpochAssembler::flush()
{
  std::vector<GnssFix> out;
  complete(waiting_, out);
  complete(current_, out);
  return out;
}

std::vector<GnssFix> GnssEpochAssembler::flushIdle(double now_s)
{
  std::vector<GnssFix> out;
  if (waiting_.pending && now_s - waiting_.first_receive_time_s >= reorder_wait_s_)
    complete(waiting_, out);
  const bool waits = reorder_wait_s_ > 0.0 && missingGroups(current_) != 0 &&
                     now_s - current_.first_receive_time_s < reorder_wait_s_;
  if (current_.pending && !waits)
  {
    if (waiting_.pending)
      complete(waiting_, out);  // keep the order of the fixes
    complete(current_, out);
  }
  return out;
}

}  // namespace acc
