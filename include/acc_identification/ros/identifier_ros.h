#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/calibration/identification.h"
#include "acc_identification/calibration/model_adequacy.h"
#include "acc_identification/calibration/online_identifier.h"
#include "acc_identification/calibration/drive_record.h"
#include "acc_identification/calibration/sliding_window.h"
#include "acc_identification/io/acc_engagement.h"
#include "acc_identification/parameters/parameter_reader.h"
#include "acc_identification/ros/stability_look_schedule.h"

#include <acc_identification/AccParameters.h>
#include <acc_identification/RelativeState.h>
#include <std_msgs/Bool.h>
#include <std_msgs/String.h>

namespace acc
{
/// The node's settings (private parameters; defaults in config/identifier.yaml).
struct IdentifierSettings
{
  double window_s = 120.0;            ///< sliding window length [s]
  double period_s = 1.0;              ///< recalibration period, on the ROS clock (sim time too) [s]
  double stale_after_s = 5.0;         ///< WARN when no relative_state came for this long (wall clock) [s]
  double max_gap_s = 0.5;             ///< a longer hole in relative_state splits the window [s]
  /// A jump in time (back beyond max_gap_s, ahead beyond max_forward_jump_s) changes the window
  /// only once this many consecutive samples agree on the new time base (at least 2: one stamp
  /// never empties the window); until then they are held, and dropped as outliers should the old
  /// time base go on.
  int jump_confirm_samples = 5;
  double max_forward_jump_s = 30.0;   ///< a longer step ahead is a jump, held until confirmed [s]
  int min_segment_samples = 20;       ///< shorter pieces between holes are not simulated
  int starts = 8;                     ///< fresh Halton starts per solve, besides the warm start
  int queue_size = 1000;              ///< subscriber queue: a replay may burst
  int drive_max_evaluations = 40;     ///< per period, continuing the drive-so-far solve
  /// The drive so far's bound (max_samples 0: unbounded); see acc::DriveBound.
  DriveBound drive_bound;
  double stability_period_s = 10.0;   ///< at most one string-stability test of the drive per this (ROS time)
  double alpha = 0.05;                ///< level of the string-stability test
  /// The drive fit's Euler step check runs with each look when the data's median step is at least
  /// this (OnlineIdentifierOptions::euler_check_min_step_s) [s].
  double euler_check_min_step_s = 0.15;
  IdentifiabilityCriteria criteria;
  /// How the ACC's engagement reports on acc_engaged are read (~require_acc_engaged,
  /// ~acc_engaged_timeout_s): a sample while the ACC is off is a split point, not used.
  AccEngagementSettings engagement;
  /// The drive fit's model adequacy (~adequacy_* parameters; the dip check needs perturbations
  /// of a platoon and is the campaign's).
  ModelAdequacyOptions adequacy;
};

/// Reads the private parameters; false and reader.error() on a bad value (type or range).
bool loadIdentifierSettings(ParameterReader& reader, IdentifierSettings& settings);

/// What the node warns of at start in settings that are valid one by one and useless together
/// (a window shorter than the data a fit needs: every window estimate would say so); "" if none.
std::string identifierSettingsNote(const IdentifierSettings& settings);

/// The message for one update: the window's solve (times from its first and last sample, GNSS
/// time), each quantity NaN only where the window does not determine it; the drive so far; the
/// latest string-stability test of the drive (none yet: verdict "undecided", NaN p-value).
acc_identification::AccParameters toMessage(const OnlineUpdate& update, double window_start_s, double window_end_s,
                                            double drive_start_s);
/// A relative_state message as a window sample. A sample the pairing marked valid but whose values
/// are physically impossible (acc::RunPlausibilityBounds, the batch readers' check) is marked
/// invalid, a split point, and why says so; otherwise why is left empty.
WindowSample toWindowSample(const acc_identification::RelativeState& message, std::string& why);

/// The drive fit's model adequacy into the message (model_adequate, model_adequacy_reasons).
void setModelAdequacy(const ModelAdequacy& adequacy, acc_identification::AccParameters& m);

/// The same for a window alone (no drive, no test yet).
acc_identification::AccParameters toMessage(const Identification& identification, double window_start_s, double window_end_s);

/// The identifier node's counters at one instant: totals since the node started.
struct IdentifierCounters
{
  std::uint64_t received = 0;
  std::uint64_t invalid = 0;           ///< marked invalid by the pairing: split points
  std::uint64_t non_finite = 0;        ///< a NaN or infinite value or time
  std::uint64_t implausible = 0;       ///< outside acc::RunPlausibilityBounds: split points
  std::uint64_t acc_off = 0;           ///< while the ACC reported itself off: split points, not used
  std::uint64_t acc_state_unknown = 0; ///< engagement required but not known: split points, not used
  std::uint64_t engagement_reports = 0;
  std::uint64_t disengagements = 0;
  std::uint64_t setting_changes = 0;   ///< acc_setting reports of a new setting (with samples before: a new drive)
  std::uint64_t out_of_order = 0;      ///< late or duplicate: rejected
  std::uint64_t time_outliers = 0;     ///< a jump in time the old time base contradicted: dropped
  std::uint64_t restarts = 0;          ///< confirmed jumps back: window cleared, drive restarted
  std::uint64_t jumps_ahead = 0;       ///< confirmed jumps ahead
  std::uint64_t held = 0;              ///< samples of a jump awaiting confirmation (now, not a total)
  std::uint64_t drive_resets = 0;
  std::uint64_t solves = 0;
  std::uint64_t skipped_periods = 0;   ///< a solve overran the period
  std::uint64_t not_identifiable = 0;
  std::uint64_t unusable_windows = 0;  ///< periods whose window held only pieces too short to simulate, split by holes
  std::uint64_t published = 0;
  std::uint64_t failures = 0;          ///< solves and string-stability tests that threw
  std::uint64_t stability_tests = 0;
  std::uint64_t drive_samples_let_go = 0;  ///< to keep the drive within its bound (expected, not a fault)
  std::uint64_t drive_blocks_let_go = 0;
};

/// The level (diagnostic_msgs::DiagnosticStatus) and summary of one diagnostics report.
struct IdentifierHealth
{
  std::uint8_t level = 0;
  std::string message;
};

/// What happened between two reports, as relative_state_node reports it: ERROR when a solve or a
/// test threw since the previous report (with last_failure, what it threw), WARN when a period was
/// skipped or samples were rejected, dropped, implausible, of an unknown ACC state (engagement
/// required) or a jump in time was confirmed since then, WARN before the first sample, else OK
/// ("ACC off: ..." while samples come with the ACC off: the driver's choice, not a fault). One
/// bad sample an hour ago is no reason to stay WARN: the totals are the key-values.
/// silent_s: wall seconds since the last relative_state; beyond stale_after_s the input has
/// stopped (WARN, after the faults above): the estimate and verdict stay those of the data so far.
/// A period whose window held samples but only pieces too short to simulate (a receiver slower
/// than max_gap_s allows, or holes everywhere) is WARN too, with unusable_window_note
/// (SlidingWindow::describeShortPieces): samples arrive, and nothing of them can be used.
/// ros_time_still_s: wall seconds ROS time has stood still (under /use_sim_time); beyond
/// stale_after_s while samples come, no period runs (a replay left /use_sim_time true and nothing
/// publishes /clock): ERROR, nothing is estimated or published.
IdentifierHealth identifierHealth(const IdentifierCounters& now, const IdentifierCounters& previous,
                                  const std::string& last_failure, double silent_s = 0.0,
                                  double stale_after_s = std::numeric_limits<double>::infinity(),
                                  const std::string& unusable_window_note = "", double ros_time_still_s = 0.0);

/// Runs work and catches whatever it throws: true when it returned; false when it threw, with
/// failure saying what (a std::exception's what(), or that it was not a std::exception).
bool runCatchingEverything(const std::function<void()>& work, std::string& failure);

/// identifier_node: subscribes to relative_state, keeps a sliding window and the drive so far, and
/// every period recalibrates the ACC model on the window (warm-started from the previous fit),
/// continues the drive's calibration, and publishes acc_parameters. Solves run on a worker thread
/// so that the subscriber never waits; a solve still running when the next period comes makes
/// that period skip (counted, and said). The drive's sequential string-stability verdict
/// (SequentialVerdict: anytime-valid, a decision once taken is kept) runs on a thread of its own:
/// at most once per ~stability_period_s of ROS time it makes every look due at data times
/// drive start + k ~stability_period_s (late, never lost, when the thread was busy), and one at
/// the last sample when the data stop; each message carries its latest look. Whatever a solve or a test throws is caught on its thread, counted
/// and reported (ERROR with what it threw): the node goes on with the next period.
///
/// Samples are checked as the batch readers check them (acc::RunPlausibilityBounds: implausible
/// values are split points; samples while the ACC's engagement reports on acc_engaged say it is
/// off are split points, acc::AccEngagement), and jumps in time need ~jump_confirm_samples consistent samples
/// before they clear or move the window (acc::SlidingWindow). Diagnostics report what changed
/// since the last report, with every total as a key-value.
class IdentifierRos
{
public:
  /// One period's computation: OnlineIdentifier::update by default. A seam for tests, which inject
  /// a solve that throws to check that the worker survives it and says so.
  using SolveFunction = std::function<OnlineUpdate(OnlineIdentifier& identifier,
                                                   const std::vector<CarFollowingRun>& window_segments,
                                                   const std::vector<CarFollowingRun>& drive_segments)>;

  IdentifierRos(ros::NodeHandle node, ros::NodeHandle private_node, SolveFunction solve = {});
  ~IdentifierRos();
  bool ok() const { return ok_; }

private:
  /// What the timer hands to the worker.
  struct Job
  {
    std::vector<CarFollowingRun> segments;
    std::vector<CarFollowingRun> drive_segments;
    double window_start_s = 0.0;
    double window_end_s = 0.0;
    double drive_start_s = 0.0;
    std::uint64_t drive_samples_taken = 0;   ///< since the drive began: says whether it grew
    std::uint64_t drive_samples_let_go = 0;  ///< of this drive, to keep within the bound
    bool drive_reset = false;  ///< time went back: the drive starts anew
    bool test_stability = false;  ///< hand the drive to the stability thread after this solve
    bool data_stopped = false;    ///< the drive did not grow this period: look at its last sample too
    std::string short_pieces_note;  ///< the window's pieces too short to simulate (SlidingWindow::describeShortPieces)
    std::string acc_setting;        ///< the ACC's setting the window and the drive are of ("": none reported)
  };
  /// What the worker hands to the stability thread.
  struct StabilityJob
  {
    std::vector<CarFollowingRun> drive_segments;
    bool data_stopped = false;
    std::uint64_t drive_generation = 0;  ///< which drive: a newer one resets the sequential verdict
    Identification drive;                ///< the drive's fit this period, for the Euler step check
  };

  void onRelativeState(const acc_identification::RelativeState::ConstPtr& message);
  void onAccEngaged(const std_msgs::Bool::ConstPtr& message);
  /// A new setting starts a new drive: the window is cleared and the drive restarted.
  void onAccSetting(const std_msgs::String::ConstPtr& message);
  /// Whether the ACC drove when the sample arrived (now, on the ROS clock): false when it did not,
  /// counted and said once per stretch.
  bool accDrove(double sample_time_s);
  void onPeriod(const ros::TimerEvent& event);
  /// One period at ROS time now_s. A catch-up period (/clock stood still: the end of a replay, a
  /// pause) only asks for the last look of a drive that stopped, and publishes a look not yet
  /// published; otherwise it does nothing (the last estimate stands).
  void runPeriod(double now_s, bool catch_up);
  /// Every wall second under /use_sim_time: a catch-up period when /clock has not moved since the last.
  void checkClockMoves();
  void workerLoop();
  void stabilityLoop();
  /// Gives the stability thread the drive, unless it is still busy with an earlier one.
  void offerStabilityJob(const Job& job, const OnlineUpdate& update);
  /// One job of the worker: the solve, the message, the stability request.
  void runJob(Job& job);
  /// Counts a solve or test that threw and keeps what it threw for the diagnostics.
  void noteFailure(const char* what, const std::string& failure);
  IdentifierCounters counters();
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  bool ok_ = false;
  IdentifierSettings settings_;
  SolveFunction solve_;
  std::mutex window_mutex_;
  SlidingWindow window_;
  DriveRecord drive_;
  bool drive_reset_pending_ = false;     ///< under window_mutex_
  std::string acc_setting_;              ///< the latest reported setting, under window_mutex_
  std::string unusable_window_note_;     ///< why the last unusable window was, under window_mutex_
  StabilityLookSchedule look_schedule_;  ///< timer thread only

  std::mutex job_mutex_;
  std::condition_variable job_ready_;
  std::optional<Job> job_;
  bool busy_ = false;
  bool stopping_ = false;
  std::thread worker_;
  std::optional<OnlineIdentifier> identifier_;  ///< worker thread only (testDrive() is const)

  std::mutex stability_mutex_;
  std::condition_variable stability_ready_;
  std::optional<StabilityJob> stability_job_;
  bool stability_busy_ = false;
  bool stopping_stability_ = false;
  std::optional<SequentialLook> stability_result_;  ///< the latest look, under stability_mutex_
  std::optional<EulerStepBias> euler_step_result_;  ///< the drive fit's latest check, under stability_mutex_
  std::uint64_t euler_step_checks_ = 0;             ///< under stability_mutex_
  std::uint64_t drive_generation_ = 0;              ///< drive resets so far, under stability_mutex_
  /// The drive's sequential verdict: stability thread only (with the generation it belongs to).
  std::optional<SequentialVerdict> sequential_;
  std::uint64_t sequential_generation_ = 0;
  std::thread stability_worker_;

  std::mutex engagement_mutex_;
  AccEngagement engagement_;  ///< under engagement_mutex_

  ros::Subscriber subscriber_;
  ros::Subscriber engagement_subscriber_;
  ros::Subscriber setting_subscriber_;
  ros::Publisher publisher_;
  ros::Timer period_timer_;
  ros::WallTimer clock_timer_;   ///< checkClockMoves
  double last_seen_ros_s_ = -1.0;  ///< ROS time at the last checkClockMoves
  std::atomic<std::uint64_t> looks_published_{0};  ///< stability_tests_ as of the last published message
  std::atomic<double> last_sample_wall_s_{0.0};  ///< ros::WallTime of the last relative_state (0: none yet)
  std::atomic<double> clock_moved_wall_s_{0.0};  ///< ros::WallTime ROS time last moved (sim time; 0: not seen)
  diagnostic_updater::Updater updater_;
  ros::WallTimer diagnostic_timer_;

  // Counters (atomic: read by the diagnostics, written by the callbacks and the worker). What the
  // window rejected, dropped or confirmed is in window_.counts(), under window_mutex_.
  std::atomic<std::uint64_t> received_{0}, invalid_{0}, non_finite_values_{0}, implausible_{0};
  std::atomic<std::uint64_t> solves_{0}, skipped_periods_{0}, not_identifiable_{0}, unusable_windows_{0}, published_{0};
  std::atomic<std::uint64_t> stability_tests_{0}, drive_resets_{0}, failures_{0}, setting_changes_{0};
  std::mutex failure_mutex_;
  std::string last_failure_;  ///< what the last failed solve or test threw, under failure_mutex_
  /// Counters at the last diagnostics report (diagnostics thread only): the level reports changes.
  IdentifierCounters reported_;
  std::atomic<bool> stability_request_dropped_{false};
  std::atomic<double> last_solve_time_s_{0.0}, last_drive_time_s_{0.0}, last_stability_time_s_{0.0};
};

}  // namespace acc
