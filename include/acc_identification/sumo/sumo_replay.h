#pragma once

#include <cstddef>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/model/car_following_run.h"
#include "acc_identification/sumo/sumo_acc_simulation.h"
#include "acc_identification/sumo/sumo_vtype.h"

namespace acc
{
/// How a replay runs SUMO: headless `sumo` driven over TraCI by scripts/sumo_traci_replay.py
/// (python3 with Debian's sumo-tools), on a straight one-lane road whose limit is above any car.
struct SumoReplayOptions
{
  std::string python = "/usr/bin/python3";
  std::string driver_script;    ///< sumo_traci_replay.py (the tool passes the one beside it)
  std::string sumo = "sumo";    ///< the SUMO binary
  /// Where the scenario (network, routes, job, trace, SUMO's log) is written; empty: a fresh
  /// temporary folder, removed afterwards.
  std::string work_dir;
  double leader_length_m = 4.5;
  double lane_speed_limit_mps = 70.0;
  /// A step of SUMO's that differs from what its ACC law and bounds give by more than this was
  /// changed by something else (its safe-speed override) [m/s].
  double departure_tolerance_mps = 1e-6;
};

/// One car behind a leader in SUMO: the leader's speeds (imposed), the car's vType, its start.
struct SumoCarStart
{
  std::string vtype_id;
  double gap_m = 0.0;
  double speed_mps = 0.0;
};

/// What SUMO did: every car's speed and gap at each step (sample 0 is the start).
struct SumoRun
{
  std::vector<std::vector<double>> speed_mps;  ///< [car][sample], car 0 the leader
  std::vector<std::vector<double>> gap_m;      ///< [car][sample], car 0 empty
};

/// Runs SUMO with the cars of `cars` behind a leader driving leader_speed_mps at step_s, vTypes
/// from vtype_file. Throws std::runtime_error with SUMO's or the driver's reason.
SumoRun runSumo(const std::vector<double>& leader_speed_mps, double step_s, const std::vector<SumoCarStart>& cars,
                const std::string& vtype_file, const SumoReplayOptions& options);

/// Why SUMO cannot replay the run as it is (fewer than two samples, or steps that differ by more
/// than 1 %), or "" when it can.
std::string nonUniformStepReason(const CarFollowingRun& run);

/// The run's uniform step [s]; throws std::runtime_error with nonUniformStepReason when there is
/// none (SUMO steps uniformly: such a run must be split or resampled first).
double uniformStepS(const CarFollowingRun& run);

/// Where SUMO's law and the identified model agree, and what the steps were.
struct SumoStepCounts
{
  std::size_t steps = 0;
  std::size_t speed_control = 0, gap_control = 0, gap_closing = 0, collision_avoidance = 0;
  std::size_t below_15_mps = 0;         ///< SUMO's gap margin d0 > 0: its desired gap is longer
  std::size_t speed_bound_active = 0;   ///< accel, emergencyDecel or the desired speed cut the law
  std::size_t safe_speed_override = 0;  ///< SUMO departed from its ACC law (its safe speed)
  std::size_t held = 0;                 ///< between action steps: the last decision held
  std::size_t law_coincides = 0;        ///< none of the above changed the law, and its gains are the model's
};

/// A pair replay: SUMO, the package's simulation of the vType's model, and the measured car.
struct SumoPairReplay
{
  std::string run;
  std::string vtype_id;
  std::size_t samples = 0;
  double step_s = 0.0;
  double rmse_speed_sumo_vs_model_mps = 0.0;
  double rmse_speed_sumo_vs_measured_mps = 0.0;
  double rmse_speed_model_vs_measured_mps = 0.0;
  double rmse_gap_sumo_vs_model_m = 0.0;
  double rmse_gap_sumo_vs_measured_m = 0.0;
  double rmse_gap_model_vs_measured_m = 0.0;
  /// SUMO against the package's replica of SUMO's law (sumo_acc_simulation.h): near zero when the
  /// law is read right and SUMO's safe-speed override stayed out.
  double rmse_speed_sumo_vs_replica_mps = 0.0;
  SumoStepCounts counts;
  PackageModel model;
  bool model_from_vtype_params = false;  ///< the vType carried its source model
  /// Where the package's model ran away (its errors are over the samples before it); NaN if never.
  double model_diverged_at_s = std::numeric_limits<double>::quiet_NaN();
  std::vector<std::string> explanation;  ///< why SUMO and the model differ, largest cause first
};

/// Replays run's leader in SUMO with the vType behind it, from the measured start.
SumoPairReplay replayPairInSumo(const CarFollowingRun& run, const SumoAccVType& vtype, const std::string& vtype_file,
                                const SumoReplayOptions& options);

/// A platoon to replay: the leader's speeds (uniform step) and the vTypes in order behind it, each
/// car's start, and (optional, per car) its measured speeds on the same samples.
struct SumoPlatoonInput
{
  std::string name;
  std::vector<double> time_s;
  std::vector<double> leader_speed_mps;
  std::vector<SumoAccVType> vtypes;
  std::vector<SumoCarStart> starts;
  std::vector<std::vector<double>> measured_speed_mps;  ///< empty, or one (possibly empty) per car
};

/// The vTypes behind the run's leader, every car started at its model's equilibrium at the
/// leader's first speed (nothing measured).
SumoPlatoonInput equilibriumPlatoon(const CarFollowingRun& run, const std::vector<SumoAccVType>& vtypes);

/// Each perturbation's dip by position: in SUMO, in the package's chain of the vTypes' models
/// (the platoon check's simulation), in the package's chain of SUMO's law, and measured.
struct SumoPlatoonDip
{
  std::string vtype_id;
  double sumo_dip_mps = 0.0;
  double model_dip_mps = 0.0;    ///< the package's chain of the vTypes' models
  double replica_dip_mps = 0.0;  ///< the package's chain of SUMO's law (sumo_acc_simulation.h)
  double measured_dip_mps = std::numeric_limits<double>::quiet_NaN();  ///< the real car's, where given
};
struct SumoPlatoonPerturbation
{
  double onset_s = 0.0;
  double leader_dip_mps = 0.0;
  /// Why some or all dips are not measured (Perturbation::incomplete or cut_note), "" otherwise.
  std::string not_measured;
  std::vector<SumoPlatoonDip> positions;
};
struct SumoPlatoonReplay
{
  std::string run;
  std::size_t samples = 0;
  double step_s = 0.0;
  std::vector<std::string> vtype_ids;
  std::vector<double> rmse_speed_sumo_vs_model_mps;    ///< per position
  std::vector<double> rmse_speed_sumo_vs_replica_mps;  ///< per position: near 0 when SUMO's law is read right
  std::vector<SumoStepCounts> steps;                   ///< per position: SUMO's modes, margins, overrides
  std::vector<SumoPlatoonPerturbation> perturbations;
};

SumoPlatoonReplay replayPlatoonInSumo(const SumoPlatoonInput& input, const std::string& vtype_file,
                                      const SumoReplayOptions& options);

nlohmann::json toJson(const SumoPairReplay& replay);
nlohmann::json toJson(const SumoPlatoonReplay& replay);
void printReplay(const SumoPairReplay& replay, std::ostream& out);
void printReplay(const SumoPlatoonReplay& replay, std::ostream& out);

}  // namespace acc
