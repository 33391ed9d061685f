#include "acc_identification/ros/identifier_ros.h"
#include "acc_identification/ros/ros_parameter_source.h"
#include "acc_identification/io/run_plausibility.h"
#include "acc_identification/model/number_text.h"
#include "acc_identification/ros/ros_time.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <sstream>

namespace acc
{
namespace
{
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A report's lines on one line, each trimmed, "; "-separated (a note is one line).
std::string joinLines(const std::string& text)
{
  std::istringstream lines(text);
  std::string line, joined;
  while (std::getline(lines, line))
  {
    const std::size_t first = line.find_first_not_of(' ');
    if (first == std::string::npos)
      continue;
    const std::size_t last = line.find_last_not_of(' ');
    joined += (joined.empty() ? "" : "; ") + line.substr(first, last - first + 1);
  }
  return joined;
}

/// "3 out-of-order, 1 time outlier" from (count, what) pairs, leaving out the zeros.
std::string listNonZero(std::initializer_list<std::pair<std::uint64_t, const char*>> items)
{
  std::ostringstream out;
  for (const auto& [count, what] : items)
  {
    if (count > 0)
    {
      out << (out.tellp() > 0 ? ", " : "") << count << " " << what;
    }
  }
  return out.str();
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

/// The reasons of the published quantities that the data do not determine, and of those held at a
/// bound (whose +- std_error is no interval: the reason gives the one-sided one), "; "-separated.
std::string quantitiesNote(const std::optional<IdentifiableQuantities>& quantities)
{
  std::string note;
  for (const char* name : {"k1", "k2", "tau_e", "eta", "equilibrium_gap_at_mean_speed", "stability_margin"})
  {
    const QuantityEstimate* q = quantities ? quantities->find(name) : nullptr;
    if (q != nullptr && (!q->determined || !q->held_by_bound.empty()))
      note += (note.empty() ? "" : "; ") + q->reason;
  }
  return note;
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
  m.std_error_t95 = q ? intervalFactor95(result.uncertainty.blocks) : kNaN;
  m.rmse_speed_mps = result.solved ? result.fit.rmse_speed_mps : kNaN;
  m.rmse_gap_m = result.solved ? result.fit.rmse_gap_m : kNaN;
  // lambda2, the band and the peak need k1, k2 and tau_e (not eta: the linearised dynamics do not
  // depend on it); the margin above may be known even without them.
  const bool dynamics = result.solved && q && allDetermined(*q, {"k1", "k2", "tau_e"});
  const bool all = dynamics && allDetermined(*q, {"eta"});
  m.lambda2 = dynamics ? result.stability.lambda2 : kNaN;
  const std::optional<bool> stable = dynamics ? knownStringStability(result.stability) : std::nullopt;
  m.string_stable = !stable ? acc_identification::AccParameters::STRING_STABILITY_UNKNOWN
                    : *stable ? acc_identification::AccParameters::STRING_STABLE
                              : acc_identification::AccParameters::STRING_UNSTABLE;
  m.amplified_band_upper_rad_s = dynamics ? result.stability.amplified_band_upper_rad_s : kNaN;
  m.peak_gain_db = dynamics ? result.stability.peak_gain_db : kNaN;
  m.peak_frequency_rad_s = dynamics ? result.stability.peak_frequency_rad_s : kNaN;
  m.solve_time_s = result.calibration.solve_time_s;
  m.optimizer_status = result.solved ? result.calibration.status : "NOT_SOLVED";
  m.identifiable = all;
  m.identifiability_note = !result.solved ? result.note : quantitiesNote(q);
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
  m.drive_std_error_t95 = q ? intervalFactor95(update.drive.uncertainty.blocks) : kNaN;
  m.drive_rmse_speed_mps = update.drive.solved ? update.drive.fit.rmse_speed_mps : kNaN;
  m.drive_note = !update.drive.solved ? update.drive.note : quantitiesNote(q);
  if (update.euler_step)
  {
    // One line, as every note.
    m.drive_note += (m.drive_note.empty() ? "" : "; ") + joinLines(describeEulerStepBias(*update.euler_step));
  }
}

/// The sequential verdict's fields (the node's published verdict).
void fillSequentialVerdict(const SequentialLook& look, acc_identification::AccParameters& m)
{
  m.stability_verdict = toString(look.verdict);
  m.stability_p_value = look.p_value;
  m.stability_margin_low = kNaN;
  m.stability_margin_high = kNaN;
  m.stability_samples = static_cast<std::uint32_t>(look.samples);
  m.stability_reason = look.reason;
  m.stability_e_value_unstable = look.e_value_unstable;
  m.stability_e_value_stable = look.e_value_stable;
  m.stability_decided_at_s = look.decided_at_s;
  m.stability_reversed = look.reversed;
  m.stability_blocks_scored = static_cast<std::uint32_t>(look.blocks_scored);
  m.stability_stable_fit_margin = look.stable_fit_margin;
  m.stability_unstable_fit_margin = look.unstable_fit_margin;
}

void fillVerdict(const OnlineUpdate& update, acc_identification::AccParameters& m)
{
  m.stability_e_value_unstable = kNaN;
  m.stability_e_value_stable = kNaN;
  m.stability_decided_at_s = kNaN;
  m.stability_stable_fit_margin = kNaN;
  m.stability_unstable_fit_margin = kNaN;
  if (update.sequential)
  {
    fillSequentialVerdict(*update.sequential, m);
    return;
  }
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

namespace
{
/// The sliding window and the identifiability criteria.
bool readWindowSettings(ParameterReader& r, IdentifierSettings& s)
{
  IdentifiabilityCriteria& c = s.criteria;
  int min_samples = static_cast<int>(c.min_samples);
  const bool ok = r.readAbove("window_s", s.window_s, 0.0) && r.readAbove("period_s", s.period_s, 0.0) &&
                  r.readAbove("stale_after_s", s.stale_after_s, 0.0) &&
                  r.readAbove("max_gap_s", s.max_gap_s, 0.0) && r.readAtLeast("min_segment_samples", s.min_segment_samples, 1) &&
                  r.readAtLeast("queue_size", s.queue_size, 1) && r.readAbove("min_duration_s", c.min_duration_s, 0.0) &&
                  r.readAtLeast("min_samples", min_samples, 1) &&
                  r.readAbove("max_relative_standard_error", c.quantities.max_relative_error_parameter, 0.0) &&
                  r.readAbove("max_forward_jump_s", s.max_forward_jump_s, 0.0) &&
                  // One stamp must not move the window.
                  r.readAtLeast("jump_confirm_samples", s.jump_confirm_samples, 2) && r.readAtLeast("starts", s.starts, 0) &&
                  r.readAtLeast("min_speed_std_mps", c.min_speed_std_mps, 0.0);
  c.min_samples = static_cast<std::size_t>(min_samples);
  return ok;
}

/// The drive so far, its string-stability test and its Euler step check.
bool readDriveSettings(ParameterReader& r, IdentifierSettings& s)
{
  int drive_max_samples = static_cast<int>(s.drive_bound.max_samples);
  const bool ok = r.readAtLeast("drive_max_evaluations", s.drive_max_evaluations, 1) &&
                  r.readAtLeast("drive_max_samples", drive_max_samples, 0) &&  // 0: unbounded
                  r.readAbove("drive_block_s", s.drive_bound.block_s, 0.0) &&
                  r.readAbove("drive_speed_band_mps", s.drive_bound.speed_band_mps, 0.0) &&
                  r.readAbove("stability_period_s", s.stability_period_s, 0.0) && r.read("alpha", s.alpha) &&
                  r.require(s.alpha > 0.0 && s.alpha < 1.0, "parameter ~alpha must be in (0, 1)") &&
                  // A large value: never.
                  r.readAtLeast("euler_check_min_step_s", s.euler_check_min_step_s, 0.0);
  s.drive_bound.max_samples = static_cast<std::size_t>(std::max(0, drive_max_samples));
  return ok;
}

/// The drive fit's model adequacy: the ratios positive, the floors not negative.
bool readAdequacySettings(ParameterReader& r, ModelAdequacyOptions& a)
{
  return r.readAbove("adequacy_max_gap_rmse_over_spread", a.max_gap_rmse_over_spread, 0.0) &&
         r.readAtLeast("adequacy_gap_rmse_floor_m", a.gap_rmse_floor_m, 0.0) &&
         r.readAbove("adequacy_max_speed_rmse_over_spread", a.max_speed_rmse_over_spread, 0.0) &&
         r.readAtLeast("adequacy_speed_rmse_floor_mps", a.speed_rmse_floor_mps, 0.0) &&
         r.readAtLeast("adequacy_bound_fraction", a.bound_fraction, 0.0) &&
         r.require(a.bound_fraction < 0.5, "parameter ~adequacy_bound_fraction must be below 0.5") &&
         r.readAtLeast("adequacy_max_standard_error_at_bound_fraction", a.max_standard_error_at_bound_fraction, 0.0) &&
         r.readAbove("adequacy_max_correlation_over_response_time", a.max_correlation_over_response_time, 0.0);
}

/// The ACC's engagement reports.
bool readEngagementSettings(ParameterReader& r, AccEngagementSettings& e)
{
  return r.read("require_acc_engaged", e.required) && r.readAtLeast("acc_engaged_timeout_s", e.timeout_s, 0.0) &&
         r.require(std::isfinite(e.timeout_s), "parameter ~acc_engaged_timeout_s must be finite (0: a report holds "
                                               "until the next)");
}
}  // namespace

bool loadIdentifierSettings(ParameterReader& reader, IdentifierSettings& s)
{
  return readWindowSettings(reader, s) && readDriveSettings(reader, s) && readAdequacySettings(reader, s.adequacy) &&
         readEngagementSettings(reader, s.engagement);
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
  // Until setModelAdequacy: the caller has the drive's segments, the update does not.
  m.model_adequate = acc_identification::AccParameters::MODEL_ADEQUACY_NOT_ASSESSED;
  m.model_adequacy_reasons = "not assessed: no drive fit judged yet";
  return m;
}

void setModelAdequacy(const ModelAdequacy& adequacy, acc_identification::AccParameters& m)
{
  m.model_adequate = !adequacy.assessed ? acc_identification::AccParameters::MODEL_ADEQUACY_NOT_ASSESSED
                     : adequacy.adequate ? acc_identification::AccParameters::MODEL_ADEQUATE
                                         : acc_identification::AccParameters::MODEL_NOT_ADEQUATE;
  m.model_adequacy_reasons.clear();
  for (const std::string& reason : adequacy.reasons)
    m.model_adequacy_reasons += (m.model_adequacy_reasons.empty() ? "" : "; ") + reason;
}

acc_identification::AccParameters toMessage(const Identification& identification, double window_start_s, double window_end_s)
{
  OnlineUpdate update;
  update.window = identification;
  // The window's own assessment (identifyAcc's, within its bounds), as the online identifier passes it on.
  update.window_quantities = identification.quantities;
  return toMessage(update, window_start_s, window_end_s, 0.0);
}

std::string identifierSettingsNote(const IdentifierSettings& settings)
{
  if (settings.window_s >= settings.criteria.min_duration_s)
    return "";
  return "~window_s (" + printfText("%g", settings.window_s) + " s) is shorter than ~min_duration_s (" +
         printfText("%g", settings.criteria.min_duration_s) +
         " s): no window can hold enough data to fit, so every window estimate will say so; only the drive so far "
         "is fitted. Lengthen the window or lower min_duration_s";
}

IdentifierRos::IdentifierRos(ros::NodeHandle node, ros::NodeHandle private_node, SolveFunction solve)
  : solve_(std::move(solve)), window_(settings_.window_s, settings_.max_gap_s, 2), drive_(settings_.max_gap_s, 2),
    look_schedule_(settings_.stability_period_s)
{
  if (!solve_)
  {
    solve_ = [](OnlineIdentifier& identifier, const std::vector<CarFollowingRun>& window_segments,
                const std::vector<CarFollowingRun>& drive_segments) {
      return identifier.update(window_segments, drive_segments);
    };
  }
  const RosParameterSource parameters(private_node);
  ParameterReader reader(parameters);
  reader.readElsewhere("diagnostic_period");  // diagnostic_updater's
  if (!loadIdentifierSettings(reader, settings_))
  {
    ROS_FATAL("identifier: %s", reader.error().c_str());
    return;
  }
  if (const std::string unread = reader.unreadNote(); !unread.empty())
    ROS_WARN("identifier: %s", unread.c_str());
  if (const std::string note = identifierSettingsNote(settings_); !note.empty())
    ROS_WARN("identifier: %s", note.c_str());
  const auto min_segment = static_cast<std::size_t>(settings_.min_segment_samples);
  const auto confirm = static_cast<std::size_t>(settings_.jump_confirm_samples);
  window_ = SlidingWindow(settings_.window_s, settings_.max_gap_s, min_segment, settings_.max_forward_jump_s, confirm);
  // The drive so far: a window that never slides, bounded by letting go of the least telling
  // blocks. It sees the same samples with the same settings, so it takes the same decisions on
  // jumps in time.
  drive_ = DriveRecord(settings_.max_gap_s, min_segment, settings_.max_forward_jump_s, confirm, settings_.drive_bound);
  OnlineIdentifierOptions options;
  options.window.criteria = settings_.criteria;
  options.window.multistart.starts = static_cast<std::size_t>(settings_.starts);
  options.drive_max_evaluations_per_start = settings_.drive_max_evaluations;
  options.stability_every_updates = 0;  // on the stability thread instead
  options.stability.alpha = settings_.alpha;
  options.euler_check_min_step_s = settings_.euler_check_min_step_s;
  identifier_.emplace(options);
  SequentialVerdictOptions verdict_options;
  verdict_options.alpha = settings_.alpha;
  verdict_options.look_period_s = settings_.stability_period_s;
  sequential_.emplace(verdict_options);
  look_schedule_ = StabilityLookSchedule(settings_.stability_period_s);
  engagement_ = AccEngagement(settings_.engagement);
  // Latched: a subscriber that comes late (a `rostopic echo` after a replay has ended) gets the
  // last estimate and verdict rather than nothing.
  publisher_ = node.advertise<acc_identification::AccParameters>("acc_parameters", 10, /*latch=*/true);
  subscriber_ = node.subscribe("relative_state", static_cast<std::uint32_t>(settings_.queue_size),
                               &IdentifierRos::onRelativeState, this);
  engagement_subscriber_ = node.subscribe("acc_engaged", 10, &IdentifierRos::onAccEngaged, this);
  setting_subscriber_ = node.subscribe("acc_setting", 10, &IdentifierRos::onAccSetting, this);
  worker_ = std::thread(&IdentifierRos::workerLoop, this);
  stability_worker_ = std::thread(&IdentifierRos::stabilityLoop, this);
  period_timer_ = node.createTimer(ros::Duration(settings_.period_s), &IdentifierRos::onPeriod, this);
  clock_timer_ = node.createWallTimer(ros::WallDuration(1.0), [this](const ros::WallTimerEvent&) { checkClockMoves(); });
  updater_.setHardwareID("acc_identifier");
  updater_.add("ACC identification", this, &IdentifierRos::diagnose);
  // Health on the wall clock: update() would wait for the updater's own period on ROS time, which
  // stops with /clock at the end of a replay and leaves the last counts stale.
  diagnostic_timer_ = node.createWallTimer(ros::WallDuration(1.0),
                                           [this](const ros::WallTimerEvent&) { updater_.force_update(); });
  ROS_INFO("identifier: window %.0f s and the drive so far (at most %zu samples, let go of in %.0f s blocks), "
           "every %.2f s, %d fresh starts plus a warm start; sequential string-stability verdict of the drive, a look every %.0f s "
           "of data (alpha %.3g, anytime-valid); excitation: speed std >= %.2f m/s; a jump in time needs %d consistent samples",
           settings_.window_s, settings_.drive_bound.max_samples, settings_.drive_bound.block_s, settings_.period_s,
           settings_.starts, settings_.stability_period_s, settings_.alpha, settings_.criteria.min_speed_std_mps,
           settings_.jump_confirm_samples);
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
  last_sample_wall_s_ = ros::WallTime::now().toSec();
  std::string implausible;
  WindowSample sample = toWindowSample(*message, implausible);
  // Each sample not used is counted once, for its first reason: the ACC's state (counted by
  // accDrove), an implausible value, the pairing's mark; the window then counts only what is
  // wrong with the others' time (late, a jump, not finite).
  const bool acc_drove = accDrove(sample.time_s);
  if (acc_drove && !implausible.empty())
  {
    ++implausible_;
    ROS_WARN_THROTTLE(1.0, "identifier: relative_state at %.3f s: %s; used as a split point (counted)",
                      sample.time_s, implausible.c_str());
  }
  else if (acc_drove && !message->valid)
  {
    ++invalid_;  // the pairing already said why
  }
  sample.valid = sample.valid && acc_drove;
  sample.counted = !sample.valid;
  SlidingWindow::AddResult result;
  std::size_t dropped_before = 0, dropped_after = 0;
  {
    std::lock_guard<std::mutex> lock(window_mutex_);
    dropped_before = window_.counts().time_outliers;
    // Out-of-order samples, time outliers, confirmed jumps: counted by the window itself.
    result = window_.add(sample);
    dropped_after = window_.counts().time_outliers;
    // The drive sees the same samples; a time reset that clears the window starts a new drive.
    if (drive_.add(sample) == SlidingWindow::AddResult::kRestarted)
    {
      drive_reset_pending_ = true;
    }
  }
  if (dropped_after > dropped_before)
  {
    ROS_WARN_THROTTLE(1.0, "identifier: %zu relative_state sample(s) that jumped in time dropped: the time base "
                      "went on without them (counted in diagnostics)", dropped_after - dropped_before);
  }
  switch (result)
  {
    case SlidingWindow::AddResult::kAdded: return;
    case SlidingWindow::AddResult::kInvalid: return;  // counted above
    case SlidingWindow::AddResult::kHeld: break;  // used once confirmed; counted by the window if dropped
    case SlidingWindow::AddResult::kNonFinite:
      if (std::isfinite(sample.time_s))
      {
        ++non_finite_values_;  // a non-finite time is counted by the window
      }
      break;
    case SlidingWindow::AddResult::kJumpedAhead:
    case SlidingWindow::AddResult::kOutOfOrder:
    case SlidingWindow::AddResult::kRestarted: break;
  }
  ROS_WARN_THROTTLE(1.0, "identifier: relative_state at %.3f s: %s (counted in diagnostics)", sample.time_s,
                    SlidingWindow::describe(result).c_str());
}

void IdentifierRos::onAccEngaged(const std_msgs::Bool::ConstPtr& message)
{
  std::string previous;
  {
    std::lock_guard<std::mutex> lock(engagement_mutex_);
    previous = engagement_.latestReport();
    engagement_.report(ros::Time::now().toSec(), message->data);
  }
  if (previous != (message->data ? "engaged" : "off"))
  {
    ROS_INFO("identifier: acc_engaged says the ACC is %s: relative_state samples %s", message->data ? "engaged" : "off",
             message->data ? "are used" : "are split points, not used, until it is engaged again (counted)");
  }
}

void IdentifierRos::onAccSetting(const std_msgs::String::ConstPtr& message)
{
  std::string previous;
  bool restarted = false;
  {
    std::lock_guard<std::mutex> lock(window_mutex_);
    if (message->data == acc_setting_)
    {
      return;  // a source that repeats itself
    }
    previous = acc_setting_;
    acc_setting_ = message->data;
    // The samples so far were driven at another setting (or one not reported): they are not this
    // setting's, so neither the window nor the drive may mix them with what comes.
    restarted = !window_.empty() || drive_.size() > 0;
    if (restarted)
    {
      window_.clear();
      drive_.restart();
      drive_reset_pending_ = true;
    }
  }
  ++setting_changes_;
  const std::string was = previous.empty() ? "not reported" : "'" + previous + "'";
  ROS_INFO("identifier: acc_setting says the ACC's setting is '%s' (was %s)%s", message->data.c_str(), was.c_str(),
           restarted ? ": a new drive starts, the window is cleared" : "");
}

bool IdentifierRos::accDrove(double sample_time_s)
{
  AccEngagement::Judgement judgement;
  std::string why;
  {
    std::lock_guard<std::mutex> lock(engagement_mutex_);
    judgement = engagement_.judge(ros::Time::now().toSec());
    why = engagement_.describe(judgement.use);
  }
  if (judgement.use == AccEngagement::Use::kStateUnknown && judgement.starts_stretch)
  {
    ROS_WARN("identifier: relative_state at %.3f s: %s (~require_acc_engaged): samples are split points, not used, "
             "until a report says engaged (counted)", sample_time_s, why.c_str());
  }
  return judgement.use == AccEngagement::Use::kUsed;
}

void IdentifierRos::onPeriod(const ros::TimerEvent& event)
{
  runPeriod(event.current_real.toSec(), false);
}

void IdentifierRos::checkClockMoves()
{
  // Under /use_sim_time the period timer runs on /clock, which stops with the end of a replay: the
  // period that would see the data stop never came, so the drive's last seconds were never looked
  // at (nor a look still running published). Live, ROS time always moves and this does nothing.
  if (!ros::Time::isSimTime())
    return;
  const double now_s = ros::Time::now().toSec();
  if (now_s != last_seen_ros_s_)
    clock_moved_wall_s_ = ros::WallTime::now().toSec();  // the diagnostics tell a clock that never moves
  if (now_s > 0.0 && now_s == last_seen_ros_s_)
    runPeriod(now_s, true);
  last_seen_ros_s_ = now_s;
}

void IdentifierRos::runPeriod(double now_s, bool catch_up)
{
  Job job;
  bool unusable_window = false;
  {
    std::lock_guard<std::mutex> lock(window_mutex_);
    if (window_.empty())
    {
      return;
    }
    std::size_t short_pieces = 0;
    job.segments = window_.segments(&short_pieces);
    job.short_pieces_note = window_.describeShortPieces(short_pieces);
    // One short piece is a drive that has just begun; several and none long enough is data that
    // arrive and cannot be used (a 1 Hz receiver against max_gap_s 0.5 s): the diagnostics warn.
    unusable_window = job.segments.empty() && short_pieces >= 2;
    if (unusable_window)
      unusable_window_note_ = job.short_pieces_note;
    job.drive_segments = drive_.segments();
    job.window_start_s = window_.startTimeS();
    job.window_end_s = window_.endTimeS();
    job.drive_start_s = drive_.startTimeS();
    job.drive_samples_taken = drive_.samplesTaken();
    job.drive_samples_let_go = drive_.samplesLetGoThisDrive();
    job.drive_reset = drive_reset_pending_;
    job.acc_setting = acc_setting_;
    drive_reset_pending_ = false;
  }
  // Test the drive when it has grown since the last test, at most once per stability_period_s,
  // and once more as soon as the data stop (StabilityLookSchedule).
  if (stability_request_dropped_.exchange(false))
    look_schedule_.lookLost();  // the thread was busy: ask again
  // A catch-up period comes when /clock has stood still for a second: the data have stopped.
  const StabilityLookSchedule::Decision decision =
      look_schedule_.decide(now_s, job.drive_samples_taken, catch_up, stability_tests_ == looks_published_);
  if (!decision.run_period)
    return;
  if (unusable_window)
    ++unusable_windows_;  // counted per period that runs, not per catch-up second after a replay
  job.test_stability = decision.look;
  job.data_stopped = decision.data_stopped;
  {
    std::lock_guard<std::mutex> lock(job_mutex_);
    if (busy_)
    {
      if (job.test_stability)
        look_schedule_.lookLost();  // the look asked for goes with the period: ask again
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
    // Whatever the solve throws (std::exception or not), this thread and the node go on: the
    // period publishes nothing, the failure is counted and the diagnostics say what it was.
    std::string failure;
    if (!runCatchingEverything([&] { runJob(job); }, failure))
    {
      noteFailure("solve", failure);
    }
    std::lock_guard<std::mutex> lock(job_mutex_);
    busy_ = false;
  }
}

void IdentifierRos::runJob(Job& job)
{
  if (job.drive_reset)
  {
    identifier_->resetDrive();
    ++drive_resets_;
    std::lock_guard<std::mutex> lock(stability_mutex_);
    stability_result_.reset();
    euler_step_result_.reset();
    ++drive_generation_;
  }
  OnlineUpdate update = solve_(*identifier_, job.segments, job.drive_segments);
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
  std::uint64_t looks_in_message = 0;
  {
    std::lock_guard<std::mutex> lock(stability_mutex_);
    update.sequential = stability_result_;
    update.euler_step = euler_step_result_;
    looks_in_message = stability_tests_;
  }
  if (job.test_stability)
  {
    offerStabilityJob(job, update);
  }
  acc_identification::AccParameters message = toMessage(update, job.window_start_s, job.window_end_s, job.drive_start_s);
  if (!job.short_pieces_note.empty())
  {
    // Samples the window holds but cannot simulate: said, never dropped silently.
    message.identifiability_note += (message.identifiability_note.empty() ? "" : "; ") + job.short_pieces_note;
    ROS_WARN_THROTTLE(10.0, "identifier: %s", job.short_pieces_note.c_str());
  }
  message.drive_samples_let_go = static_cast<std::uint32_t>(job.drive_samples_let_go);
  message.acc_setting = job.acc_setting;
  // The drive fit judged on the drive so far: one simulation and one autocorrelation scan (a few
  // milliseconds on a 3-hour drive), so every message says whether its verdict rests on a model
  // that fits.
  if (update.drive.solved && !update.drive.calibration.diverged)
    setModelAdequacy(assessModelAdequacy(update.drive.calibration.parameters, job.drive_segments, settings_.adequacy,
                                         update.drive.uncertainty.standard_error),
                     message);
  publisher_.publish(message);
  ++published_;
  looks_published_ = looks_in_message;
}

void IdentifierRos::noteFailure(const char* what, const std::string& failure)
{
  ++failures_;
  ROS_ERROR_THROTTLE(10.0, "identifier: %s failed: %s (counted; the node goes on)", what, failure.c_str());
  std::lock_guard<std::mutex> lock(failure_mutex_);
  last_failure_ = std::string(what) + ": " + failure;
}

void IdentifierRos::offerStabilityJob(const Job& job, const OnlineUpdate& update)
{
  std::lock_guard<std::mutex> lock(stability_mutex_);
  if (stability_busy_)
  {
    stability_request_dropped_ = true;  // still on an earlier look: the timer asks again
    return;
  }
  stability_job_ = StabilityJob{job.drive_segments, job.data_stopped, drive_generation_, update.drive};
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
    if (job.drive_generation != sequential_generation_)
    {
      sequential_->reset();  // a new drive: its verdict starts from nothing
      sequential_generation_ = job.drive_generation;
    }
    std::vector<SequentialLook> looks;
    const auto start = std::chrono::steady_clock::now();
    std::string failure;
    if (!runCatchingEverything([&] { looks = sequential_->lookLive(job.drive_segments, job.data_stopped); }, failure))
    {
      looks.clear();
      noteFailure("sequential string-stability verdict", failure);
    }
    // The drive fit's Euler step check, where the data's step is coarse enough for it to matter.
    std::optional<EulerStepBias> euler_step;
    if (!runCatchingEverything([&] { euler_step = identifier_->checkEulerStep(job.drive_segments, job.drive); },
                               failure))
      noteFailure("Euler step check", failure);
    last_stability_time_s_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::lock_guard<std::mutex> lock(stability_mutex_);
    if (job.drive_generation == drive_generation_)
    {
      if (!looks.empty())
      {
        stability_tests_ += looks.size();
        stability_result_ = looks.back();
      }
      if (euler_step)
      {
        ++euler_step_checks_;
        euler_step_result_ = std::move(euler_step);
      }
    }
    stability_busy_ = false;
  }
}

IdentifierCounters IdentifierRos::counters()
{
  IdentifierCounters c;
  c.received = received_;
  c.invalid = invalid_;
  c.implausible = implausible_;
  {
    std::lock_guard<std::mutex> lock(engagement_mutex_);
    c.acc_off = engagement_.samplesOff();
    c.acc_state_unknown = engagement_.samplesUnknown();
    c.engagement_reports = engagement_.reports();
    c.disengagements = engagement_.disengagements();
  }
  c.setting_changes = setting_changes_;
  c.drive_resets = drive_resets_;
  c.solves = solves_;
  c.skipped_periods = skipped_periods_;
  c.not_identifiable = not_identifiable_;
  c.unusable_windows = unusable_windows_;
  c.published = published_;
  c.failures = failures_;
  c.stability_tests = stability_tests_;
  std::lock_guard<std::mutex> lock(window_mutex_);
  const SlidingWindow::Counts& w = window_.counts();
  c.non_finite = non_finite_values_ + w.non_finite_times;
  c.out_of_order = w.out_of_order;
  c.time_outliers = w.time_outliers;
  c.restarts = w.restarts;
  c.jumps_ahead = w.jumps_ahead;
  c.held = window_.heldSamples();
  c.drive_samples_let_go = drive_.samplesLetGo();
  c.drive_blocks_let_go = drive_.blocksLetGo();
  return c;
}

IdentifierHealth identifierHealth(const IdentifierCounters& now, const IdentifierCounters& previous,
                                  const std::string& last_failure, double silent_s, double stale_after_s,
                                  const std::string& unusable_window_note, double ros_time_still_s)
{
  IdentifierHealth health;
  const auto since = [](std::uint64_t total, std::uint64_t before) { return total > before ? total - before : 0; };
  const std::uint64_t failures = since(now.failures, previous.failures);
  const std::uint64_t skipped = since(now.skipped_periods, previous.skipped_periods);
  const std::string samples = listNonZero({
      {since(now.out_of_order, previous.out_of_order), "out-of-order (rejected)"},
      {since(now.time_outliers, previous.time_outliers), "time outliers (dropped)"},
      {since(now.non_finite, previous.non_finite), "non-finite"},
      {since(now.implausible, previous.implausible), "implausible (split points)"},
      {since(now.restarts, previous.restarts), "time jumps back (window cleared)"},
      {since(now.jumps_ahead, previous.jumps_ahead), "time jumps ahead"},
      {since(now.acc_state_unknown, previous.acc_state_unknown), "with the ACC's state unknown (not used)"},
  });
  const std::uint64_t acc_off = since(now.acc_off, previous.acc_off);
  const std::uint64_t unusable = since(now.unusable_windows, previous.unusable_windows);
  if (failures > 0)
  {
    health.level = diagnostic_msgs::DiagnosticStatus::ERROR;
    health.message = "since last report: " + std::to_string(failures) + " failed solve(s) or test(s); last: " +
                     last_failure;
  }
  else if (now.received > 0 && silent_s <= stale_after_s && ros_time_still_s > stale_after_s)
  {
    health.level = diagnostic_msgs::DiagnosticStatus::ERROR;
    health.message = "relative_state arrives but ROS time has stood still for " +
                     printfText("%.0f", ros_time_still_s) +
                     " s (wall clock): /use_sim_time is true and nothing publishes /clock? No period runs: nothing "
                     "is estimated or published";
  }
  else if (skipped > 0)
  {
    health.level = diagnostic_msgs::DiagnosticStatus::WARN;
    health.message = "since last report: " + std::to_string(skipped) + " period(s) skipped (the solve overran)";
  }
  else if (!samples.empty())
  {
    health.level = diagnostic_msgs::DiagnosticStatus::WARN;
    health.message = "since last report: relative_state samples " + samples;
  }
  else if (unusable > 0)
  {
    health.level = diagnostic_msgs::DiagnosticStatus::WARN;
    health.message = "since last report: " + std::to_string(unusable) +
                     " period(s) whose window had no piece long enough to simulate: " + unusable_window_note;
  }
  else if (now.received == 0)
  {
    health.level = diagnostic_msgs::DiagnosticStatus::WARN;
    health.message = "no relative_state yet";
  }
  else if (silent_s > stale_after_s)
  {
    health.level = diagnostic_msgs::DiagnosticStatus::WARN;
    health.message = "no relative_state for " + printfText("%.0f", silent_s) +
                     " s (wall clock): the estimate and the verdict are those of the data up to the last sample";
  }
  else
  {
    health.level = diagnostic_msgs::DiagnosticStatus::OK;
    health.message = acc_off > 0 ? "ACC off (acc_engaged): " + std::to_string(acc_off) +
                                       " relative_state sample(s) since last report not used"
                                 : "identifying";
  }
  return health;
}

bool runCatchingEverything(const std::function<void()>& work, std::string& failure)
{
  try
  {
    work();
    return true;
  }
  catch (const std::exception& error)
  {
    failure = error.what();
  }
  catch (...)
  {
    failure = "an exception that is not a std::exception";
  }
  return false;
}

void IdentifierRos::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  // The level says what happened since the last report (one bad sample an hour ago is no reason
  // to stay WARN, as relative_state_node does); the totals stay in the key-values.
  const IdentifierCounters c = counters();
  std::string last_failure;
  {
    std::lock_guard<std::mutex> lock(failure_mutex_);
    last_failure = last_failure_;
  }
  std::string unusable_window_note;
  {
    std::lock_guard<std::mutex> lock(window_mutex_);
    unusable_window_note = unusable_window_note_;
  }
  const double last_sample_wall_s = last_sample_wall_s_;
  const double silent_s = last_sample_wall_s > 0.0 ? ros::WallTime::now().toSec() - last_sample_wall_s : 0.0;
  const double clock_moved_wall_s = clock_moved_wall_s_;
  const double ros_time_still_s = ros::Time::isSimTime() && clock_moved_wall_s > 0.0
                                      ? ros::WallTime::now().toSec() - clock_moved_wall_s
                                      : 0.0;
  const IdentifierHealth health = identifierHealth(c, reported_, last_failure, silent_s, settings_.stale_after_s,
                                                   unusable_window_note, ros_time_still_s);
  reported_ = c;
  status.summary(health.level, health.message);
  status.add("samples received", c.received);
  status.add("invalid samples (split points)", c.invalid);
  status.add("non-finite samples", c.non_finite);
  status.add("implausible samples (split points)", c.implausible);
  status.add("samples with the ACC off (split points, not used)", c.acc_off);
  status.add("samples with the ACC's state unknown (split points, not used)", c.acc_state_unknown);
  status.add("acc_engaged reports", c.engagement_reports);
  status.add("ACC disengagements reported", c.disengagements);
  {
    std::lock_guard<std::mutex> lock(engagement_mutex_);
    status.add("ACC engagement (latest report)", engagement_.latestReport());
  }
  status.add("out-of-order samples (rejected)", c.out_of_order);
  status.add("time outliers (dropped)", c.time_outliers);
  status.add("time jumps back (window cleared)", c.restarts);
  status.add("time jumps ahead (confirmed)", c.jumps_ahead);
  status.add("samples held (jump awaiting confirmation)", c.held);
  status.add("drive resets", c.drive_resets);
  status.add("ACC setting changes reported", c.setting_changes);
  {
    std::lock_guard<std::mutex> lock(window_mutex_);
    status.add("ACC setting (latest report)", acc_setting_.empty() ? std::string("none reported") : acc_setting_);
  }
  status.add("drive samples let go (bound)", c.drive_samples_let_go);
  status.add("drive blocks let go (bound)", c.drive_blocks_let_go);
  status.add("solves", c.solves);
  status.add("skipped periods (solve overran)", c.skipped_periods);
  status.add("windows not identifiable", c.not_identifiable);
  status.add("windows with no piece long enough to simulate", c.unusable_windows);
  status.add("messages published", c.published);
  status.add("failed solves or tests", c.failures);
  status.add("last failure", last_failure.empty() ? std::string("none") : last_failure);
  status.add("looks of the sequential string-stability verdict", c.stability_tests);
  {
    std::lock_guard<std::mutex> lock(stability_mutex_);
    status.add("Euler step checks of the drive fit (median step >= ~euler_check_min_step_s)", euler_step_checks_);
  }
  status.add("last window solve [s]", last_solve_time_s_.load());
  status.add("last drive solve [s]", last_drive_time_s_.load());
  status.add("last sequential-verdict update [s]", last_stability_time_s_.load());
}

}  // namespace acc
