#pragma once

#include <string>
#include <vector>

namespace acc
{
/// How fast the lead vehicle changes speed between the held speeds of a profile. The paper gives
/// held speeds and hold times but no accelerations; these are the documented assumptions.
struct LeadRamp
{
  double acceleration_mps2 = 0.0;  ///< magnitude when speeding up
  double deceleration_mps2 = 0.0;  ///< magnitude when slowing down
};

/// Step tests A-C (cruise control moving its set speed by 5 mph): a gentle 0.5 m/s^2 both ways.
constexpr LeadRamp kCruiseControlRamp{0.5, 0.5};
/// The "dynamic" profiles D-I, whose changes the paper calls quick or rapid: firm braking at
/// 2.0 m/s^2 (about 0.2 g, an ordinary brisk stop, far from an emergency stop at 6-9 m/s^2) and
/// 1.5 m/s^2 acceleration (brisk for a passenger car at 20-50 mph).
constexpr LeadRamp kRapidRamp{1.5, 2.0};

/// One speed held for a while; the lead ramps to it from the previous one at the profile's ramp.
struct SpeedHold
{
  double speed_mps = 0.0;
  double hold_s = 0.0;
};

/// A lead-vehicle speed profile of Section III of Gunter et al., rebuilt from its description.
struct LeadProfileSpec
{
  char id = '?';
  std::string name;         ///< the paper's label, e.g. "medium-velocity dip"
  std::string description;  ///< the held speeds built, with their assumptions (ramp: see below)
  LeadRamp ramp;
  std::vector<SpeedHold> holds;  ///< starts at holds[0].speed_mps at t = 0
};

constexpr double kMetersPerSecondPerMph = 0.44704;

/// The profile ids the paper uses: "ABCDEFGHI".
const std::string& leadProfileIds();
bool isLeadProfileId(char id);

/// The specification of profile id (A..I, case-insensitive); throws std::invalid_argument for
/// any other id. Built from the paper's text: the recorded profiles are not published.
LeadProfileSpec leadProfileSpec(char id);

/// Lead speed of profile id sampled every time_step_s from t = 0 to the end of the last hold
/// [m/s]. Throws std::invalid_argument for an unknown id or a step that is not positive.
std::vector<double> leadProfile(char id, double time_step_s);
/// The same with another ramp (for sensitivity studies).
std::vector<double> leadProfile(char id, double time_step_s, const LeadRamp& ramp);
/// Samples any specification (piecewise linear in time: ramps at the spec's rates, then holds).
std::vector<double> sampleLeadProfile(const LeadProfileSpec& spec, double time_step_s);

/// "speed changes ramp at +a / -d m/s^2 (assumed; ...)".
std::string describeLeadRamp(const LeadRamp& ramp);

/// The profile's description with its default ramp.
std::string leadProfileDescription(char id);

}  // namespace acc
