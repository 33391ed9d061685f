#include "acc_identification/calibration/fit_traces.h"

#include <fstream>
#include <stdexcept>

#include "acc_identification/io/csv_fields.h"
#include "acc_identification/model/follower_simulation.h"

namespace acc
{
namespace
{
FitTrace traceOf(const AccParameters& p, const std::string& name, const CarFollowingRun& run, const std::string& part)
{
  const SimulatedFollower simulated = scorable(simulateFollower(p, run));
  return {name, part, run.time_s, run.follower_speed_mps, simulated.speed_mps, run.space_gap_m, simulated.space_gap_m};
}
}  // namespace

std::vector<FitTrace> fitTraces(const AccParameters& p, const std::vector<std::string>& run_names,
                                const std::vector<CarFollowingRun>& training,
                                const std::vector<CarFollowingRun>& testing)
{
  std::vector<FitTrace> traces;
  for (std::size_t i = 0; i < training.size(); ++i)
  {
    const std::string& name = i < run_names.size() ? run_names[i] : training[i].name;
    traces.push_back(traceOf(p, name, training[i], testing.empty() ? "fit" : "train"));
    if (i < testing.size())
      traces.push_back(traceOf(p, name, testing[i], "held_out"));
  }
  return traces;
}

void writeFitTracesCsv(const std::vector<FitTrace>& traces, const std::string& path)
{
  std::ofstream out(path);
  out.precision(17);
  out << "run,part,time_s,measured_speed_mps,simulated_speed_mps,speed_residual_mps,measured_gap_m,"
         "simulated_gap_m,gap_residual_m\n";
  for (const FitTrace& t : traces)
  {
    for (std::size_t k = 0; k < t.time_s.size(); ++k)
    {
      out << csvQuoted(t.run) << ',' << t.part << ',' << t.time_s[k] << ',' << t.measured_speed_mps[k] << ','
          << t.simulated_speed_mps[k] << ',' << t.measured_speed_mps[k] - t.simulated_speed_mps[k] << ','
          << t.measured_gap_m[k] << ',' << t.simulated_gap_m[k] << ',' << t.measured_gap_m[k] - t.simulated_gap_m[k]
          << '\n';
    }
  }
  if (!out)
    throw std::runtime_error("cannot write " + path);
}

}  // namespace acc
