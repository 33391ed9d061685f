// The GNSS errors put into a synthetic drive, measured back from its NMEA logs as the relative
// state would see them: gap error about 0.43 m (Section V-A), speed noise 0.06 m/s between receivers.
#include <gtest/gtest.h>

#include <cmath>
#include <numeric>
#include <string>
#include <vector>

#include "acc_identification/conversion/openacc_to_nmea.h"
#include "acc_identification/gnss/nmea_log.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/relative_state/vehicle_geometry.h"
#include "acc_identification/synthesis/gnss_error_model.h"
#include "acc_identification/synthesis/synthesis.h"

namespace acc
{
namespace
{
struct Moments
{
  double mean = 0.0;
  double sigma = 0.0;
  double mean_abs = 0.0;
};

Moments moments(const std::vector<double>& x)
{
  Moments m;
  for (double v : x)
  {
    m.mean += v;
    m.mean_abs += std::abs(v);
  }
  m.mean /= static_cast<double>(x.size());
  m.mean_abs /= static_cast<double>(x.size());
  for (double v : x)
    m.sigma += (v - m.mean) * (v - m.mean);
  m.sigma = std::sqrt(m.sigma / static_cast<double>(x.size() - 1));
  return m;
}

std::vector<GnssFix> roundTrip(const std::vector<GnssFix>& fixes, const std::string& name)
{
  const std::string path = testing::TempDir() + "synthesis_noise_" + name + ".nmea";
  std::string error;
  EXPECT_TRUE(writeNmeaLog(path, fixes, "GN", error)) << error;
  NmeaLogResult log = readNmeaLog(path);
  EXPECT_EQ(log.statistics.rejected(), 0u);
  return log.fixes;
}

// Profile A (about 12 minutes) with 24 seeds: about 850 correlation times of 20 s in all, so
// the measured sigma is within about 2.5 % (1-sigma) of the true one. (One 12-minute drive alone
// can be 15 % off: slowly wandering errors average out slowly.)
TEST(SynthesisNoise, GapAndSpeedErrorsAreThoseAsked)
{
  std::vector<double> gap_error, leader_speed_error, speed_difference_error;
  for (std::uint64_t seed = 1; seed <= 24; ++seed)
  {
    SynthesisOptions options;
    options.profile = 'A';
    options.parameters = paperMaximumSetting();
    options.seed = seed;
    const SynthesizedDrive drive = synthesizeDrive(options);
    const std::vector<GnssFix> leader = roundTrip(drive.leader_fixes, "leader" + std::to_string(seed));
    const std::vector<GnssFix> follower = roundTrip(drive.follower_fixes, "follower" + std::to_string(seed));
    ASSERT_EQ(leader.size(), drive.truth.run.size());
    ASSERT_EQ(follower.size(), drive.truth.run.size());
    for (std::size_t k = 0; k < leader.size(); ++k)
    {
      gap_error.push_back(straightLineGap(leader[k], follower[k], options.geometry) - drive.straight_line_gap_m[k]);
      const double leader_error = leader[k].speed_over_ground_mps - drive.truth.run.leader_speed_mps[k];
      const double follower_error = follower[k].speed_over_ground_mps - drive.truth.run.follower_speed_mps[k];
      leader_speed_error.push_back(leader_error);
      speed_difference_error.push_back(leader_error - follower_error);
    }
  }
  const Moments gap = moments(gap_error);
  RecordProperty("gap_error_sigma_m", std::to_string(gap.sigma));
  std::cout << "gap error: mean " << gap.mean << " m, sigma " << gap.sigma << " m, mean |e| " << gap.mean_abs << " m\n";
  // Two receivers of 0.30 m per axis: sigma sqrt(2) 0.30 = 0.42 m.
  EXPECT_NEAR(gap.sigma, 0.424, 0.05);
  EXPECT_NEAR(gap.mean, 0.0, 0.06);

  const Moments speed = moments(leader_speed_error);
  const Moments difference = moments(speed_difference_error);
  std::cout << "speed error: sigma " << speed.sigma << " m/s; two receivers' difference mean |e| "
            << difference.mean_abs << " m/s\n";
  EXPECT_NEAR(speed.sigma, 0.053, 0.003);
  EXPECT_NEAR(speed.mean, 0.0, 0.002);
  EXPECT_NEAR(difference.mean_abs, 0.06, 0.003);  // the paper's 0.06 m/s mean absolute difference
}

TEST(SynthesisNoise, PositionErrorWandersSlowly)
{
  // Gauss-Markov with T = 20 s: the lag-1 (0.1 s) correlation is exp(-0.1 / 20) = 0.995 and
  // the lag-200 (20 s) one exp(-1) = 0.37; white speed noise has none.
  GnssErrorSettings settings;
  GnssErrorModel model(settings, 99);
  std::vector<double> east, speed;
  for (int k = 0; k < 200000; ++k)
  {
    const GnssEpochError e = model.next(0.1);
    east.push_back(e.east_m);
    speed.push_back(e.along_track_speed_mps);
  }
  auto correlation = [](const std::vector<double>& x, std::size_t lag) {
    double sum = 0.0, norm = 0.0;
    for (std::size_t k = 0; k + lag < x.size(); ++k)
      sum += x[k] * x[k + lag];
    for (double v : x)
      norm += v * v;
    return sum / norm;
  };
  EXPECT_NEAR(correlation(east, 1), std::exp(-0.1 / 20.0), 0.002);
  EXPECT_NEAR(correlation(east, 200), std::exp(-1.0), 0.1);
  EXPECT_NEAR(correlation(speed, 1), 0.0, 0.01);
  EXPECT_NEAR(moments(east).sigma, 0.30, 0.03);
}

}  // namespace
}  // namespace acc
