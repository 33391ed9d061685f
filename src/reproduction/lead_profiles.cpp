#include "acc_identification/reproduction/lead_profiles.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstddef>
#include <sstream>
#include <stdexcept>

namespace acc
{
namespace
{
constexpr double kStepHoldS = 60.0;         // "holding the velocity for (at least) 60 seconds"
constexpr double kOscillationHoldS = 30.0;  // "holding each velocity for 30 seconds"
// The paper does not say how many oscillations were driven; six cycles (13 holds) give 420-440 s,
// the range of Table I's durations for D-H (370-500 s).
constexpr int kOscillationCycles = 6;
constexpr double kDipLeadInS = 30.0;   // cruise before the first dip (Table I: test I lasted 255 s)
constexpr double kDipHoldS = 5.0;      // "holding each decreased velocity for 5 seconds"
constexpr double kDipRecoveryS = 45.0; // "returning to 50 mph for 45 seconds after each"

double mph(double miles_per_hour) { return miles_per_hour * kMetersPerSecondPerMph; }

std::vector<SpeedHold> stepTest(double low_mph, double high_mph)
{
  std::vector<SpeedHold> holds;
  for (double v = low_mph; v <= high_mph + 1e-9; v += 5.0)
  {
    holds.push_back({mph(v), kStepHoldS});
  }
  for (double v = high_mph - 5.0; v >= low_mph - 1e-9; v -= 5.0)
  {
    holds.push_back({mph(v), kStepHoldS});
  }
  return holds;
}

std::vector<SpeedHold> oscillation(double high_mph, double low_mph)
{
  std::vector<SpeedHold> holds;
  for (int cycle = 0; cycle < kOscillationCycles; ++cycle)
  {
    holds.push_back({mph(high_mph), kOscillationHoldS});
    holds.push_back({mph(low_mph), kOscillationHoldS});
  }
  holds.push_back({mph(high_mph), kOscillationHoldS});
  return holds;
}

std::vector<SpeedHold> dips()
{
  std::vector<SpeedHold> holds{{mph(50.0), kDipLeadInS}};
  for (double dip_mph : {5.0, 10.0, 15.0, 20.0})
  {
    holds.push_back({mph(50.0 - dip_mph), kDipHoldS});
    holds.push_back({mph(50.0), kDipRecoveryS});
  }
  return holds;
}

LeadProfileSpec makeSpec(char id, const std::string& name, const std::string& what,
                         const LeadRamp& ramp, std::vector<SpeedHold> holds)
{
  return {id, name, std::string(1, id) + ", " + name + ": " + what, ramp, std::move(holds)};
}
}  // namespace

const std::string& leadProfileIds()
{
  static const std::string ids = "ABCDEFGHI";
  return ids;
}

bool isLeadProfileId(char id)
{
  const char upper = static_cast<char>(std::toupper(static_cast<unsigned char>(id)));
  return upper != '\0' && leadProfileIds().find(upper) != std::string::npos;
}

LeadProfileSpec leadProfileSpec(char id)
{
  const std::string osc = "alternates every 30 s, 6 cycles (count assumed), ";
  switch (std::toupper(static_cast<unsigned char>(id)))
  {
    case 'A':
      return makeSpec('A', "low-velocity step test", "5 to 30 mph and back in 5 mph steps held 60 s",
                      kCruiseControlRamp, stepTest(5.0, 30.0));
    case 'B':
      return makeSpec('B', "medium-velocity step test", "35 to 55 mph and back in 5 mph steps held 60 s",
                      kCruiseControlRamp, stepTest(35.0, 55.0));
    case 'C':
      return makeSpec('C', "high-velocity step test", "60 to 70 mph and back in 5 mph steps held 60 s",
                      kCruiseControlRamp, stepTest(60.0, 70.0));
    case 'D':
      return makeSpec('D', "low-velocity oscillatory", osc + "30 and 20 mph", kRapidRamp, oscillation(30.0, 20.0));
    case 'E':
      return makeSpec('E', "medium-velocity 5 mph oscillatory", osc + "50 and 45 mph", kRapidRamp,
                      oscillation(50.0, 45.0));
    case 'F':
      return makeSpec('F', "medium-velocity 10 mph oscillatory", osc + "50 and 40 mph", kRapidRamp,
                      oscillation(50.0, 40.0));
    case 'G':
      return makeSpec('G', "high-velocity 5 mph oscillatory", osc + "70 and 65 mph", kRapidRamp,
                      oscillation(70.0, 65.0));
    case 'H':
      return makeSpec('H', "high-velocity 10 mph oscillatory", osc + "70 and 60 mph", kRapidRamp,
                      oscillation(70.0, 60.0));
    case 'I':
      return makeSpec('I', "medium-velocity dip",
                      "50 mph for 30 s (assumed), then dips of 5, 10, 15 and 20 mph held 5 s, each "
                      "followed by 45 s at 50 mph; rebuilt from the text, the recorded test I is not "
                      "published",
                      kRapidRamp, dips());
    default:
      throw std::invalid_argument(std::string("unknown lead profile '") + id +
                                  "': the paper's profiles are A to I");
  }
}

std::vector<double> sampleLeadProfile(const LeadProfileSpec& spec, double time_step_s)
{
  if (!(time_step_s > 0.0) || !std::isfinite(time_step_s))
  {
    throw std::invalid_argument("lead profile time step must be a positive number of seconds");
  }
  if (spec.holds.empty() || !(spec.ramp.acceleration_mps2 > 0.0) || !(spec.ramp.deceleration_mps2 > 0.0))
  {
    throw std::invalid_argument("lead profile needs at least one hold and positive ramp rates");
  }
  // Breakpoints of the piecewise-linear speed: the end of each ramp and the end of each hold.
  std::vector<double> knot_time_s{0.0};
  std::vector<double> knot_speed_mps{spec.holds.front().speed_mps};
  for (std::size_t i = 0; i < spec.holds.size(); ++i)
  {
    const double change = spec.holds[i].speed_mps - knot_speed_mps.back();
    const double rate = change > 0.0 ? spec.ramp.acceleration_mps2 : spec.ramp.deceleration_mps2;
    knot_time_s.push_back(knot_time_s.back() + std::abs(change) / rate);
    knot_speed_mps.push_back(spec.holds[i].speed_mps);
    knot_time_s.push_back(knot_time_s.back() + spec.holds[i].hold_s);
    knot_speed_mps.push_back(spec.holds[i].speed_mps);
  }
  const auto samples = static_cast<std::size_t>(std::floor(knot_time_s.back() / time_step_s + 1e-9)) + 1;
  std::vector<double> speed(samples);
  std::size_t segment = 0;
  for (std::size_t k = 0; k < samples; ++k)
  {
    const double t = static_cast<double>(k) * time_step_s;
    while (segment + 2 < knot_time_s.size() && t > knot_time_s[segment + 1])
    {
      ++segment;
    }
    const double span = knot_time_s[segment + 1] - knot_time_s[segment];
    const double fraction = span > 0.0 ? std::min(1.0, (t - knot_time_s[segment]) / span) : 1.0;
    speed[k] = knot_speed_mps[segment] + fraction * (knot_speed_mps[segment + 1] - knot_speed_mps[segment]);
  }
  return speed;
}

std::vector<double> leadProfile(char id, double time_step_s)
{
  return sampleLeadProfile(leadProfileSpec(id), time_step_s);
}

std::vector<double> leadProfile(char id, double time_step_s, const LeadRamp& ramp)
{
  LeadProfileSpec spec = leadProfileSpec(id);
  spec.ramp = ramp;
  return sampleLeadProfile(spec, time_step_s);
}

std::string describeLeadRamp(const LeadRamp& ramp)
{
  std::ostringstream text;
  text << "speed changes ramp at +" << ramp.acceleration_mps2 << " / -" << ramp.deceleration_mps2
       << " m/s^2 (assumed; the paper gives no accelerations)";
  return text.str();
}

std::string leadProfileDescription(char id)
{
  const LeadProfileSpec spec = leadProfileSpec(id);
  return spec.description + "; " + describeLeadRamp(spec.ramp);
}

}  // namespace acc
