#pragma once

#include <vector>

namespace acc
{
/// Lead speed of the paper's Fig. 7: cruise_speed_mps for lead_in_s, then
/// cruise + amplitude sin(w (t - lead_in_s)) until duration_s, sampled every time_step_s.
/// Throws std::invalid_argument for a step or duration that is not positive.
std::vector<double> sinusoidLeadProfile(double cruise_speed_mps, double amplitude_mps, double frequency_rad_s,
                                        double lead_in_s, double duration_s, double time_step_s);

/// The lead speed followed by hold_s of its last value: room at the end of a record for the
/// disturbance to reach the back of a long platoon.
std::vector<double> withFinalHold(std::vector<double> lead_speed_mps, double hold_s, double time_step_s);

}  // namespace acc
