#pragma once

#include <cstdint>
#include <deque>
#include <optional>
#include <vector>

#include "acc_identification/gnss/gnss_fix.h"
#include "acc_identification/gnss/nmea_sentence.h"
#include "acc_identification/gnss/utc_date.h"

namespace acc
{
/// Combines the sentences of one epoch into one GnssFix. An epoch is the run of sentences with
/// the same UTC time of day; sentences without time (VTG) belong to the epoch being assembled.
/// An epoch completes when a sentence of another time arrives, or when flushed (the driver
/// flushes after a short silence so that a fix does not wait for the next epoch). A sentence of
/// an epoch already completed (one of the last three) is counted and leaves no second fix of that
/// time: a replay stalled on a loaded host, or a link that reorders, must not give one instant two
/// fixes.
/// Within an epoch, each field comes from the best sentence that carried it:
///   position: GGA = GNS > PUBX,00 > RMC = GLL;  altitude, satellites, HDOP: GGA = GNS > PUBX,00;
///   speed and course: RMC = VTG > PUBX,00;  sigmas: GST > PUBX,00;  date: RMC, ZDA.
/// Between equals the combined talker GN beats a single constellation's (GPGGA < GNGNS), else
/// the first one stays.
///
/// Over a link that reorders (UDP across a radio with jitter) an epoch's sentences can arrive
/// apart: its RMC after the next epoch's GGA, or after a pause longer than the idle flush. With a
/// reorder wait (setReorderWait, 0 by default: the behaviour above exactly), an epoch that lacks
/// a field group (position, speed) which each of the stream's last three epochs carried is not
/// completed yet: it waits for its late sentences while the next epoch assembles, and completes
/// when they come, when a sentence two epochs newer arrives, or after the reorder wait.
class GnssEpochAssembler
{
public:
  /// Adds a sentence received at receive_time_s. Returns the fixes it completed, oldest first.
  std::vector<GnssFix> add(const NmeaSentence& sentence, double receive_time_s);
  /// Completes every pending epoch, waiting or not (end of stream, a long silence).
  std::vector<GnssFix> flush();
  /// A pause of idle_s since the last sentence: completes the pending epoch, unless it waits for
  /// late sentences, and any waiting epoch older than the reorder wait.
  std::vector<GnssFix> flushIdle(double now_s);

  /// Seconds an incomplete epoch may wait for its late sentences (0: never wait).
  void setReorderWait(double wait_s) { reorder_wait_s_ = wait_s; }

  bool hasPending() const { return current_.pending || waiting_.pending; }
  /// Receive time of the last sentence added to the pending epoch.
  double lastReceiveTime() const { return current_.last_receive_time_s; }
  std::uint64_t epochsWithoutTime() const { return epochs_without_time_; }
  std::uint64_t dateLagCorrections() const { return dates_.lagCorrections(); }
  /// Sentences that reached an epoch waiting for them (with a reorder wait).
  std::uint64_t lateSentencesMerged() const { return late_merged_; }
  /// Sentences whose epoch had already been completed: not in any fix (their raw line is).
  std::uint64_t lateSentencesAfterFix() const { return late_after_fix_; }
  /// A second sentence of one type and talker in one epoch (a log with every line twice, a
  /// receiver repeating itself): not used, the first kept (their raw lines are).
  std::uint64_t repeatedSentences() const { return repeated_; }

private:
  /// One epoch being assembled.
  struct Epoch
  {
    bool pending = false;
    GnssFix fix;
    double time_of_day_s = GnssFix::kNaN;
    std::optional<std::int64_t> sentence_day;
    int position_rank = 0, altitude_rank = 0, velocity_rank = 0, sigma_rank = 0, quality_rank = 0;
    std::vector<std::uint32_t> sources;  ///< the type and talker of each sentence merged (sourceOf)
    double first_receive_time_s = GnssFix::kNaN;
    double last_receive_time_s = GnssFix::kNaN;
  };

  static void start(Epoch& epoch, double receive_time_s);
  static void merge(Epoch& epoch, const NmeaSentence& sentence);
  void addTo(Epoch& epoch, const NmeaSentence& sentence, double receive_time_s);
  /// Completes an epoch: its fix, or none for an epoch without time (counted).
  void complete(Epoch& epoch, std::vector<GnssFix>& out);
  /// The field groups (kValidPosition, kValidSpeed) each of the last three fixes had, that this
  /// epoch lacks: nonzero means its late sentences are probably on the way.
  std::uint32_t missingGroups(const Epoch& epoch) const;
  bool recentlyCompleted(double time_of_day_s) const;

  Epoch current_;
  Epoch waiting_;  ///< an incomplete older epoch, waiting for late sentences
  double reorder_wait_s_ = 0.0;
  std::deque<std::uint32_t> recent_groups_;  ///< field groups of the last fixes, newest last
  std::deque<double> recent_times_;          ///< times of day of the last completed epochs
  std::uint64_t epochs_without_time_ = 0;
  std::uint64_t late_merged_ = 0;
  std::uint64_t late_after_fix_ = 0;
  std::uint64_t repeated_ = 0;
  UtcDateTracker dates_;
};

}  // namespace acc
