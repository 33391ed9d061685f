#include "acc_identification/ros/identifier_ros.h"

#include <chrono>
#include <cmath>
#include <limits>

namespace acc
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

template <typename T>
bool readPositive(const ros::NodeHandle& node, const std::string& name, T& value, std::string& error)
{
  node.param(name, value, value);
  if (!(value > 0))
  {
    error = "parameter ~" + name + " must be positive";
    return false;
  }
  return true;
}

ros::Time toRosTime(double time_s) { return time_s > 0.0 ? ros::Time(time_s) : ros::Time(); }
}  // namespace

bool loadIdentifierSettings(const ros::NodeHandle& p, IdentifierSettings& s, std::string& error)
{
  IdentifiabilityCriteria& c = s.criteria;
  int min_samples = static_cast<int>(c.min_samples);
  const bool ok = readPositive(p, "window_s", s.window_s, error) && readPositive(p, "period_s", s.period_s, error) &&
                  readPositive(p, "max_gap_s", s.max_gap_s, error) &&
                  readPositive(p, "min_segment_samples", s.min_segment_samples, error) &&
                  readPositive(p, "queue_size", s.queue_size, error) &&
                  readPositive(p, "min_duration_s", c.min_duration_s, error) &&
                  readPositive(p, "min_samples", min_samples, error) &&
                  readPositive(p, "max_relative_standard_error", c.max_relative_standard_error, error);
  if (!ok)
  {
    return false;
  }
  c.min_samples = static_cast<std::size_t>(min_samples);
  p.param("starts", s.starts, s.starts);
  p.param("min_speed_std_mps", c.min_speed_std_mps, c.min_speed_std_mps);
  if (s.starts < 0 || c.min_speed_std_mps < 0.0)
  {
    error = "parameters ~starts and ~min_speed_std_mps must not be negative";
    return false;
  }
  return true;
}

acc_identification::AccParameters toMessage(const Identification& result, double window_start_s, double window_end_s)
{
  acc_identification::AccParameters m;
  m.header.stamp = toRosTime(window_end_s);
  m.window_start = toRosTime(window_start_s);
  m.window_end = toRosTime(window_end_s);
  m.samples = static_cast<std::uint32_t>(result.samples);
  m.segments = static_cast<std::uint32_t>(result.segments);
  // Not identifiable: the numbers would be noise, so they are NaN and the note says why.
  const bool publish = result.solved && result.identifiable;
  const AccParameters& p = result.calibration.parameters;
  const AccParameters& se = result.uncertainty.standard_error;
  m.k1_per_s2 = publish ? p.k1_per_s2 : kNaN;
  m.k2_per_s = publish ? p.k2_per_s : kNaN;
  m.tau_e_s = publish ? p.tau_e_s : kNaN;
  m.eta_m = publish ? p.eta_m : kNaN;
  m.k1_std_error = publish ? se.k1_per_s2 : kNaN;
  m.k2_std_error = publish ? se.k2_per_s : kNaN;
  m.tau_e_std_error = publish ? se.tau_e_s : kNaN;
  m.eta_std_error = publish ? se.eta_m : kNaN;
  m.rmse_speed_mps = result.solved ? result.fit.rmse_speed_mps : kNaN;
  m.rmse_gap_m = result.solved ? result.fit.rmse_gap_m : kNaN;
  m.lambda2 = publish ? result.stability.lambda2 : kNaN;
  m.string_stable = publish && result.stability.string_stable;
  m.amplified_band_upper_rad_s = publish ? result.stability.amplified_band_upper_rad_s : kNaN;
  m.peak_gain_db = publish ? result.stability.peak_gain_db : kNaN;
  m.peak_frequency_rad_s = publish ? result.stability.peak_frequency_rad_s : kNaN;
  m.solve_time_s = result.calibration.solve_time_s;
  m.optimizer_status = result.solved ? result.calibration.status : "NOT_SOLVED";
  m.identifiable = publish;
  m.identifiability_note = result.note;
  return m;
}

IdentifierRos::IdentifierRos(ros::NodeHandle node, ros::NodeHandle private_node)
  : window_(settings_.window_s, settings_.max_gap_s, 2)
{
  std::string error;
  if (!loadIdentifierSettings(private_node, settings_, error))
  {
    ROS_FATAL("identifier: %s", error.c_str());
    return;
  }
  window_ = SlidingWindow(settings_.window_s, settings_.max_gap_s, static_cast<std::size_t>(settings_.min_segment_samples));
  options_.criteria = settings_.criteria;
  options_.multistart.starts = static_cast<std::size_t>(settings_.starts);
  publisher_ = node.advertise<acc_identification::AccParameters>("acc_parameters", 10);
  subscriber_ = node.subscribe("relative_state", static_cast<std::uint32_t>(settings_.queue_size),
                               &IdentifierRos::onRelativeState, this);
  worker_ = std::thread(&IdentifierRos::workerLoop, this);
  period_timer_ = node.createTimer(ros::Duration(settings_.period_s), &IdentifierRos::onPeriod, this);
  updater_.setHardwareID("acc_identifier");
  updater_.add("ACC identification", this, &IdentifierRos::diagnose);
  // Health on the wall clock: update() would wait for the updater's own period on ROS time, which
  // stops with /clock at the end of a replay and leaves the last counts stale.
  diagnostic_timer_ = node.createWallTimer(ros::WallDuration(1.0),
                                           [this](const ros::WallTimerEvent&) { updater_.force_update(); });
  ROS_INFO("identifier: window %.0f s, every %.2f s, %d fresh starts plus a warm start; excitation: speed std >= %.2f m/s",
           settings_.window_s, settings_.period_s, settings_.starts, settings_.criteria.min_speed_std_mps);
  ok_ = true;
}

IdentifierRos::~IdentifierRos()
{
  {
    std::lock_guard<std::mutex> lock(job_mutex_);
    stopping_ = true;
  }
  job_ready_.notify_all();
  if (worker_.joinable())
  {
    worker_.join();
  }
}

void IdentifierRos::onRelativeState(const acc_identification::RelativeState::ConstPtr& message)
{
  ++received_;
  const WindowSample sample{message->header.stamp.toSec(), message->space_gap_m, message->follower_speed_mps,
                            message->leader_speed_mps, static_cast<bool>(message->valid)};
  SlidingWindow::AddResult result;
  {
    std::lock_guard<std::mutex> lock(window_mutex_);
    result = window_.add(sample);
  }
  switch (result)
  {
    case SlidingWindow::AddResult::kAdded: return;
    case SlidingWindow::AddResult::kInvalid: ++invalid_; return;  // the pairing already said why
    case SlidingWindow::AddResult::kNonFinite: ++non_finite_; break;
    case SlidingWindow::AddResult::kOutOfOrder: ++out_of_order_; break;
    case SlidingWindow::AddResult::kRestarted: ++restarts_; break;
  }
  ROS_WARN_THROTTLE(1.0, "identifier: relative_state at %.3f s: %s (counted in diagnostics)", sample.time_s,
                    SlidingWindow::describe(result).c_str());
}

void IdentifierRos::onPeriod(const ros::TimerEvent&)
{
  Job job;
  {
    std::lock_guard<std::mutex> lock(window_mutex_);
    if (window_.empty())
    {
      return;
    }
    job.segments = window_.segments();
    job.window_start_s = window_.startTimeS();
    job.window_end_s = window_.endTimeS();
  }
  {
    std::lock_guard<std::mutex> lock(job_mutex_);
    if (busy_)
    {
      ++skipped_periods_;
      ROS_WARN_THROTTLE(5.0, "identifier: the previous solve overran the %.2f s period: this period is skipped "
                        "(%llu skipped so far)", settings_.period_s, static_cast<unsigned long long>(skipped_periods_.load()));
      return;
    }
    busy_ = true;
    job_ = std::move(job);
  }
  job_ready_.notify_one();
}

void IdentifierRos::workerLoop()
{
  for (;;)
  {
    Job job;
    {
      std::unique_lock<std::mutex> lock(job_mutex_);
      job_ready_.wait(lock, [this] { return stopping_ || job_.has_value(); });
      if (stopping_)
      {
        return;
      }
      job = std::move(*job_);
      job_.reset();
    }
    std::vector<AccParameters> warm;
    if (warm_start_)
    {
      warm.push_back(*warm_start_);
    }
    const Identification result = identifyAcc(job.segments, options_, warm);
    if (result.solved)
    {
      ++solves_;
      last_solve_time_s_ = result.calibration.solve_time_s;
      if (!result.calibration.diverged)
      {
        warm_start_ = result.calibration.parameters;
      }
    }
    if (!result.identifiable)
    {
      ++not_identifiable_;
      ROS_INFO_THROTTLE(10.0, "identifier: window %.1f-%.1f s not identifiable: %s", job.window_start_s,
                        job.window_end_s, result.note.c_str());
    }
    publisher_.publish(toMessage(result, job.window_start_s, job.window_end_s));
    ++published_;
    std::lock_guard<std::mutex> lock(job_mutex_);
    busy_ = false;
  }
}

void IdentifierRos::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  if (skipped_periods_ > 0)
  {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "solves overran the period");
  }
  else if (out_of_order_ > 0 || non_finite_ > 0)
  {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "bad relative_state samples (see counters)");
  }
  else if (received_ == 0)
  {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "no relative_state yet");
  }
  else
  {
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "identifying");
  }
  status.add("samples received", received_.load());
  status.add("invalid samples (split points)", invalid_.load());
  status.add("non-finite samples (split points)", non_finite_.load());
  status.add("out-of-order samples (rejected)", out_of_order_.load());
  status.add("time jumps back (window cleared)", restarts_.load());
  status.add("solves", solves_.load());
  status.add("skipped periods (solve overran)", skipped_periods_.load());
  status.add("windows not identifiable", not_identifiable_.load());
  status.add("messages published", published_.load());
  status.add("last solve time [s]", last_solve_time_s_.load());
}

}  // namespace acc
