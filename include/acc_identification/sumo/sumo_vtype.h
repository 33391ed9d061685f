#pragma once

#include <limits>
#include <ostream>
#include <string>
#include <vector>

#include "acc_identification/model/acc_parameters.h"
#include "acc_identification/model/car_following_run.h"
#include "acc_identification/model/follower_effects.h"
#include "acc_identification/sumo/sumo_acc_law.h"

namespace acc
{
/// One SUMO vType with carFollowModel="ACC" (SUMO 1.15, sumo_acc_law.h): what an identified car
/// becomes in a SUMO additional file.
struct SumoAccVType
{
  std::string id;
  double tau_s = 1.0;                 ///< tau: the ACC's headway time (SUMO's default 1 s)
  double min_gap_m = 2.5;             ///< minGap (SUMO's default)
  double length_m = 5.0;              ///< length (SUMO's default)
  double accel_mps2 = 2.6;            ///< accel: largest acceleration (SUMO's passenger default)
  double decel_mps2 = 4.5;            ///< decel: the deceleration SUMO's safe speeds assume
  double emergency_decel_mps2 = 9.0;  ///< emergencyDecel: the hardest braking SUMO lets the ACC command and its safe speed use
  /// maxSpeed; NaN: not written (the lane's speed limit is then the ACC's desired speed).
  double max_speed_mps = std::numeric_limits<double>::quiet_NaN();
  /// actionStepLength: SUMO decides every this long and holds its acceleration in between (the
  /// export's stand-in for a reaction delay d: 2 d); NaN: not written (every simulation step).
  double action_step_length_s = std::numeric_limits<double>::quiet_NaN();
  SumoAccGains gains;
  /// The package's model this vType was made from, written as <param> entries so that a replay
  /// compares SUMO with exactly that model; absent in a vType made elsewhere.
  bool has_source_model = false;
  AccParameters source_parameters;
  std::vector<EffectKind> source_effects;
  std::vector<double> source_effect_values;  ///< catalogue order, effect after effect
};

/// The shortest vehicle length the export gives SUMO [m] (SUMO's own position resolution).
constexpr double kShortestSumoLengthM = 0.1;
/// The shortest headway time the export gives SUMO, which refuses 0 [s].
constexpr double kShortestSumoTauS = 0.001;

/// How one part of the identified model reaches SUMO.
enum class SumoMapping
{
  exact,        ///< SUMO's law has it, term for term (above 15 m/s, where d0 = 0)
  approximate,  ///< SUMO has something like it; the note says how it differs
  none,         ///< SUMO's ACC has no equivalent: the exported car lacks it
};

std::string toString(SumoMapping mapping);

struct SumoMappingNote
{
  std::string part;  ///< "k1", "asymmetric_response.closing_gain_ratio", "reaction_delay", ...
  SumoMapping mapping = SumoMapping::exact;
  std::string note;
};

/// The follower's largest acceleration and deceleration in the data: speed differences over
/// window_s (long enough that 10 Hz speed noise does not inflate them), the largest of every run.
struct ObservedAccelerationLimits
{
  double max_acceleration_mps2 = std::numeric_limits<double>::quiet_NaN();
  double max_deceleration_mps2 = std::numeric_limits<double>::quiet_NaN();  ///< a positive number
};
ObservedAccelerationLimits observedAccelerationLimits(const std::vector<CarFollowingRun>& runs, double window_s = 1.0);

struct SumoExportOptions
{
  /// The vehicle's length in SUMO when eta allows it: SUMO 1.15's desired gap holds minGap + length,
  /// so eta is split as length = min(this, eta), minGap = eta - length.
  double vehicle_length_m = 4.5;
  /// Floors of the exported limits when the data hold no braking or acceleration at all.
  double min_accel_mps2 = 0.5;
  double min_decel_mps2 = 1.0;
  /// emergencyDecel when the model has no fitted deceleration limit: SUMO's default (the data do
  /// not show what the car can brake in an emergency).
  double emergency_decel_mps2 = 9.0;
};

/// A vType and the notes on what each part of the model became.
struct SumoExport
{
  SumoAccVType vtype;
  std::vector<SumoMappingNote> notes;
  /// What a user of the vType must know of the model itself (its adequacy, an effect the platoon
  /// diagnosis found that SUMO cannot carry), written beside the notes.
  std::vector<std::string> caveats;
};

/// The identified model (base parameters and effects) as SUMO's ACC:
///   gapClosing/gapControl/collisionAvoidance gains: k2 on the speed difference, k1 on the spacing
///   error (all three modes alike, so the mode switches change nothing above 15 m/s);
///   tau = tau_e; minGap + length = eta; accel and decel from the data, emergencyDecel SUMO's
///   default (or all three the fitted acceleration limits); the effects where SUMO has an
///   equivalent (notes say which).
/// The identified parameters must be finite.
SumoExport exportToSumo(const std::string& id, const AccParameters& parameters, const std::vector<EffectKind>& effects,
                        const std::vector<double>& effect_values, const ObservedAccelerationLimits& limits,
                        const SumoExportOptions& options = {});

/// A vType id from a car's name: letters, digits, '_', '-' and '.' kept, anything else '_'.
std::string sumoId(const std::string& name);

/// The data's attribution for vTypes identified from JRC OpenACC files (CC BY 4.0 asks for it
/// wherever something made from the data is shipped).
extern const char* const kSumoOpenAccProvenance;

/// The additional file: every vType, the notes and caveats as comments, and the data's
/// provenance line when given. Throws std::runtime_error when the file cannot be written.
void writeSumoAdditional(const std::vector<SumoExport>& exports, const std::string& path,
                         const std::string& provenance);

/// writeSumoAdditional for the tools' --sumo-vtype: says on log what was written ("SUMO vType(s)
/// ID, ... written to PATH") or why not ("error: ..."), and returns whether it was.
bool saveSumoVTypes(const std::vector<SumoExport>& exports, const std::string& path, const std::string& provenance,
                    std::ostream& log);

/// One fitted model as calibrate's and diagnose's --sumo-vtype write it: exportToSumo with the
/// acceleration limits observed in its runs, the caveat when one is given (e.g. a model that does
/// not describe its data), the OpenACC attribution when the runs came from OpenACC files.
bool saveFittedModelVType(const std::string& path, const std::string& id, const AccParameters& base,
                          const std::vector<EffectKind>& effects, const std::vector<double>& effect_values,
                          const std::vector<CarFollowingRun>& runs, const std::string& caveat, bool from_openacc,
                          std::ostream& log);

/// Every vType with carFollowModel="ACC" in a SUMO additional or route file (attributes absent:
/// SUMO 1.15's defaults). Throws std::runtime_error naming the file and what is wrong.
std::vector<SumoAccVType> readSumoAccVTypes(const std::string& path);

/// The package's model that a vType stands for: its source model when it carries one, else the
/// model SUMO's law equals above 15 m/s (k1, k2 from the gap-closing gains, tau_e = tau,
/// eta = minGap + length, the acceleration limits, the short-gap ratio from the collision-avoidance
/// space gain).
struct PackageModel
{
  AccParameters parameters;
  std::vector<EffectKind> effects;
  std::vector<double> effect_values;
  EffectSettings settings() const;
};
PackageModel packageModelOf(const SumoAccVType& vtype);

}  // namespace acc
