#pragma once

#include <array>
#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// Box constraints of the calibration: the paper's k1, k2, tau_e, eta >= 0, plus upper bounds far
/// above any published ACC fit (Gunter et al. Table II: k1 < 0.1, k2 < 0.5, tau_e < 1.7,
/// eta < 9). The Euler map of the follower, [s; v] -> [[1, -h], [h k1, 1 - h c]] [s; v] with
/// c = k1 tau_e + k2, is stable when h c < 2 + h^2 k1 / 2 and h k1 < c. The bounds keep the first
/// (h c <= 1.3 at 10 Hz); the second fails for tau_e < h with little k2 (a nearly undamped
/// spring), whose slow growth the objective catches as divergence.
struct ParameterBounds
{
  AccParameters lower{0.0, 0.0, 0.0, 0.0};
  AccParameters upper{2.0, 3.0, 5.0, 50.0};
};

/// The reduced objective at one (k1, k2, tau_e): eta already at its least-squares optimum.
struct ReducedObjectiveValue
{
  double mse_speed_mps2 = 0.0;          ///< mean over samples of (v_measured - v_simulated)^2
  std::array<double, 3> gradient{};     ///< d mse / d (k1, k2, tau_e), exact (forward sensitivities)
  double eta_m = 0.0;                   ///< the best eta within its bounds for this (k1, k2, tau_e)
  bool diverged = false;                ///< the Euler recursion blew up: mse is the penalty below
};

/// Value reported for a divergent simulation: an RMSE of 1000 m/s, finite so that an optimiser
/// backs off instead of propagating NaN, and worse than any real fit.
constexpr double kDivergedMseMps2 = 1.0e6;

/// The calibration objective of Gunter et al. (Section IV) over one or more segments, each
/// simulated by explicit Euler from its own measured initial gap and speed, driven by the measured
/// leader speed, exactly as simulateFollower(); the squared speed errors of all segments (every
/// sample, including each segment's first) are pooled.
///
/// Speed: for fixed (k1, k2, tau_e) the recursion is linear and eta enters as a constant input,
/// so v = v_a + eta v_g (v_a: eta = 0; v_g: response to a unit eta). One pass carries v_a, v_g
/// and their sensitivities to (k1, k2, tau_e) and accumulates the few sums from which the best
/// eta (one division, clipped), the MSE and its exact gradient follow. The gradient is the
/// partial derivative at the optimal eta (envelope theorem; also right when eta sits on a bound).
class CalibrationObjective
{
public:
  /// Every segment must satisfy describeRunProblem() == ""; throws std::invalid_argument if not.
  CalibrationObjective(const std::vector<CarFollowingRun>& segments, ParameterBounds bounds = {});

  ReducedObjectiveValue evaluate(double k1_per_s2, double k2_per_s, double tau_e_s,
                                 bool with_gradient) const;

  std::size_t sampleCount() const { return sample_count_; }
  const ParameterBounds& bounds() const { return bounds_; }

private:
  struct Segment
  {
    double initial_gap_m = 0.0;
    double initial_speed_mps = 0.0;
    std::vector<double> step_s;          ///< h_k = t[k+1] - t[k]
    std::vector<double> leader_speed_mps;
    std::vector<double> follower_speed_mps;
  };
  std::vector<Segment> segments_;
  std::size_t sample_count_ = 0;
  ParameterBounds bounds_;
};

/// One run simulated at p by the objective's own pass: per sample the speed residual
/// v_measured - v_simulated and the Jacobian row d v_simulated / d (k1, k2, tau_e, eta), from the
/// forward sensitivities (the first sample, the measured start, has residual and row 0). For the
/// sandwich standard errors (fit_statistics.h). diverged: the recursion ran away (rows stop there).
struct SensitivityRows
{
  std::vector<double> time_s;
  std::vector<double> residual;
  std::vector<Eigen::Vector4d> row;
  bool diverged = false;
};

SensitivityRows sensitivityRows(const AccParameters& p, const CarFollowingRun& run);

}  // namespace acc
