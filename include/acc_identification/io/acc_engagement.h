#pragma once

#include <cstdint>
#include <string>

namespace acc
{
/// How the reports of the ACC's engagement are read (identifier_node's ~require_acc_engaged and
/// ~acc_engaged_timeout_s; the tools' --require-acc-engaged).
struct AccEngagementSettings
{
  /// A sample is used only while the latest report says engaged: before the first report, and
  /// after a stale one, it is not (ACC state unknown). false: those samples are used, so that a
  /// drive without an engagement source is read as before.
  bool required = false;
  /// A report older than this no longer says anything (a CAN bridge that died) [s]; 0: a report
  /// holds until the next one (a source that publishes on change only).
  double timeout_s = 0.0;
};

/// Why the settings cannot be used ("" when they can): a timeout that is negative or not finite.
std::string describeAccEngagementSettingsProblem(const AccEngagementSettings& settings);

/// Whether the ACC was driving when a sample arrived, from the reports of an engagement source
/// (std_msgs/Bool on acc_engaged: a CAN bridge, the ACC's switch, a laptop in the car). Only the
/// samples the ACC drives obey its law: a braking by the safety driver inside a window would be
/// fitted as the ACC's, and the ACC resuming afterwards starts from the driver's state, which the
/// model does describe. So a sample while the ACC is off is a split point and is not used, as the
/// OpenACC reader treats a row whose Driver column is not ACC.
///
/// One rule for the live node and the bag reader: reports and samples are ordered by their arrival
/// on the ROS clock (a bag's record times in batch, which a replay reproduces), so a bag read in
/// batch uses the samples the node used. A report whose time is after a sample's (a clock that
/// went back, as a looping replay's does) counts as the latest one. The status is applied as it
/// arrives: a driver's braking before the ACC reports itself off stays in the data.
class AccEngagement
{
public:
  enum class Use
  {
    kUsed,          ///< engaged, or unknown and not required
    kAccOff,        ///< the latest report says not engaged
    kStateUnknown,  ///< required, and no report yet or the latest is older than timeout_s
  };

  /// One sample's judgement. starts_stretch: the previous sample was used, or was not used for
  /// another reason (say it once per stretch, not once per sample).
  struct Judgement
  {
    Use use = Use::kUsed;
    bool starts_stretch = false;
  };

  /// Throws std::invalid_argument when describeAccEngagementSettingsProblem says why.
  explicit AccEngagement(const AccEngagementSettings& settings = {});

  /// A report from the source, arriving at arrival_s [s].
  void report(double arrival_s, bool engaged);

  /// Judges a sample arriving at arrival_s [s] and counts it.
  Judgement judge(double arrival_s);

  /// Why a sample judged `use` is not used, for the logs and the readers' problem lines; "" for kUsed.
  std::string describe(Use use) const;

  std::uint64_t reports() const { return reports_; }
  std::uint64_t samplesOff() const { return samples_off_; }          ///< not used: ACC off
  std::uint64_t samplesUnknown() const { return samples_unknown_; }  ///< not used: state unknown
  std::uint64_t disengagements() const { return disengagements_; }   ///< reports of off after on (or first)
  /// "engaged", "off" or "no report yet": the latest report, whatever its age.
  std::string latestReport() const;

private:
  Use useAt(double arrival_s) const;

  AccEngagementSettings settings_;
  bool has_report_ = false;
  bool engaged_ = false;
  double report_time_s_ = 0.0;
  Use previous_use_ = Use::kUsed;
  std::uint64_t reports_ = 0;
  std::uint64_t samples_off_ = 0;
  std::uint64_t samples_unknown_ = 0;
  std::uint64_t disengagements_ = 0;
};

}  // namespace acc
