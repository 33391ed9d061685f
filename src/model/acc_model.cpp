#include "acc_identification/model/acc_model.h"

#include <cmath>

namespace acc
{
double accelerationMps2(const AccParameters& p, double space_gap_m, double speed_mps,
                        double relative_speed_mps)
{
  return accelerationLaw(p.k1_per_s2, p.k2_per_s, p.tau_e_s, p.eta_m, space_gap_m, speed_mps, relative_speed_mps);
}

AccelerationPartials accelerationPartials(const AccParameters& p)
{
  // f_v is taken at fixed dv: the relative-speed term's dependence on v belongs to f_dv.
  return AccelerationPartials{p.k1_per_s2, -p.k1_per_s2 * p.tau_e_s, p.k2_per_s};
}

bool satisfiesRationalDrivingConstraints(const AccParameters& p)
{
  const double values[] = {p.k1_per_s2, p.k2_per_s, p.tau_e_s, p.eta_m};
  for (double value : values)
  {
    if (!std::isfinite(value) || value < 0.0)
    {
      return false;
    }
  }
  return true;
}

double equilibriumSpaceGapM(const AccParameters& p, double speed_mps)
{
  return p.eta_m + p.tau_e_s * speed_mps;
}

}  // namespace acc
