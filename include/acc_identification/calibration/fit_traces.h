#pragma once

#include <string>
#include <vector>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// One run (or half of one) as measured and as the fitted model simulates it, from its own
/// measured start: what `calibrate --report` plots.
struct FitTrace
{
  std::string run;
  std::string part;  ///< "fit" (all of a run), "train" or "held_out" (--split half)
  std::vector<double> time_s;
  std::vector<double> measured_speed_mps, simulated_speed_mps;
  std::vector<double> measured_gap_m, simulated_gap_m;
};

/// The traces of training (and held-out) runs, in order, named by the whole runs' names (a run's
/// two halves are one run of the report); a diverged simulation keeps its samples up to the
/// divergence and NaN after (simulateFollower's rule: those are not to be read).
std::vector<FitTrace> fitTraces(const AccParameters& p, const std::vector<std::string>& run_names,
                                const std::vector<CarFollowingRun>& training,
                                const std::vector<CarFollowingRun>& testing);

/// run,part,time_s,measured_speed_mps,simulated_speed_mps,speed_residual_mps,measured_gap_m,
/// simulated_gap_m,gap_residual_m (residual = measured - simulated), 17 significant digits.
/// Throws std::runtime_error when the file cannot be written.
void writeFitTracesCsv(const std::vector<FitTrace>& traces, const std::string& path);

}  // namespace acc
