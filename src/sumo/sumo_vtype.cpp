#include "acc_identification/sumo/sumo_vtype.h"

#include <tinyxml2.h>

#include <algorithm>
#include <charconv>
#include <cctype>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <stdexcept>

#include "acc_identification/model/number_text.h"

namespace acc
{
const char* const kSumoOpenAccProvenance =
    "Identified from the JRC OpenACC database (Makridis, Mattas, Anesiadou, Ciuffo, Transportation Research Part "
    "C 125 (2021) 103047), (c) European Union, licensed under CC BY 4.0 "
    "(https://creativecommons.org/licenses/by/4.0); the JRC does not endorse this package. Changes: the cars' "
    "speeds and gaps calibrated with the ACC model, the model mapped onto SUMO's ACC.";

std::string toString(SumoMapping mapping)
{
  switch (mapping)
  {
    case SumoMapping::exact:
      return "exact";
    case SumoMapping::approximate:
      return "approximate";
    case SumoMapping::none:
      return "none";
  }
  return "unknown";
}

ObservedAccelerationLimits observedAccelerationLimits(const std::vector<CarFollowingRun>& runs, double window_s)
{
  double largest_acceleration = -std::numeric_limits<double>::infinity();
  double largest_deceleration = -std::numeric_limits<double>::infinity();
  for (const CarFollowingRun& run : runs)
  {
    std::size_t later = 0;
    for (std::size_t k = 0; k < run.size(); ++k)
    {
      // The first sample at least window_s after k (two pointers: the runs' steps need not be uniform).
      later = std::max(later, k + 1);
      while (later < run.size() && run.time_s[later] - run.time_s[k] < window_s)
        ++later;
      if (later >= run.size())
        break;
      const double acceleration = (run.follower_speed_mps[later] - run.follower_speed_mps[k]) /
                                  (run.time_s[later] - run.time_s[k]);
      largest_acceleration = std::max(largest_acceleration, acceleration);
      largest_deceleration = std::max(largest_deceleration, -acceleration);
    }
  }
  ObservedAccelerationLimits limits;
  if (std::isfinite(largest_acceleration))
  {
    limits.max_acceleration_mps2 = largest_acceleration;
    limits.max_deceleration_mps2 = largest_deceleration;
  }
  return limits;
}

EffectSettings PackageModel::settings() const
{
  return makeCombinedEffectSettings(effects, effect_values);
}

namespace
{
/// The shortest text that reads back as the same double ("2.4", not "2.4000000000000004").
std::string shortest(double value)
{
  char text[32];
  const auto [end, error] = std::to_chars(text, text + sizeof text, value);
  return error == std::errc() ? std::string(text, end) : std::string("nan");
}

/// The exported limits: the fitted ones when the model has them, else the data's, floored.
void exportLimits(const EffectSettings& settings, bool fitted, const ObservedAccelerationLimits& limits,
                  const SumoExportOptions& options, SumoExport& out)
{
  SumoAccVType& vtype = out.vtype;
  if (fitted)
  {
    // The fitted limits bound the command exactly: SUMO lets an ACC command brake down to
    // emergencyDecel, so that is the fitted deceleration too.
    vtype.accel_mps2 = settings.max_acceleration_mps2;
    vtype.decel_mps2 = vtype.emergency_decel_mps2 = settings.max_deceleration_mps2;
    out.notes.push_back({"acceleration_limits", SumoMapping::exact,
                         "accel and decel = emergencyDecel are the fitted limits (SUMO bounds each step's speed "
                         "change by them; its safe speed may then override the law, which sumo_replay counts)"});
    return;
  }
  const bool observed = std::isfinite(limits.max_acceleration_mps2);
  vtype.accel_mps2 = std::max(options.min_accel_mps2, observed ? limits.max_acceleration_mps2 : 0.0);
  vtype.decel_mps2 = std::max(options.min_decel_mps2, observed ? limits.max_deceleration_mps2 : 0.0);
  // What the car can brake in an emergency the data do not show: SUMO's own default. An ACC
  // command may brake harder than decel (down to this) in SUMO, as in the identified model, and
  // SUMO's safe speed falls back on it instead of overriding the law.
  vtype.emergency_decel_mps2 = std::max(vtype.decel_mps2, options.emergency_decel_mps2);
  out.notes.push_back({"accel, decel", SumoMapping::approximate,
                       "not identified: the largest acceleration (accel, a bound SUMO enforces and the model does "
                       "not) and deceleration (decel, what SUMO's safe speed assumes) the car showed in the data, "
                       "from 1 s speed differences; emergencyDecel is SUMO's default"});
}

/// minGap + length = eta (SUMO 1.15 subtracts the follower's length from the spacing error).
void exportStandstillGap(double eta_m, const SumoExportOptions& options, SumoExport& out)
{
  out.vtype.length_m = std::max(kShortestSumoLengthM, std::min(options.vehicle_length_m, eta_m));
  out.vtype.min_gap_m = std::max(0.0, eta_m - out.vtype.length_m);
  const bool exact = std::abs(out.vtype.min_gap_m + out.vtype.length_m - eta_m) < 1e-9;
  out.notes.push_back({"eta", exact ? SumoMapping::exact : SumoMapping::approximate,
                       "minGap + length = eta above 15 m/s; below it SUMO 1.15 adds Xiao et al.'s margin d0 (2 m "
                       "below 10.8 m/s, 75/v - 5 up to 15 m/s), which the identified model does not have" +
                           std::string(exact ? "" : "; eta is shorter than SUMO's shortest length")});
}

void exportResponseEffects(const AccParameters& p, const EffectSettings& settings, bool asymmetric, SumoExport& out)
{
  SumoAccGains& gains = out.vtype.gains;
  gains.gap_closing_gain_speed_per_s = gains.gap_control_gain_speed_per_s = p.k2_per_s;
  gains.gap_closing_gain_space_per_s2 = gains.gap_control_gain_space_per_s2 = p.k1_per_s2;
  gains.collision_avoidance_gain_speed_per_s = p.k2_per_s;
  gains.collision_avoidance_gain_space_per_s2 = p.k1_per_s2;
  out.notes.push_back({"k1, k2", SumoMapping::exact,
                       "k1 on the spacing error and k2 on the speed difference in all three gap-control modes "
                       "(gap, gap closing, collision avoidance), so SUMO's mode switches change nothing"});
  // SUMO refuses tau = 0 (a fit can put tau_e on its lower bound): the shortest tau it takes
  // changes the desired gap by under a centimetre.
  out.vtype.tau_s = std::max(kShortestSumoTauS, p.tau_e_s);
  out.notes.push_back({"tau_e", p.tau_e_s >= kShortestSumoTauS ? SumoMapping::exact : SumoMapping::approximate,
                       p.tau_e_s >= kShortestSumoTauS ? "tau = tau_e"
                                                      : "tau = " + shortest(kShortestSumoTauS) +
                                                            " s: tau_e is 0, which SUMO refuses"});
  if (!asymmetric)
    return;
  gains.collision_avoidance_gain_space_per_s2 = p.k1_per_s2 * settings.short_gap_gain_ratio;
  out.notes.push_back({"asymmetric_response.short_gap_gain_ratio", SumoMapping::exact,
                       "collisionAvoidanceGainSpace = k1 r_s: SUMO's collision-avoidance mode is the law while "
                       "the gap is shorter than desired"});
  out.notes.push_back({"asymmetric_response.closing_gain_ratio", SumoMapping::none,
                       "SUMO switches gains on the spacing error's sign only, not on whether the car closes in: "
                       "k2 is exported unscaled (r_c = " +
                           std::to_string(settings.closing_gain_ratio) + " is lost)"});
}

/// A dead time d as SUMO's actionStepLength = 2 d: SUMO decides every 2 d and holds the
/// acceleration in between, so its decisions are d old on average, as the delayed model's are.
/// Not the same law: it reproduces what a delay does to a braking passed along a platoon (the
/// dips), not the speed trace (docs/SUMO.md, measured).
void exportReactionDelay(const EffectSettings& settings, SumoExport& out)
{
  // SUMO takes action steps in whole simulation steps: whole 0.1 s steps (the data's 10 Hz).
  const double steps = std::round(20.0 * settings.reaction_delay_s);
  if (steps < 2.0)
  {
    out.notes.push_back({"reaction_delay", SumoMapping::none,
                         "a dead time under one 0.1 s step: SUMO's ACC acts every step"});
    return;
  }
  out.vtype.action_step_length_s = steps / 10.0;  // whole 0.1 s steps, "2.4" in the file
  out.notes.push_back({"reaction_delay", SumoMapping::approximate,
                       "actionStepLength = 2 d (SUMO decides every 2 d and holds its acceleration, a decision d old "
                       "on average): it passes a braking on along a platoon as the delayed model does, but it is "
                       "not the same law and its speed trace differs (docs/SUMO.md)"});
}

void exportSetSpeed(const EffectSettings& settings, SumoExport& out)
{
  out.vtype.max_speed_mps = settings.set_speed_mps;
  out.vtype.gains.speed_control_gain_per_s = -settings.cruise_gain_per_s;
  out.notes.push_back({"set_speed_cruise", SumoMapping::approximate,
                       "maxSpeed = the set speed (SUMO never exceeds it) and speedControlGain = -cruise gain; SUMO "
                       "applies speed control only beyond 120 m of gap, the model whenever it commands less"});
}

std::string noEquivalentNote(EffectKind kind)
{
  switch (kind)
  {
    case EffectKind::actuation_lag:
      return "SUMO 1.15's ACC realises its command within the step (no first-order lag)";
    case EffectKind::sensor_time_offset:
      return "a clock offset between the two receivers is a property of the recording, not of the car";
    case EffectKind::speed_dependent_time_gap:
      return "SUMO's desired gap is linear in speed (tau v) plus its own fixed margin d0(v)";
    case EffectKind::leader_acceleration_feedforward:
      return "SUMO's ACC has no term in the leader's acceleration (its CACC model does, from communication)";
    case EffectKind::speed_dependent_gains:
      return "SUMO's gains are constants";
    case EffectKind::quadratic_closing_response:
      return "SUMO's ACC is linear in the speed difference within each of its modes";
    case EffectKind::leader_braking_anticipation:
      return "SUMO's ACC has no term in the leader's acceleration, on either side";
    default:
      return "";
  }
}
}  // namespace

SumoExport exportToSumo(const std::string& id, const AccParameters& parameters, const std::vector<EffectKind>& effects,
                        const std::vector<double>& effect_values, const ObservedAccelerationLimits& limits,
                        const SumoExportOptions& options)
{
  SumoExport out;
  out.vtype.id = id;
  out.vtype.has_source_model = true;
  out.vtype.source_parameters = parameters;
  out.vtype.source_effects = effects;
  out.vtype.source_effect_values = effect_values;
  const EffectSettings settings = makeCombinedEffectSettings(effects, effect_values);
  const auto has = [&](EffectKind kind) { return std::find(effects.begin(), effects.end(), kind) != effects.end(); };
  exportResponseEffects(parameters, settings, has(EffectKind::asymmetric_response), out);
  exportStandstillGap(parameters.eta_m, options, out);
  exportLimits(settings, has(EffectKind::acceleration_limits), limits, options, out);
  if (has(EffectKind::reaction_delay))
    exportReactionDelay(settings, out);
  if (has(EffectKind::set_speed_cruise))
    exportSetSpeed(settings, out);
  else
    out.notes.push_back({"free-road speed", SumoMapping::none,
                         "not identified: no maxSpeed (the lane's limit is the desired speed) and SUMO's default "
                         "speedControlGain, used only beyond 120 m of gap"});
  for (EffectKind kind : effects)
  {
    const std::string note = noEquivalentNote(kind);
    if (!note.empty())
      out.notes.push_back({effectName(kind), SumoMapping::none, note});
  }
  return out;
}

std::string sumoId(const std::string& name)
{
  std::string id = name.empty() ? std::string("acc") : name;
  for (char& c : id)
  {
    const bool kept = std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '-' || c == '.';
    if (!kept)
      c = '_';
  }
  return id;
}

namespace
{
void setNumber(tinyxml2::XMLElement* element, const char* name, double value)
{
  element->SetAttribute(name, shortest(value).c_str());
}

void addParam(tinyxml2::XMLElement* vtype, const std::string& key, const std::string& value)
{
  tinyxml2::XMLElement* param = vtype->InsertNewChildElement("param");
  param->SetAttribute("key", ("acc_identification." + key).c_str());
  param->SetAttribute("value", value.c_str());
}

void addSourceModel(tinyxml2::XMLElement* element, const SumoAccVType& vtype)
{
  const AccParameters& p = vtype.source_parameters;
  addParam(element, "k1_per_s2", shortest(p.k1_per_s2));
  addParam(element, "k2_per_s", shortest(p.k2_per_s));
  addParam(element, "tau_e_s", shortest(p.tau_e_s));
  addParam(element, "eta_m", shortest(p.eta_m));
  std::string effects, values;
  for (EffectKind kind : vtype.source_effects)
    effects += (effects.empty() ? "" : " ") + effectName(kind);
  for (double value : vtype.source_effect_values)
    values += (values.empty() ? "" : " ") + shortest(value);
  addParam(element, "effects", effects);
  addParam(element, "effect_values", values);
}

void addVType(tinyxml2::XMLDocument& document, tinyxml2::XMLElement* root, const SumoExport& item)
{
  const SumoAccVType& v = item.vtype;
  for (const std::string& caveat : item.caveats)
    root->InsertEndChild(document.NewComment((" " + v.id + ": CAVEAT: " + caveat + " ").c_str()));
  for (const SumoMappingNote& note : item.notes)
    root->InsertEndChild(document.NewComment((" " + v.id + ": " + note.part + " [" + toString(note.mapping) +
                                              "]: " + note.note + " ")
                                                 .c_str()));
  tinyxml2::XMLElement* element = root->InsertNewChildElement("vType");
  element->SetAttribute("id", v.id.c_str());
  element->SetAttribute("carFollowModel", "ACC");
  setNumber(element, "tau", v.tau_s);
  setNumber(element, "minGap", v.min_gap_m);
  setNumber(element, "length", v.length_m);
  setNumber(element, "accel", v.accel_mps2);
  setNumber(element, "decel", v.decel_mps2);
  setNumber(element, "emergencyDecel", v.emergency_decel_mps2);
  if (std::isfinite(v.max_speed_mps))
    setNumber(element, "maxSpeed", v.max_speed_mps);
  if (std::isfinite(v.action_step_length_s))
    setNumber(element, "actionStepLength", v.action_step_length_s);
  // The identified car drives the lane's limit exactly: no speed deviation drawn per vehicle.
  element->SetAttribute("speedFactor", "1");
  element->SetAttribute("speedDev", "0");
  setNumber(element, "speedControlGain", v.gains.speed_control_gain_per_s);
  setNumber(element, "gapClosingControlGainSpeed", v.gains.gap_closing_gain_speed_per_s);
  setNumber(element, "gapClosingControlGainSpace", v.gains.gap_closing_gain_space_per_s2);
  setNumber(element, "gapControlGainSpeed", v.gains.gap_control_gain_speed_per_s);
  setNumber(element, "gapControlGainSpace", v.gains.gap_control_gain_space_per_s2);
  setNumber(element, "collisionAvoidanceGainSpeed", v.gains.collision_avoidance_gain_speed_per_s);
  setNumber(element, "collisionAvoidanceGainSpace", v.gains.collision_avoidance_gain_space_per_s2);
  setNumber(element, "collisionAvoidanceOverride", v.gains.collision_avoidance_override_mps);
  if (v.has_source_model)
    addSourceModel(element, v);
}
}  // namespace

void writeSumoAdditional(const std::vector<SumoExport>& exports, const std::string& path, const std::string& provenance)
{
  tinyxml2::XMLDocument document;
  document.InsertEndChild(document.NewDeclaration());
  document.InsertEndChild(document.NewComment(
      " SUMO 1.15 vTypes of identified ACCs (carFollowModel ACC), made by acc_identification; docs/SUMO.md "
      "gives the mapping. Each vType's comments say what of its model SUMO has (exact), has in part "
      "(approximate) or lacks (none). "));
  if (!provenance.empty())
    document.InsertEndChild(document.NewComment((" " + provenance + " ").c_str()));
  tinyxml2::XMLElement* root = document.NewElement("additional");
  document.InsertEndChild(root);
  for (const SumoExport& item : exports)
    addVType(document, root, item);
  if (document.SaveFile(path.c_str()) != tinyxml2::XML_SUCCESS)
    throw std::runtime_error("cannot write the SUMO vType file " + path);
}

bool saveSumoVTypes(const std::vector<SumoExport>& exports, const std::string& path, const std::string& provenance,
                    std::ostream& log)
{
  try
  {
    writeSumoAdditional(exports, path, provenance);
  }
  catch (const std::exception& error)
  {
    log << "error: " << error.what() << "\n";
    return false;
  }
  log << "SUMO vType" << (exports.size() == 1 ? " " : "s ");
  for (std::size_t i = 0; i < exports.size(); ++i)
    log << (i > 0 ? ", " : "") << exports[i].vtype.id;
  log << " written to " << path << "\n";
  return true;
}

bool saveFittedModelVType(const std::string& path, const std::string& id, const AccParameters& base,
                          const std::vector<EffectKind>& effects, const std::vector<double>& effect_values,
                          const std::vector<CarFollowingRun>& runs, const std::string& caveat, bool from_openacc,
                          std::ostream& log)
{
  SumoExport exported = exportToSumo(sumoId(id), base, effects, effect_values, observedAccelerationLimits(runs));
  if (!caveat.empty())
    exported.caveats.push_back(caveat);
  return saveSumoVTypes({exported}, path, from_openacc ? kSumoOpenAccProvenance : "", log);
}

namespace
{
/// The vType's id, "" when the file gives none (SUMO then refuses it; here it names errors).
std::string vtypeId(const tinyxml2::XMLElement* element)
{
  const char* id = element->Attribute("id");
  return id != nullptr ? id : "";
}

double number(const tinyxml2::XMLElement* element, const char* name, double fallback, const std::string& path)
{
  const char* text = element->Attribute(name);
  if (text == nullptr)
    return fallback;
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  if (end == text || *end != '\0' || !std::isfinite(value))
    throw std::runtime_error(path + ": vType '" + vtypeId(element) + "': " + name + "=\"" + text +
                             "\" is not a number");
  return value;
}

std::vector<double> numbers(const std::string& text, const std::string& where)
{
  std::istringstream in(text);
  std::vector<double> values;
  std::string field;
  while (in >> field)
  {
    char* end = nullptr;
    values.push_back(std::strtod(field.c_str(), &end));
    // nan or inf: the model's trace would be non-finite from its first step, and every error
    // scored over what is left (its start) would read 0.
    if (*end != '\0' || !std::isfinite(values.back()))
      throw std::runtime_error(where + ": '" + field + "' is not a finite number");
  }
  return values;
}

void readSourceModel(const tinyxml2::XMLElement* element, const std::string& path, SumoAccVType& vtype)
{
  std::map<std::string, std::string> params;
  for (const auto* param = element->FirstChildElement("param"); param != nullptr;
       param = param->NextSiblingElement("param"))
  {
    const char* key = param->Attribute("key");
    const char* value = param->Attribute("value");
    if (key != nullptr && value != nullptr && std::string(key).rfind("acc_identification.", 0) == 0)
      params[std::string(key).substr(19)] = value;
  }
  if (params.count("k1_per_s2") == 0)
    return;
  const std::string where = path + ": vType '" + vtype.id + "'";
  const auto single = [&](const std::string& key) {
    const std::vector<double> values = numbers(params[key], where + " param " + key);
    if (values.size() != 1)
      throw std::runtime_error(where + ": param acc_identification." + key + " needs one number");
    return values.front();
  };
  vtype.source_parameters = {single("k1_per_s2"), single("k2_per_s"), single("tau_e_s"), single("eta_m")};
  std::istringstream effects(params["effects"]);
  std::string name;
  std::size_t expected_values = 0;
  while (effects >> name)
  {
    EffectKind kind = EffectKind::none;
    if (!parseEffectName(name, &kind))
      throw std::runtime_error(where + ": unknown effect '" + name + "'");
    vtype.source_effects.push_back(kind);
    expected_values += candidateEffect(kind).parameters.size();
  }
  vtype.source_effect_values = numbers(params["effect_values"], where + " param effect_values");
  if (vtype.source_effect_values.size() != expected_values)
    throw std::runtime_error(where + ": " + std::to_string(vtype.source_effect_values.size()) +
                             " effect values for effects needing " + std::to_string(expected_values));
  vtype.has_source_model = true;
}

/// What this reader cannot take as SUMO would, said rather than guessed: a vClass whose defaults
/// are not a passenger car's (a truck's length, accel, decel, and its maxSpeed: a truck capped at
/// 36.11 m/s was replayed behind a leader at 40) with those attributes left to it, and emergency
/// braking weaker than the normal (SUMO stops on an assertion).
void refuseWhatSumoReadsOtherwise(const tinyxml2::XMLElement* element, const SumoAccVType& v, const std::string& path)
{
  const std::string where = path + ": vType '" + v.id + "'";
  const char* vclass = element->Attribute("vClass");
  if (vclass != nullptr && std::string(vclass) != "passenger")
    for (const char* attribute : {"length", "accel", "decel", "emergencyDecel", "maxSpeed"})
      if (element->Attribute(attribute) == nullptr)
        throw std::runtime_error(where + ": vClass \"" + vclass + "\" leaves " + attribute +
                                 " to its class default, which this reader does not know (it knows a passenger "
                                 "car's): give length, accel, decel, emergencyDecel and maxSpeed in the vType");
  if (v.emergency_decel_mps2 < v.decel_mps2)
    throw std::runtime_error(where + ": emergencyDecel " + significant(v.emergency_decel_mps2) + " below decel " +
                             significant(v.decel_mps2) + ": SUMO refuses to simulate it (an assertion)");
}

SumoAccVType readVType(const tinyxml2::XMLElement* element, const std::string& path)
{
  SumoAccVType v;
  v.id = vtypeId(element);
  v.tau_s = number(element, "tau", v.tau_s, path);
  v.min_gap_m = number(element, "minGap", v.min_gap_m, path);
  v.length_m = number(element, "length", v.length_m, path);
  v.accel_mps2 = number(element, "accel", v.accel_mps2, path);
  v.decel_mps2 = number(element, "decel", v.decel_mps2, path);
  v.emergency_decel_mps2 = number(element, "emergencyDecel", std::max(v.decel_mps2, 9.0), path);
  v.max_speed_mps = number(element, "maxSpeed", v.max_speed_mps, path);
  v.action_step_length_s = number(element, "actionStepLength", v.action_step_length_s, path);
  SumoAccGains& g = v.gains;
  g.speed_control_gain_per_s = number(element, "speedControlGain", g.speed_control_gain_per_s, path);
  g.gap_closing_gain_speed_per_s = number(element, "gapClosingControlGainSpeed", g.gap_closing_gain_speed_per_s, path);
  g.gap_closing_gain_space_per_s2 =
      number(element, "gapClosingControlGainSpace", g.gap_closing_gain_space_per_s2, path);
  g.gap_control_gain_speed_per_s = number(element, "gapControlGainSpeed", g.gap_control_gain_speed_per_s, path);
  g.gap_control_gain_space_per_s2 = number(element, "gapControlGainSpace", g.gap_control_gain_space_per_s2, path);
  g.collision_avoidance_gain_speed_per_s =
      number(element, "collisionAvoidanceGainSpeed", g.collision_avoidance_gain_speed_per_s, path);
  g.collision_avoidance_gain_space_per_s2 =
      number(element, "collisionAvoidanceGainSpace", g.collision_avoidance_gain_space_per_s2, path);
  g.collision_avoidance_override_mps =
      number(element, "collisionAvoidanceOverride", g.collision_avoidance_override_mps, path);
  readSourceModel(element, path, v);
  refuseWhatSumoReadsOtherwise(element, v, path);
  return v;
}

/// A nested <carFollowing-X> element, SUMO's older form, sets the model in place of the attribute:
/// refused, since this reader takes the attributes (it would read an ACC that SUMO runs as X).
void refuseNestedCarFollowing(const tinyxml2::XMLElement* vtype, const std::string& path)
{
  for (const auto* child = vtype->FirstChildElement(); child != nullptr; child = child->NextSiblingElement())
  {
    const std::string name = child->Name();
    if (name.rfind("carFollowing-", 0) == 0)
      throw std::runtime_error(path + ": vType '" + vtypeId(vtype) + "' holds a nested <" + name +
                               "> element, which SUMO takes as its model and parameters: write the model as the "
                               "vType's carFollowModel attribute and its parameters as attributes");
  }
}

void collectVTypes(const tinyxml2::XMLElement* parent, const std::string& path, std::vector<SumoAccVType>& out)
{
  for (const auto* child = parent->FirstChildElement(); child != nullptr; child = child->NextSiblingElement())
  {
    const char* model = child->Attribute("carFollowModel");
    if (std::string(child->Name()) == "vType")
      refuseNestedCarFollowing(child, path);
    if (std::string(child->Name()) == "vType" && model != nullptr && std::string(model) == "ACC")
      out.push_back(readVType(child, path));
    else
      collectVTypes(child, path, out);  // vTypes inside a vTypeDistribution
  }
}
}  // namespace

std::vector<SumoAccVType> readSumoAccVTypes(const std::string& path)
{
  tinyxml2::XMLDocument document;
  if (document.LoadFile(path.c_str()) != tinyxml2::XML_SUCCESS)
    throw std::runtime_error("cannot read the SUMO file " + path + ": " + document.ErrorStr());
  if (document.RootElement() == nullptr)
    throw std::runtime_error(path + " holds no XML element");
  std::vector<SumoAccVType> vtypes;
  collectVTypes(document.RootElement(), path, vtypes);
  return vtypes;
}

PackageModel packageModelOf(const SumoAccVType& vtype)
{
  PackageModel model;
  if (vtype.has_source_model)
  {
    model.parameters = vtype.source_parameters;
    model.effects = vtype.source_effects;
    model.effect_values = vtype.source_effect_values;
    return model;
  }
  const SumoAccGains& g = vtype.gains;
  model.parameters = {g.gap_closing_gain_space_per_s2, g.gap_closing_gain_speed_per_s, vtype.tau_s,
                      vtype.min_gap_m + vtype.length_m};
  model.effects = {EffectKind::acceleration_limits};
  model.effect_values = {vtype.accel_mps2, vtype.emergency_decel_mps2};
  if (g.gap_closing_gain_space_per_s2 > 0.0 &&
      g.collision_avoidance_gain_space_per_s2 != g.gap_closing_gain_space_per_s2)
  {
    model.effects.push_back(EffectKind::asymmetric_response);
    model.effect_values.push_back(1.0);
    model.effect_values.push_back(g.collision_avoidance_gain_space_per_s2 / g.gap_closing_gain_space_per_s2);
  }
  return model;
}

}  // namespace acc
