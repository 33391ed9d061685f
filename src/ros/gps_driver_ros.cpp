#include "acc_identification/ros/gps_driver_ros.h"
#include "acc_identification/ros/ros_parameter_source.h"
#include "acc_identification/ros/ros_time.h"

#include <algorithm>
#include <cmath>
#include <thread>
#include <vector>

#include <ros/callback_queue.h>

#include <acc_identification/Sentence.h>
#include <geometry_msgs/TwistStamped.h>
#include <sensor_msgs/NavSatFix.h>
#include <sensor_msgs/TimeReference.h>

#include "acc_identification/gnss/gnss_velocity.h"

namespace acc
{
namespace
{
double seconds(std::chrono::steady_clock::duration d) { return std::chrono::duration<double>(d).count(); }
}  // namespace

acc_identification::GnssFix toMessage(const GnssFix& fix, const std::string& frame_id)
{
  acc_identification::GnssFix m;
  m.header.stamp = toRosTime(fix.gnss_time_s);
  m.header.frame_id = frame_id;
  m.receive_time = toRosTime(fix.receive_time_s);
  m.latitude_deg = fix.latitude_deg;
  m.longitude_deg = fix.longitude_deg;
  m.altitude_m = fix.altitude_m;
  m.speed_over_ground_mps = fix.speed_over_ground_mps;
  m.course_rad = fix.course_rad;
  m.fix_quality = fix.fix_quality;
  m.satellites_used = fix.satellites_used;
  m.hdop = fix.hdop;
  m.latitude_sigma_m = fix.latitude_sigma_m;
  m.longitude_sigma_m = fix.longitude_sigma_m;
  m.altitude_sigma_m = fix.altitude_sigma_m;
  m.valid_fields = fix.valid_fields;
  return m;
}

GnssFix fromMessage(const acc_identification::GnssFix& m)
{
  GnssFix fix;
  fix.gnss_time_s = m.header.stamp.toSec();
  fix.has_date = (m.valid_fields & acc_identification::GnssFix::VALID_DATE) != 0;
  fix.receive_time_s = m.receive_time.toSec();
  fix.latitude_deg = m.latitude_deg;
  fix.longitude_deg = m.longitude_deg;
  fix.altitude_m = m.altitude_m;
  fix.speed_over_ground_mps = m.speed_over_ground_mps;
  fix.course_rad = m.course_rad;
  fix.fix_quality = m.fix_quality;
  fix.satellites_used = m.satellites_used;
  fix.hdop = m.hdop;
  fix.latitude_sigma_m = m.latitude_sigma_m;
  fix.longitude_sigma_m = m.longitude_sigma_m;
  fix.altitude_sigma_m = m.altitude_sigma_m;
  fix.valid_fields = m.valid_fields;
  return fix;
}

std::int8_t navSatStatusOf(std::uint8_t gga_quality)
{
  switch (gga_quality)
  {
    case 1:
    case 3: return sensor_msgs::NavSatStatus::STATUS_FIX;
    case 2: return sensor_msgs::NavSatStatus::STATUS_SBAS_FIX;
    case 4:
    case 5: return sensor_msgs::NavSatStatus::STATUS_GBAS_FIX;
    default: return sensor_msgs::NavSatStatus::STATUS_NO_FIX;  // 0, 6 dead reckoning, 7, 8
  }
}

namespace
{
bool standardStamp(const GnssFix& fix, bool use_gnss_time, ros::Time& stamp)
{
  return toRosTime(use_gnss_time ? fix.gnss_time_s : fix.receive_time_s, stamp);
}

/// GST (or PUBX,00) gave all three sigmas: a partial set (e.g. a GST with an empty altitude sigma)
/// would put NaN into a covariance declared known, so it counts as none.
bool hasAllPositionSigmas(const GnssFix& fix)
{
  return fix.has(GnssFix::kValidPositionSigma) && std::isfinite(fix.latitude_sigma_m) &&
         std::isfinite(fix.longitude_sigma_m) && std::isfinite(fix.altitude_sigma_m);
}

void setDiagonalCovariance(double east_sigma_m, double north_sigma_m, double up_sigma_m, std::uint8_t type,
                           sensor_msgs::NavSatFix& navsat)
{
  navsat.position_covariance.fill(0.0);
  navsat.position_covariance[0] = east_sigma_m * east_sigma_m;
  navsat.position_covariance[4] = north_sigma_m * north_sigma_m;
  navsat.position_covariance[8] = up_sigma_m * up_sigma_m;
  navsat.position_covariance_type = type;
}

/// The covariance rule of toNavSatFix (gps_driver_ros.h, docs/ROS_API.md). position_covariance is
/// in ENU (REP-145), so east takes the longitude sigma and north the latitude sigma.
void setPositionCovariance(const GnssFix& fix, double hdop_uere_m, sensor_msgs::NavSatFix& navsat)
{
  if (hasAllPositionSigmas(fix))
  {
    setDiagonalCovariance(fix.longitude_sigma_m, fix.latitude_sigma_m, fix.altitude_sigma_m,
                          sensor_msgs::NavSatFix::COVARIANCE_TYPE_DIAGONAL_KNOWN, navsat);
  }
  else if (fix.has(GnssFix::kValidHdop))
  {
    // The usual rule of thumb (nmea_navsat_driver's too): the vertical error is about twice the
    // horizontal one.
    const double horizontal_sigma_m = fix.hdop * hdop_uere_m;
    setDiagonalCovariance(horizontal_sigma_m, horizontal_sigma_m, 2.0 * horizontal_sigma_m,
                          sensor_msgs::NavSatFix::COVARIANCE_TYPE_APPROXIMATED, navsat);
  }
  else
  {
    setDiagonalCovariance(0.0, 0.0, 0.0, sensor_msgs::NavSatFix::COVARIANCE_TYPE_UNKNOWN, navsat);
  }
}
}  // namespace

bool hasRosGnssTime(const GnssFix& fix)
{
  ros::Time unused;
  return toRosTime(fix.gnss_time_s, unused);
}

bool toNavSatFix(const GnssFix& fix, const std::string& frame_id, double hdop_uere_m, bool use_gnss_time,
                 sensor_msgs::NavSatFix& navsat)
{
  if (!fix.has(GnssFix::kValidPosition) || !standardStamp(fix, use_gnss_time, navsat.header.stamp))
  {
    return false;
  }
  navsat.header.frame_id = frame_id;
  navsat.status.status = navSatStatusOf(fix.fix_quality);
  navsat.status.service = sensor_msgs::NavSatStatus::SERVICE_GPS;
  navsat.latitude = fix.latitude_deg;
  navsat.longitude = fix.longitude_deg;
  // NavSatFix wants height above the ellipsoid: MSL altitude plus geoid separation when sent.
  navsat.altitude = fix.has(GnssFix::kValidAltitude)
                        ? fix.altitude_m + (std::isnan(fix.geoid_separation_m) ? 0.0 : fix.geoid_separation_m)
                        : std::nan("");
  setPositionCovariance(fix, hdop_uere_m, navsat);
  return true;
}

bool toEnuTwist(const GnssFix& fix, const std::string& frame_id, bool use_gnss_time,
                geometry_msgs::TwistStamped& twist)
{
  EnuVelocity velocity;
  if (!enuVelocity(fix, velocity) || !standardStamp(fix, use_gnss_time, twist.header.stamp))
  {
    return false;
  }
  twist.header.frame_id = frame_id;
  twist.twist.linear.x = velocity.east_mps;
  twist.twist.linear.y = velocity.north_mps;
  return true;
}

TimeReferenceOutcome toTimeReference(const GnssFix& fix, const std::string& frame_id, const std::string& source,
                                     sensor_msgs::TimeReference& reference)
{
  // A time of day counted from 1970 (no date yet) would state a GNSS time decades off.
  if (!fix.has_date)
    return TimeReferenceOutcome::kNoDate;
  ros::Time gnss_time, receive_time;
  if (!toRosTime(fix.gnss_time_s, gnss_time) || !toRosTime(fix.receive_time_s, receive_time))
    return TimeReferenceOutcome::kOutsideRosTime;
  reference.header.stamp = receive_time;
  reference.header.frame_id = frame_id;
  reference.time_ref = gnss_time;
  reference.source = source;
  return TimeReferenceOutcome::kMade;
}

GpsDriverRos::GpsDriverRos(ros::NodeHandle node, ros::NodeHandle private_node)
  : node_(node)
  , decoder_([this](std::string_view line, NmeaParseOutcome) { publishLine(line); },
             [this](const GnssFix& fix) { publishFix(fix); })
  , updater_(node, private_node)
{
  int queue_size = 1000;  // a fast replay (rate 0) bursts; a short queue would drop messages
  const RosParameterSource parameters(private_node);
  ParameterReader reader(parameters);
  reader.readElsewhere("diagnostic_period");  // diagnostic_updater's
  settings_ok_ = readParameters(reader, queue_size);
  if (!settings_ok_)
  {
    ROS_FATAL("gps_driver: %s: the driver exits", reader.error().c_str());
    return;
  }
  unread_parameters_ = reader.unreadNote();
  if (!unread_parameters_.empty())
    ROS_WARN("gps_driver: %s", unread_parameters_.c_str());
  topic_source_ = source_uri_ == "topic";
  // A replayed bag already holds the sentences: republishing them would duplicate the topic.
  if (!topic_source_)
    sentence_publisher_ = node_.advertise<acc_identification::Sentence>("nmea_sentence", queue_size);
  fix_publisher_ = node_.advertise<acc_identification::GnssFix>("fix", queue_size);
  navsat_publisher_ = node_.advertise<sensor_msgs::NavSatFix>("navsat_fix", queue_size);
  vel_publisher_ = node_.advertise<geometry_msgs::TwistStamped>("vel", queue_size);
  time_reference_publisher_ = node_.advertise<sensor_msgs::TimeReference>("time_reference", queue_size);

  if (topic_source_)
  {
    // Subscribed in runTopic(), after waitForSubscribers(): a player waiting for this
    // subscriber then starts only once the fixes have somewhere to go.
    queue_size_in_ = static_cast<std::uint32_t>(std::max(1, queue_size));
  }
  else
  {
    std::string error;
    source_ = makeByteSource(source_uri_, error);
    if (!source_)
      ROS_FATAL("gps_driver: %s: the driver exits", error.c_str());
  }
  updater_.setHardwareID(source_uri_);
  updater_.add("NMEA receiver " + frame_id_, this, &GpsDriverRos::diagnose);
  last_bytes_ = last_fix_ = last_diagnostic_ = SteadyClock::now();
}

bool GpsDriverRos::readParameters(ParameterReader& r, int& queue_size)
{
  double epoch_reorder_wait_s = 0.0;
  const bool ok =
      r.read("source", source_uri_) && r.read("frame_id", frame_id_) && r.read("vel_frame_id", vel_frame_id_) &&
      r.read("time_ref_source", time_ref_source_) && r.readAbove("epoch_idle_s", epoch_idle_s_, 0.0) &&
      r.readAbove("epoch_idle_wall_s", epoch_idle_wall_s_, 0.0) &&
      r.readAtLeast("end_of_file_wait_s", end_of_file_wait_s_, 0.0) &&
      r.readAtLeast("epoch_reorder_wait_s", epoch_reorder_wait_s, 0.0) && r.readAbove("hdop_uere_m", hdop_uere_m_, 0.0) &&
      r.read("use_gnss_time", use_gnss_time_) && r.readAbove("expected_rate_hz", expected_rate_hz_, 0.0) &&
      r.readAbove("fix_timeout_s", fix_timeout_s_, 0.0) &&
      r.readAtLeast("wait_for_subscribers", wait_for_subscribers_, 0) && r.read("wait_for_topics", wait_for_topics_) &&
      r.readAtLeast("wait_for_subscribers_timeout_s", wait_for_subscribers_timeout_s_, 0.0) &&
      r.readAbove("diagnostic_period_s", diagnostic_period_s_, 0.0) && r.readAtLeast("queue_size", queue_size, 1);
  // nmea_navsat_driver's parameter and default: the source is the receiver, named by its frame.
  if (time_ref_source_.empty())
    time_ref_source_ = frame_id_;
  decoder_.setReorderWait(epoch_reorder_wait_s);
  return ok;
}

int GpsDriverRos::run()
{
  if (!settings_ok_)
    return 1;
  if (topic_source_)
    return runTopic();
  if (!source_)
    return 1;
  waitForSubscribers();
  ROS_INFO("gps_driver: reading %s as frame '%s'", source_->description().c_str(), frame_id_.c_str());
  // Room for the largest UDP datagram (65,507 bytes of payload): a read returns one datagram and
  // discards whatever of it does not fit, so a smaller buffer would lose the tail of a large one
  // (socat sends blocks of 8192 bytes) without a trace.
  std::vector<char> buffer(65536);
  while (ros::ok())
  {
    const ReadResult result = source_->read(buffer.data(), buffer.size(), 0.02);
    const SteadyClock::time_point now = SteadyClock::now();
    reportSourceState();
    if (result.status == ReadStatus::kEnd)
    {
      finishReplay();
      return 0;
    }
    if (result.status == ReadStatus::kData)
    {
      receive_time_ = ros::Time::now();
      warnIfNoClock();
      last_bytes_ = now;
      decoder_.feed(buffer.data(), result.size, receive_time_.toSec());
    }
    else if (seconds(now - last_bytes_) >= epoch_idle_s_)
    {
      // Idle on the host's steady clock (not ROS time, which may be paused under /use_sim_time).
      receive_time_ = ros::Time::now();
      decoder_.flushEpoch(receive_time_.toSec());
    }
    if (seconds(now - last_diagnostic_) >= diagnostic_period_s_)
      updater_.force_update();
    ros::spinOnce();
  }
  return 0;
}

void GpsDriverRos::warnIfNoClock()
{
  // A receiver read under /use_sim_time with no /clock (a replay.launch earlier on this master
  // left it true) is stamped 0: every receive stamp (navsat_fix, vel, nmea_sentence, time_reference,
  // fix.receive_time) would be 0 without a word.
  if (!warned_no_clock_ && ros::Time::isSimTime() && receive_time_.isZero())
  {
    warned_no_clock_ = true;
    ROS_WARN("gps_driver: /use_sim_time is true and no /clock is published: receive stamps are 0. For a "
             "receiver or a log read live, set it false (rosparam set /use_sim_time false; a replay.launch "
             "leaves it true), or publish a clock");
  }
}

void GpsDriverRos::reportSourceState()
{
  // Logged once per change between open and not open (the retries' back-off changes the state's
  // text every time; /diagnostics carries it), so that a receiver unplugged or a server gone is in
  // the log beside the data it explains.
  const bool open = source_->isOpen();
  if (open == source_open_)
    return;
  source_open_ = open;
  if (open)
    ROS_INFO("gps_driver: %s open again (reopened %llu time(s))", source_->description().c_str(),
             static_cast<unsigned long long>(source_->reopenCount()));
  else
    ROS_WARN("gps_driver: %s: %s (the driver keeps retrying; no data until it opens)",
             source_->description().c_str(), source_->state().c_str());
}

int GpsDriverRos::runTopic()
{
  waitForSubscribers();
  sentence_subscriber_ = node_.subscribe("nmea_sentence_in", queue_size_in_, &GpsDriverRos::onSentence, this);
  ROS_INFO("gps_driver: decoding sentences from %s as frame '%s'", sentence_subscriber_.getTopic().c_str(),
           frame_id_.c_str());
  while (ros::ok())
  {
    ros::getGlobalCallbackQueue()->callAvailable(ros::WallDuration(0.02));
    flushIdleTopicEpoch();
    if (seconds(SteadyClock::now() - last_diagnostic_) >= diagnostic_period_s_)
      updater_.force_update();
  }
  return 0;
}

void GpsDriverRos::onSentence(const acc_identification::Sentence::ConstPtr& message)
{
  ++sentences_in_;
  // The recorded receive time; a sentence without one gets the (possibly simulated) ROS time.
  receive_time_ = message->header.stamp.isZero() ? ros::Time::now() : message->header.stamp;
  last_bytes_ = SteadyClock::now();
  const std::string& line = message->sentence;
  decoder_.feed(line.data(), line.size(), receive_time_.toSec());
  decoder_.feed("\r\n", 2, receive_time_.toSec());  // one message is one whole line
}

void GpsDriverRos::flushIdleTopicEpoch()
{
  // Both clocks must agree on the pause: at 100x a sentence still in transit is 0.05 s of bag
  // time late after half a millisecond, but not after 50 ms of the host's time.
  const double wall_idle_s = seconds(SteadyClock::now() - last_bytes_);
  const ros::Time now = ros::Time::now();
  if (wall_idle_s >= epoch_idle_wall_s_)
    decoder_.flushAll();
  else if (wall_idle_s >= epoch_idle_s_ && !now.isZero())
    decoder_.flushIfIdle(now.toSec(), epoch_idle_s_);
}

std::string GpsDriverRos::sourceDescription() const
{
  if (source_)
    return source_->description();
  return topic_source_ ? "topic " + sentence_subscriber_.getTopic() : source_uri_;
}

void GpsDriverRos::waitForSubscribers()
{
  if (wait_for_subscribers_ <= 0)
    return;
  // ~wait_for_topics: by default every output topic but time_reference (added later: a listener
  // that does not know it would wait for the timeout), so that a test or a recorder subscribed to
  // all of them misses nothing; a chain needs only fix (and from a topic source the sentences are
  // not republished).
  std::vector<const ros::Publisher*> publishers;
  for (const std::string& topic : wait_for_topics_)
  {
    if (topic == "nmea_sentence" && !topic_source_)
      publishers.push_back(&sentence_publisher_);
    else if (topic == "fix")
      publishers.push_back(&fix_publisher_);
    else if (topic == "navsat_fix")
      publishers.push_back(&navsat_publisher_);
    else if (topic == "vel")
      publishers.push_back(&vel_publisher_);
    else if (topic == "time_reference")
      publishers.push_back(&time_reference_publisher_);
    else if (topic != "nmea_sentence")
      ROS_WARN("gps_driver: ~wait_for_topics: no output topic '%s' (ignored)", topic.c_str());
  }
  const auto ready = [&] {
    for (const ros::Publisher* p : publishers)
      if (static_cast<int>(p->getNumSubscribers()) < wait_for_subscribers_)
        return false;
    return true;
  };
  const SteadyClock::time_point start = SteadyClock::now();
  while (ros::ok() && !ready())
  {
    if (seconds(SteadyClock::now() - start) > wait_for_subscribers_timeout_s_)
    {
      ROS_WARN("gps_driver: fewer than %d subscriber(s) on each topic after %.0f s; starting anyway",
               wait_for_subscribers_, wait_for_subscribers_timeout_s_);
      return;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
}

void GpsDriverRos::finishReplay()
{
  receive_time_ = ros::Time::now();
  decoder_.finish(receive_time_.toSec());
  updater_.force_update();
  ROS_INFO("gps_driver: end of %s: %s", source_->description().c_str(), decoder_.statistics().summary().c_str());
  // Give the transport a moment to deliver the last messages before the process exits, and, in a
  // launch that ends with this node (replay_nmea.launch), the chain time to finish its last samples.
  const SteadyClock::time_point end = SteadyClock::now();
  while (ros::ok() && seconds(SteadyClock::now() - end) < end_of_file_wait_s_)
  {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    ros::spinOnce();
  }
  ros::spinOnce();
}

void GpsDriverRos::publishLine(std::string_view line)
{
  if (topic_source_)
    return;
  acc_identification::Sentence message;
  message.header.stamp = receive_time_;
  message.header.frame_id = frame_id_;
  message.sentence.assign(line.data(), line.size());
  sentence_publisher_.publish(message);
}

void GpsDriverRos::publishFix(const GnssFix& fix)
{
  have_fix_ = true;
  last_fix_ = SteadyClock::now();
  last_fix_quality_ = fix.fix_quality;
  if (hasRosGnssTime(fix))
  {
    fix_publisher_.publish(toMessage(fix, frame_id_));
  }
  else
  {
    // Stamped 0 it would pair as a time reset in relative_state_node: not published, counted.
    ++fixes_outside_ros_time_;
    ROS_WARN_THROTTLE(1.0, "gps_driver: GNSS time %.3f s is outside what ros::Time holds: fix not published "
                      "(counted in diagnostics)", fix.gnss_time_s);
  }

  sensor_msgs::NavSatFix navsat;
  if (toNavSatFix(fix, frame_id_, hdop_uere_m_, use_gnss_time_, navsat))
  {
    navsat_publisher_.publish(navsat);
  }
  geometry_msgs::TwistStamped twist;
  if (toEnuTwist(fix, vel_frame_id_, use_gnss_time_, twist))
  {
    vel_publisher_.publish(twist);
  }
  publishTimeReference(fix);
}

void GpsDriverRos::publishTimeReference(const GnssFix& fix)
{
  sensor_msgs::TimeReference reference;
  switch (toTimeReference(fix, frame_id_, time_ref_source_, reference))
  {
    case TimeReferenceOutcome::kMade: time_reference_publisher_.publish(reference); break;
    case TimeReferenceOutcome::kNoDate: ++time_references_without_date_; break;
    case TimeReferenceOutcome::kOutsideRosTime: ++time_references_outside_ros_time_; break;
  }
}

void GpsDriverRos::diagnose(diagnostic_updater::DiagnosticStatusWrapper& status)
{
  const SteadyClock::time_point now = SteadyClock::now();
  const NmeaStatistics s = decoder_.statistics();
  const double period_s = std::max(1e-3, seconds(now - last_diagnostic_));
  const double rate_hz = static_cast<double>(s.fixes - fixes_at_last_diagnostic_) / period_s;
  const std::uint64_t errors =
      s.bad_checksum + s.malformed + fixes_outside_ros_time_ + time_references_outside_ros_time_;
  const std::uint64_t new_errors = errors - errors_at_last_diagnostic_;
  const std::uint64_t new_fixes = s.fixes - fixes_at_last_diagnostic_;
  // A receiver that sends no date at all (GGA and VTG only): its fixes never pair with a dated one's.
  const bool all_undated = new_fixes > 5 && time_references_without_date_ - undated_at_last_diagnostic_ >= new_fixes;
  const std::uint64_t new_repeated = s.repeated_sentences - repeated_at_last_diagnostic_;
  const double since_fix_s = seconds(now - last_fix_);
  last_diagnostic_ = now;
  fixes_at_last_diagnostic_ = s.fixes;
  errors_at_last_diagnostic_ = errors;
  undated_at_last_diagnostic_ = time_references_without_date_;
  repeated_at_last_diagnostic_ = s.repeated_sentences;

  if (source_ && !source_->isOpen())
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "source closed: " + source_->state());
  else if (!have_fix_ || since_fix_s > fix_timeout_s_)
    status.summary(diagnostic_msgs::DiagnosticStatus::ERROR, "no fix for " + std::to_string(since_fix_s) + " s");
  else if (last_fix_quality_ == 0)
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "receiver reports no position fix");
  else if (rate_hz < 0.8 * expected_rate_hz_)
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "fix rate below expected");
  else if (new_errors > 0)
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN, "bad sentences or times received");
  else if (all_undated)
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                   "fixes without a date (the receiver sends neither RMC nor ZDA): they pair only with another "
                   "undated receiver's");
  else if (new_repeated > 0)
    status.summary(diagnostic_msgs::DiagnosticStatus::WARN,
                   "sentences repeated within an epoch (every line twice? two writers on one link?): the first kept");
  else
    status.summary(diagnostic_msgs::DiagnosticStatus::OK, "receiving fixes");

  status.add("source", sourceDescription());
  status.add("source state", source_ ? source_->state() : std::string("subscribed"));
  status.add("source reopened", source_ ? source_->reopenCount() : 0);
  if (topic_source_)
    status.add("sentences in", sentences_in_);
  status.add("fix rate [Hz]", rate_hz);
  status.add("expected rate [Hz]", expected_rate_hz_);
  status.add("time since last fix [s]", have_fix_ ? since_fix_s : std::nan(""));
  status.add("fix quality", static_cast<int>(last_fix_quality_));
  status.add("lines", s.lines);
  status.add("sentences ok", s.sentences_ok);
  status.add("bad checksum", s.bad_checksum);
  status.add("malformed", s.malformed);
  status.add("malformed without a checksum", s.without_checksum);
  status.add("unsupported", s.unsupported);
  status.add("stray bytes", s.stray_bytes);
  status.add("overlong lines", s.overlong_lines);
  status.add("stray-only lines (dropped)", s.stray_lines);
  status.add("lines cut by a new $", s.cut_lines);
  status.add("epochs without time", s.epochs_without_time);
  status.add("date lag corrections", s.date_lag_corrections);
  status.add("late sentences merged (reorder wait)", s.late_sentences_merged);
  status.add("late sentences after their epoch's fix", s.late_sentences_after_fix);
  status.add("repeated sentences (a second of one type and talker in an epoch)", s.repeated_sentences);
  status.add("fixes", s.fixes);
  status.add("fixes with a GNSS time outside ros::Time (not published on fix)", fixes_outside_ros_time_);
  status.add("fixes without a date (no time_reference)", time_references_without_date_);
  status.add("dated fixes with a time outside ros::Time (no time_reference)", time_references_outside_ros_time_);
}

}  // namespace acc
