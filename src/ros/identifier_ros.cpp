#include "acc_identification/ros/identifier_ros.h"
#include "acc_identification/io/run_plausibility.h"
#include "acc_identification/ros/ros_time.h"

#include <algorithm>
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


/// The quantity's value when the data determine it, else NaN; its standard error likewise.
void setQuantity(const std::optional<IdentifiableQuantities>& quantities, const char* name, double& value,
                 double& standard_error)
{
  const QuantityEstimate* q = quantities ? quantities->find(name) : nullptr;
  const bool determined = q != nullptr && q->determined;
  value = determined ? q->value : kNaN;
  standard_error = determined ? q->standard_error : kNaN;
}

/// The reasons of the published quantities that the data do not determine, "; "-separated.
std::string undeterminedNote(const std::optional<IdentifiableQuantities>& quantities)
{
  std::string note;
  for (const char* name : {"k1", "k2", "tau_e", "eta", "equilibrium_gap_at_mean_speed", "stability_margin"})
  {
    const QuantityEstimate* q = quantities ? quantities->find(name) : nullptr;
    if (q != nullptr && !q->determined)
      note += (note.empty() ? "" : "; ") + q->reason;
  }
  return note;
}

std::size_t sampleCount(const std::vector<CarFollowingRun>& segments)
{
  std::size_t samples = 0;
  for (const CarFollowingRun& segment : segments)
    samples += segment.size();
  return samples;
}

bool allParametersDetermined(const std::optional<IdentifiableQuantities>& quantities)
{
  for (const char* name : {"k1", "k2", "tau_e", "eta"})
  {
    const QuantityEstimate* q = quantities ? quantities->find(name) : nullptr;
    if (q == nullptr || !q->determined)
      return false;
  }
  return true;
}

void fillWindow(const OnlineUpdate& update, acc_identification::AccParameters& m)
{
  const Identification& result = update.window;
  const auto& q = update.window_quantities;
  m.samples = static_cast<std::uint32_t>(result.samples);
  m.segments = static_cast<std::uint32_t>(result.segments);
  setQuantity(q, "k1", m.k1_per_s2, m.k1_std_error);
  setQuantity(q, "k2", m.k2_per_s, m.k2_std_error);
  setQuantity(q, "tau_e", m.tau_e_s, m.tau_e_std_error);
  setQuantity(q, "eta", m.eta_m, m.eta_std_error);
  setQuantity(q, "equilibrium_gap_at_mean_speed", m.equilibrium_gap_m, m.equilibrium_gap_std_error);
  const QuantityEstimate* gap = q ? q->find("equilibrium_gap_at_mean_speed") : nullptr;
  m.equilibrium_speed_mps = gap != nullptr ? gap->speed_mps : kNaN;
  setQuantity(q, "stability_margin", m.stability_margin, m.stability_margin_std_error);
  m.rmse_speed_mps = result.solved ? result.fit.rmse_speed_mps : kNaN;
  m.rmse_gap_m = result.solved ? result.fit.rmse_gap_m : kNaN;
  // lambda2 and the band need all of k1, k2 and tau_e; the margin above may be known without them.
  const bool all = result.solved && allParametersDetermined(q);
  m.lambda2 = all ? result.stability.lambda2 : kNaN;
  m.string_stable = all && result.stability.string_stable;
  m.amplified_band_upper_rad_s = all ? result.stability.amplified_band_upper_rad_s : kNaN;
  m.peak_gain_db = all ? result.stability.peak_gain_db : kNaN;
  m.peak_frequency_rad_s = all ? result.stability.peak_frequency_rad_s : kNaN;
  m.solve_time_s = result.calibration.solve_time_s;
  m.optimizer_status = result.solved ? result.calibration.status : "NOT_SOLVED";
  m.identifiable = all;
  m.identifiability_note = !result.solved ? result.note : undeterminedNote(q);
}

void fillDrive(const OnlineUpdate& update, double drive_start_s, acc_identification::AccParameters& m)
{
  const auto& q = update.drive_quantities;
  m.drive_start = toRosTime(drive_start_s);
  m.drive_samples = static_cast<std::uint32_t>(update.drive_samples);
  setQuantity(q, "k1", m.drive_k1_per_s2, m.drive_k1_std_error);
  setQuantity(q, "k2", m.drive_k2_per_s, m.drive_k2_std_error);
  setQuantity(q, "tau_e", m.drive_tau_e_s, m.drive_tau_e_std_error);
  setQuantity(q, "eta", m.drive_eta_m, m.drive_eta_std_error);
  setQuantity(q, "stability_margin", m.drive_stability_margin, m.drive_stability_margin_std_error);
  m.drive_rmse_speed_mps = update.drive.solved ? update.drive.fit.rmse_speed_mps : kNaN;
  m.drive_note = !update.drive.solved ? update.drive.note : undeterminedNote(q);
}

void fillVerdict(const OnlineUpdate& update, acc_identification::AccParameters& m)
{
  if (!update.stability)
  {
    m.stability_verdict = toString(StabilityVerdict::Undecided);
    m.stability_p_value = kNaN;
    m.stability_margin_low = kNaN;
    m.stability_margin_high = kNaN;
    m.stability_reason = "the string-stability test of the drive has not run yet";
    return;
  }
  const StabilityTestResult& test = *update.stability;
  m.stability_verdict = toString(test.verdict);
  m.stability_p_value = test.p_value;
  m.stability_margin_low = test.tested ? test.margin_low : kNaN;
  m.stability_margin_high = test.tested ? test.margin_high : kNaN;
  m.stability_samples = static_cast<std::uint32_t>(update.stability_drive_samples);
  m.stability_reason = test.reason;
}

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
  p.param("drive_max_evaluations", s.drive_max_evaluations, s.drive_max_evaluations);
  p.param("stability_period_s", s.stability_period_s, s.stability_period_s);
  p.param("alpha", s.alpha, s.alpha);
  if (s.drive_max_evaluations < 1 || !(s.stability_period_s > 0.0) || !(s.alpha > 0.0 && s.alpha < 1.0))
  {
    error = "parameters ~drive_max_evaluations must be >= 1, ~stability_period_s > 0, ~alpha in (0, 1)";
    return false;
  }
  p.param("min_speed_std_mps", c.min_speed_std_mps, c.min_speed_std_mps);
  if (s.starts < 0 || c.min_speed_std_mps < 0.0)
  {
    error = "parameters ~starts and ~min_speed_std_mps must not be negative";
    return false;
  }
  return true;
}

acc_identification::AccParameters toMessage(const OnlineUpdate& update, double window_start_s, double window_end_s,
                                            double drive_start_s)
{
  acc_identification::AccParameters m;
  m.header.stamp = toRosTime(window_end_s);
  m.window_start = toRosTime(window_start_s);
  m.window_end = toRosTime(window_end_s);
  fillWindow(update, m);
  fillDrive(update, drive_start_s, m);
  fillVerdict(update, m);
  return m;
}

acc_identification::AccParameters toMessage(const Identification& identification, double window_start_s, double window_end_s)
{
  OnlineUpdate update;
  update.window = identification;
  if (identification.solved && !identification.calibration.diverged)
  {
    // Without the segments the equilibrium speeds are unknown: the parameters and the margin only.
    IdentifiableQuantities quantities =
        assessQuantities(identification.calibration.parameters, identification.uncertainty, {});
    auto& list = quantities.quantities;
    list.erase(std::remove_if(list.begin(), list.end(),
                              [](const QuantityEstimate& q) { return q.name.rfind("equilibrium_gap", 0) == 0; }),
               list.end());
    update.window_quantities = std::move(quantities);
  }
  return toMessage(update, window_start_s, window_end_s, 0.0);
}

IdentifierRos::IdentifierRos(ros::NodeHandle node, ros::NodeHandle private_node)
  : window_(settings_.window_s, settings_.max_gap_s, 2), drive_(1.0e9, settings_.max_gap_s, 2)
{
  std::string error;
  if (!loadIdentifierSettings(private_node, settings_, error))
  {
    ROS_FATAL("identifier: %s", error.c_str());
    return;
  }
  const auto min_segment = static_cast<std::size_t>(settings_.min_segment_samples);
  window_ = SlidingWindow(settings_.window_s, settings_.max_gap_s, min_segment);
  // The drive so far: a window that never slides (1e9 s is 31 years).
  drive_ = SlidingWindow(1.0e9, settings_.max_gap_s, min_segment);
  OnlineIdentifierOptions options;
  options.window.criteria = settings_.criteria;
  options.window.multistart.starts = static_cast<std::size_t>(settings_.starts);
  options.drive_max_evaluations_per_start = settings_.drive_max_evaluations;
  options.stability_every_updates = 0;  // on the stability thread instead
  options.stability.alpha = settings_.alpha;
  identifier_.emplace(options);
  publisher_ = node.advertise<acc_identification::AccParameters>("acc_parameters", 10);
  subscriber_ = node.subscribe("relative_state", static_cast<std::uint32_t>(settings_.queue_size),
                               &IdentifierRos::onRelativeState, this);
  worker_ = std::thread(&IdentifierRos::workerLoop, this);
  stability_worker_ = std::thread(&IdentifierRos::stabilityLoop, this);
  period_timer_ = node.createTimer(ros::Duration(settings_.period_s), &IdentifierRos::onPeriod, this);
  updater_.setHardwareID("acc_identifier");
  updater_.add("ACC identification", this, &IdentifierRos::diagnose);
  // Health on the wall clock: update() would wait for the updater's own period on ROS time, which
  // stops with /clock at the end of a replay and leaves the last counts stale.
  diagnostic_timer_ = node.createWallTimer(ros::WallDuration(1.0),
                                           [this](const ros::WallTimerEvent&) { updater_.force_update(); });
  ROS_INFO("identifier: window %.0f s and the drive so far, every %.2f s, %d fresh starts plus a warm start; "
           "string-stability test of the drive at most every %.0f s (alpha %.3g); excitation: speed std >= %.2f m/s",
           settings_.window_s, settings_.period_s, settings_.starts, settings_.stability_period_s, settings_.alpha,
           settings_.criteria.min_speed_std_mps);
  ok_ = true;
}

IdentifierRos::~IdentifierRos()
{
  {
    std::lock_guard<std::mutex> lock(job_mutex_);
    stopping_ = true;
  }
  job_ready_.notify_all();
  {
    std::lock_guard<std::mutex> lock(stability_mutex_);
    stopping_stability_ = true;
  }
  stability_ready_.notify_all();
  if (worker_.joinable())
  {
    worker_.join();
  }
  if (stability_worker_.joinable())
  {
    stability_worker_.join();
  }
}

WindowSample toWindowSample(const acc_identification::RelativeState& message, std::string& why)
{
  WindowSample sample{message.header.stamp.toSec(), message.space_gap_m, message.follower_speed_mps,
                      message.leader_speed_mps, static_cast<bool>(message.valid)};
  why.clear();
  if (sample.valid)
  {
    why = describeImplausibleValue(sample.space_gap_m, sample.follower_speed_mps, sample.leader_speed_mps,
                                   RunPlausibilityBounds{});
    sample.valid = why.empty();
  }
  return sample;
}

void IdentifierRos::onRelativeState(const acc_identification::RelativeState::ConstPtr& message)
{
  ++received_;
  std::string implausible;
  const WindowSample sample = toWindowSample(*message, implausible);
  if (!implausible.empty())
  {
    ++implausible_;
    ROS_WARN_THROTTLE(1.0, "identifier: relative_state at %.3f s: %s; used as a split point (counted)",
                      sample.time_s, implausible.c_str());
  }
  SlidingWindow::AddResult result;
  {
    std::lock_guard<std::mutex> lock(window_mutex_);
    result = window_.add(sample);
    dropped_outliers_ = window_.droppedOutliers();
    // The drive sees the same samples; a time reset that clears the window starts a new drive.
    if (drive_.add(sample) == SlidingWindow::AddResult::kRestarted)
    {
      drive_reset_pending_ = true;
    }
  }
  switch (result)
  {
    case SlidingWindow::AddResult::kAdded: return;
    case SlidingWindow::AddResult::kHeld: return;  // counted once confirmed or dropped
    case SlidingWindow::AddResult::kJumpedAhead: ++jumps_ahead_; break;
    case SlidingWindow::AddResult::kInvalid: ++invalid_; return;  // the pairing already said why
    case SlidingWindow::AddResult::kNonFinite: ++non_finite_; break;
    case SlidingWindow::AddResult::kOutOfOrder: ++out_of_order_; break;
    case SlidingWindow::AddResult::kRestarted: ++restarts_; break;
  }
  ROS_WARN_THROTTLE(1.0, "identifier: relative_state at %.3f s: %s (counted in diagnostics)", sample.time_s,
                    SlidingWindow::describe(result).c_str());
}

void IdentifierRos::onPeriod(const ros::TimerEvent& event)
{
  Job job;
  {
    std::lock_guard<std::mutex> lock(window_mutex_);
    if (window_.empty())
    {
      return;
    }
    job.segments = window_.segments();
    job.drive_segments = drive_.segments();
    job.window_start_s = window_.startTimeS();
    job.window_end_s = window_.endTimeS();
    job.drive_start_s = drive_.startTimeS();
    job.drive_reset = drive_reset_pending_;
    drive_reset_pending_ = false;
  }
  // Test the drive when it has grown since the last test, at most once per stability_period_s,
  // and once more as soon as the data stop (end of a replay, a pause): then the last verdict is
  // the test of every sample the node has seen, as a batch calibrate of them would give.
  if (stability_request_dropped_.exchange(false))
  {
    last_stability_request_samples_ = 0;  // the thread was busy: ask again
  }
  const std::size_t drive_samples = sampleCount(job.drive_segments);
  const double now_s = event.current_real.toSec();
  const bool grown = drive_samples != last_stability_request_samples_;
  const bool stalled = drive_samples == previous_period_drive_samples_;
  const bool due = now_s - last_stability_request_s_ >= settings_.stability_period_s || now_s < last_stability_request_s_;
  previous_period_drive_samples_ = drive_samples;
  if (grown && (due || stalled))
  {
    job.test_stability = true;
    last_stability_request_s_ = now_s;
    last_stability_request_samples_ = drive_samples;
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
    if (job.drive_reset)
    {
      identifier_->resetDrive();
      ++drive_resets_;
      std::lock_guard<std::mutex> lock(stability_mutex_);
      stability_result_.reset();
    }
    OnlineUpdate update;
    try
    {
      update = identifier_->update(job.segments, job.drive_segments);
    }
    catch (const std::exception& error)
    {
      // Data problems come back in the notes; anything else must not end the node.
      ++worker_errors_;
      ROS_ERROR_THROTTLE(10.0, "identifier: solve failed: %s", error.what());
      std::lock_guard<std::mutex> lock(job_mutex_);
      busy_ = false;
      continue;
    }
    if (update.window.solved)
    {
      ++solves_;
      last_solve_time_s_ = update.window_cpu_s;
    }
    last_drive_time_s_ = update.drive_cpu_s;
    if (!update.window.identifiable)
    {
      ++not_identifiable_;
      ROS_INFO_THROTTLE(10.0, "identifier: window %.1f-%.1f s not identifiable: %s", job.window_start_s,
                        job.window_end_s, update.window.note.c_str());
    }
    {
      std::lock_guard<std::mutex> lock(stability_mutex_);
      update.stability = stability_result_;
      update.stability_drive_samples = stability_samples_;
    }
    if (job.test_stability)
    {
      offerStabilityJob(job, update);
    }
    publisher_.publish(toMessage(update, job.window_start_s, job.window_end_s, job.drive_start_s));
    ++published_;
    std::lock_guard<std::mutex> lock(job_mutex_);
    busy_ = false;
  }
}

void IdentifierRos::offerStabilityJob(const Job& job, const OnlineUpdate& update)
{
  if (!update.drive.solved || update.drive.calibration.diverged)
  {
    return;
  }
  std::lock_guard<std::mutex> lock(stability_mutex_);
  if (stability_busy_)
  {
    stability_request_dropped_ = true;  // still on an earlier drive: the timer asks again
    return;
  }
  stability_job_ = StabilityJob{job.drive_segments, update.drive.calibration.parameters, update.drive_samples};
  stability_busy_ = true;
  stability_ready_.notify_one();
}

void IdentifierRos::stabilityLoop()
{
  for (;;)
  {
    StabilityJob job;
    {
      std::unique_lock<std::mutex> lock(stability_mutex_);
      stability_ready_.wait(lock, [this] { return stopping_stability_ || stability_job_.has_value(); });
      if (stopping_stability_)
      {
        return;
      }
      job = std::move(*stability_job_);
      stability_job_.reset();
    }
    std::optional<StabilityTestResult> result;
    const auto start = std::chrono::steady_clock::now();
    try
    {
      result = identifier_->testDrive(job.drive_segments, job.drive_fit);
    }
    catch (const std::exception& error)
    {
      ++worker_errors_;
      ROS_ERROR_THROTTLE(10.0, "identifier: string-stability test failed: %s", error.what());
    }
    last_stability_time_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::lock_guard<std::mutex> lock(stability_mutex_);
    if (result)
    {
      ++stability_tests_;
      stability_result_ = std::move(result);
      stability_samples_ = job.drive_samples;
    }
    stability_busy_ = false;
  }
}

void IdentifierRos::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  // The level says what happened since the last report (one bad sample an hour ago is no reason
  // to stay WARN); the totals stay in the key-values.
  const std::uint64_t errors = worker_errors_, skipped = skipped_periods_;
  const std::uint64_t bad = out_of_order_ + non_finite_ + dropped_outliers_ + implausible_;
  const bool new_errors = errors > reported_errors_, new_skipped = skipped > reported_skipped_,
             new_bad = bad > reported_bad_;
  reported_errors_ = errors;
  reported_skipped_ = skipped;
  reported_bad_ = bad;
  if (new_errors)
  {
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "solves failed since the last report (see the log)");
  }
  else if (new_skipped)
  {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "solves overran the period since the last report");
  }
  else if (new_bad)
  {
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "bad relative_state samples since the last report");
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
  status.add("time jumps ahead (confirmed)", jumps_ahead_.load());
  status.add("time outliers (dropped)", dropped_outliers_.load());
  status.add("implausible samples (split points)", implausible_.load());
  status.add("drive resets", drive_resets_.load());
  status.add("solves", solves_.load());
  status.add("skipped periods (solve overran)", skipped_periods_.load());
  status.add("windows not identifiable", not_identifiable_.load());
  status.add("messages published", published_.load());
  status.add("failed solves", worker_errors_.load());
  status.add("string-stability tests of the drive", stability_tests_.load());
  status.add("last window solve [s]", last_solve_time_s_.load());
  status.add("last drive solve [s]", last_drive_time_s_.load());
  status.add("last string-stability test [s]", last_stability_time_s_.load());
}

}  // namespace acc
