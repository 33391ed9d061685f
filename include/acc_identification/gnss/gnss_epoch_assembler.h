#pragma once

#include <cstdint>
#include <optional>

#include "acc_identification/gnss/gnss_fix.h"
#include "acc_identification/gnss/nmea_sentence.h"
#include "acc_identification/gnss/utc_date.h"

namespace acc
{
/// Combines the sentences of one epoch into one GnssFix. An epoch is the run of sentences with
/// the same UTC time of day; sentences without time (VTG) belong to the epoch being assembled.
/// An epoch completes when a sentence of another time arrives, or when flush() is called (the
/// driver flushes after a short silence so that a fix does not wait for the next epoch).
/// Within an epoch, each field comes from the best sentence that carried it:
///   position: GGA = GNS > PUBX,00 > RMC = GLL;  altitude, satellites, HDOP: GGA = GNS > PUBX,00;
///   speed and course: RMC = VTG > PUBX,00;  sigmas: GST > PUBX,00;  date: RMC, ZDA.
/// Between equals the combined talker GN beats a single constellation's (GPGGA < GNGNS), else
/// the first one stays.
class GnssEpochAssembler
{
public:
  /// Adds a sentence received at receive_time_s. Returns the previous epoch's fix when this
  /// sentence starts a new epoch.
  std::optional<GnssFix> add(const NmeaSentence& sentence, double receive_time_s);
  /// Completes the pending epoch, if any.
  std::optional<GnssFix> flush();

  bool hasPending() const { return pending_; }
  /// Receive time of the last sentence added to the pending epoch.
  double lastReceiveTime() const { return last_receive_time_s_; }
  std::uint64_t epochsWithoutTime() const { return epochs_without_time_; }
  std::uint64_t dateLagCorrections() const { return dates_.lagCorrections(); }

private:
  void start(double receive_time_s);
  void merge(const NmeaSentence& sentence);

  bool pending_ = false;
  GnssFix fix_;
  double time_of_day_s_ = GnssFix::kNaN;
  std::optional<std::int64_t> sentence_day_;
  int position_rank_ = 0, altitude_rank_ = 0, velocity_rank_ = 0, sigma_rank_ = 0, quality_rank_ = 0;
  double last_receive_time_s_ = GnssFix::kNaN;
  std::uint64_t epochs_without_time_ = 0;
  UtcDateTracker dates_;
};

}  // namespace acc
