#pragma once

#include <atomic>
#include <condition_variable>
#include <cstdint>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <diagnostic_updater/diagnostic_updater.h>
#include <ros/ros.h>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/calibration/identification.h"
#include "acc_identification/calibration/sliding_window.h"

#include <acc_identification/AccParameters.h>
#include <acc_identification/RelativeState.h>

namespace acc
{
/// The node's settings (private parameters; defaults in config/identifier.yaml).
struct IdentifierSettings
{
  double window_s = 120.0;            ///< sliding window length [s]
  double period_s = 1.0;              ///< recalibration period, on the ROS clock (sim time too) [s]
  double max_gap_s = 0.5;             ///< a longer hole in relative_state splits the window [s]
  int min_segment_samples = 20;       ///< shorter pieces between holes are not simulated
  int starts = 8;                     ///< fresh Halton starts per solve, besides the warm start
  int queue_size = 1000;              ///< subscriber queue: a replay may burst
  IdentifiabilityCriteria criteria;
};

/// Reads the private parameters; false and a message on a bad value.
bool loadIdentifierSettings(const ros::NodeHandle& private_node, IdentifierSettings& settings, std::string& error);

/// The message for one solve of a window (window times from its first and last sample, GNSS time).
acc_identification::AccParameters toMessage(const Identification& identification, double window_start_s, double window_end_s);

/// identifier_node: subscribes to relative_state, keeps a sliding window, and every period
/// recalibrates the ACC model on it (warm-started from the previous fit) and publishes
/// acc_parameters. Solves run on a worker thread so that the subscriber never waits; a solve
/// still running when the next period comes makes that period skip (counted, and said).
class IdentifierRos
{
public:
  IdentifierRos(ros::NodeHandle node, ros::NodeHandle private_node);
  ~IdentifierRos();
  bool ok() const { return ok_; }

private:
  /// What the timer hands to the worker.
  struct Job
  {
    std::vector<CarFollowingRun> segments;
    double window_start_s = 0.0;
    double window_end_s = 0.0;
  };

  void onRelativeState(const acc_identification::RelativeState::ConstPtr& message);
  void onPeriod(const ros::TimerEvent& event);
  void workerLoop();
  void diagnose(diagnostic_updater::DiagnosticStatusWrapper& status);

  bool ok_ = false;
  IdentifierSettings settings_;
  IdentificationOptions options_;

  std::mutex window_mutex_;
  SlidingWindow window_;

  std::mutex job_mutex_;
  std::condition_variable job_ready_;
  std::optional<Job> job_;
  bool busy_ = false;
  bool stopping_ = false;
  std::thread worker_;
  std::optional<AccParameters> warm_start_;  ///< worker thread only

  ros::Subscriber subscriber_;
  ros::Publisher publisher_;
  ros::Timer period_timer_;
  diagnostic_updater::Updater updater_;
  ros::WallTimer diagnostic_timer_;

  // Counters (atomic: read by the diagnostics, written by the callbacks and the worker).
  std::atomic<std::uint64_t> received_{0}, invalid_{0}, non_finite_{0}, out_of_order_{0}, restarts_{0};
  std::atomic<std::uint64_t> solves_{0}, skipped_periods_{0}, not_identifiable_{0}, published_{0};
  std::atomic<double> last_solve_time_s_{0.0};
};

}  // namespace acc
