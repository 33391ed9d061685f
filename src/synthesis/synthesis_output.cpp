#include "acc_identification/synthesis/synthesis_output.h"

#include <nlohmann/json.hpp>

#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>

#include "acc_identification/conversion/openacc_to_nmea.h"
#include "acc_identification/io/output_files.h"
#include "acc_identification/model/paper_settings.h"

#include "acc_identification/reproduction/lead_profiles.h"

namespace acc
{
namespace
{
/// Copies into target every option that `added` switches on (differs from the default).
void mergeEffect(const EffectSettings& added, EffectSettings* target)
{
  const EffectSettings off;
  auto take = [](double from, double off_value, double* to) {
    if (from != off_value)
      *to = from;
  };
  take(added.actuation_lag_s, off.actuation_lag_s, &target->actuation_lag_s);
  take(added.reaction_delay_s, off.reaction_delay_s, &target->reaction_delay_s);
  take(added.max_acceleration_mps2, off.max_acceleration_mps2, &target->max_acceleration_mps2);
  take(added.max_deceleration_mps2, off.max_deceleration_mps2, &target->max_deceleration_mps2);
  take(added.sensor_time_offset_s, off.sensor_time_offset_s, &target->sensor_time_offset_s);
  take(added.time_gap_speed_slope_s2_per_m, off.time_gap_speed_slope_s2_per_m, &target->time_gap_speed_slope_s2_per_m);
  take(added.set_speed_mps, off.set_speed_mps, &target->set_speed_mps);
  take(added.cruise_gain_per_s, off.cruise_gain_per_s, &target->cruise_gain_per_s);
}

/// The shortest decimal that reads back as exactly value (std::to_chars round trip).
void appendShortest(double value, std::string* line)
{
  char buffer[32];
  const auto result = std::to_chars(buffer, buffer + sizeof buffer, value);
  line->append(buffer, result.ptr);
}

bool parseNumber(const std::string& text, double* value)
{
  char* end = nullptr;
  *value = std::strtod(text.c_str(), &end);
  return !text.empty() && end == text.c_str() + text.size() && std::isfinite(*value);
}
}  // namespace

std::vector<EffectKind> effectsOn(const EffectSettings& settings)
{
  std::vector<EffectKind> on;
  for (const CandidateEffect& effect : candidateEffects())
    if (effectValues(effect.kind, settings) != effectValues(effect.kind, EffectSettings{}))
      on.push_back(effect.kind);
  return on;
}

bool addEffectOption(const std::string& text, EffectSettings* settings, std::string* error)
{
  const std::size_t equals = text.find('=');
  EffectKind kind = EffectKind::none;
  if (equals == std::string::npos || !parseEffectName(text.substr(0, equals), &kind) || kind == EffectKind::none)
  {
    std::string names;
    for (const CandidateEffect& effect : candidateEffects())
      names += (names.empty() ? "" : ", ") + effect.name;
    *error = "--effect '" + text + "': expected NAME=VALUE[,VALUE] with NAME one of " + names;
    return false;
  }
  const CandidateEffect& effect = candidateEffect(kind);
  std::vector<double> values;
  std::stringstream list(text.substr(equals + 1));
  for (std::string item; std::getline(list, item, ',');)
  {
    double value = 0.0;
    if (!parseNumber(item, &value))
    {
      *error = "--effect " + effect.name + ": '" + item + "' is not a finite number";
      return false;
    }
    values.push_back(value);
  }
  std::string expected;
  for (const EffectParameterSpec& parameter : effect.parameters)
    expected += (expected.empty() ? "" : ",") + parameter.name;
  if (values.size() != effect.parameters.size())
  {
    *error = "--effect " + effect.name + " takes " + std::to_string(effect.parameters.size()) + " value(s): " + expected;
    return false;
  }
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    const EffectParameterSpec& parameter = effect.parameters[i];
    if (values[i] < parameter.lower || values[i] > parameter.upper)
    {
      std::ostringstream message;
      message << "--effect " << effect.name << ": " << parameter.name << " = " << values[i] << " is outside ["
              << parameter.lower << ", " << parameter.upper << "], the range the diagnosis searches";
      *error = message.str();
      return false;
    }
  }
  for (EffectKind on : effectsOn(*settings))
    if (on == kind)
    {
      *error = "--effect " + effect.name + " given twice";
      return false;
    }
  mergeEffect(makeEffectSettings(kind, values), settings);
  return true;
}

bool writeTruthCsv(const std::string& path, const CarFollowingRun& run, std::string* error)
{
  std::ofstream out(path);
  if (!out)
  {
    *error = "cannot write " + path;
    return false;
  }
  out << "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n";
  std::string line;
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    line.clear();
    for (const std::vector<double>* column : {&run.time_s, &run.space_gap_m, &run.follower_speed_mps, &run.leader_speed_mps})
    {
      if (!line.empty())
        line += ',';
      appendShortest((*column)[k], &line);
    }
    out << line << '\n';
  }
  out.flush();
  if (!out)
  {
    *error = "write error on " + path;
    return false;
  }
  return true;
}

std::string synthesisJson(const SynthesisOptions& options, const std::string& setting_name)
{
  nlohmann::ordered_json json;
  const AccParameters& p = options.parameters;
  json["parameters"] = {{"k1_per_s2", p.k1_per_s2}, {"k2_per_s", p.k2_per_s}, {"tau_e_s", p.tau_e_s}, {"eta_m", p.eta_m}};
  json["setting"] = setting_name;
  json["effects"] = nlohmann::ordered_json::object();
  for (EffectKind kind : effectsOn(options.effects))
  {
    const CandidateEffect& effect = candidateEffect(kind);
    const std::vector<double> values = effectValues(kind, options.effects);
    nlohmann::ordered_json entry = nlohmann::ordered_json::object();
    for (std::size_t i = 0; i < values.size(); ++i)
      entry[effect.parameters[i].name] = values[i];
    json["effects"][effect.name] = entry;
  }
  const LeadProfileSpec profile = leadProfileSpec(options.profile);
  json["profile"] = {{"id", std::string(1, profile.id)}, {"name", profile.name}};
  json["seed"] = options.seed;
  json["epoch_step_s"] = options.epoch_step_s;
  json["start_time_unix_s"] = options.start_time_unix_s;
  json["start"] = {{"latitude_deg", options.start_latitude_deg},
                   {"longitude_deg", options.start_longitude_deg},
                   {"altitude_m", options.start_altitude_m},
                   {"heading_rad", options.start_heading_rad}};
  json["geometry"] = {{"leader_antenna_to_rear_bumper_m", options.geometry.leader_antenna_to_rear_bumper_m},
                      {"follower_antenna_to_front_bumper_m", options.geometry.follower_antenna_to_front_bumper_m}};
  const GnssErrorSettings& e = options.errors;
  json["gnss_errors"] = {{"horizontal_sigma_m", e.horizontal_sigma_m},
                         {"vertical_sigma_m", e.vertical_sigma_m},
                         {"position_correlation_time_s", e.position_correlation_time_s},
                         {"speed_sigma_mps", e.speed_sigma_mps}};
  return json.dump(2) + "\n";
}

std::vector<std::string> implausibilityWarnings(const CarFollowingRun& run)
{
  std::size_t collisions = 0, reversing = 0;
  double first_collision_s = 0.0, first_reversing_s = 0.0;
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    if (run.space_gap_m[k] < 0.0 && collisions++ == 0)
      first_collision_s = run.time_s[k];
    if (run.follower_speed_mps[k] < 0.0 && reversing++ == 0)
      first_reversing_s = run.time_s[k];
  }
  std::vector<std::string> warnings;
  std::ostringstream line;
  if (collisions > 0)
  {
    line << "the gap is negative (a collision) in " << collisions << " epochs, first at t = " << first_collision_s
         << " s";
    warnings.push_back(line.str());
  }
  if (reversing > 0)
  {
    line.str("");
    line << "the follower's speed is negative in " << reversing << " epochs, first at t = " << first_reversing_s
         << " s (the receiver reports speed 0 there)";
    warnings.push_back(line.str());
  }
  return warnings;
}

bool chooseParameters(const std::string& setting, const std::array<std::optional<double>, 4>& values,
                      AccParameters* parameters, std::string* setting_name, std::string* error)
{
  static const char* const kOptions[4] = {"--k1", "--k2", "--tau-e", "--eta"};
  double* fields[4] = {&parameters->k1_per_s2, &parameters->k2_per_s, &parameters->tau_e_s, &parameters->eta_m};
  const std::optional<NamedSetting> named = setting.empty() ? std::nullopt : findNamedSetting(setting);
  if (!setting.empty() && !named)
  {
    *error = "unknown setting '" + setting + "'";
    return false;
  }
  if (named)
    *parameters = named->parameters;
  *setting_name = setting;
  for (int i = 0; i < 4; ++i)
  {
    if (values[i])
    {
      *fields[i] = *values[i];
      *setting_name = "custom";
    }
    else if (!named)
    {
      *error = std::string("no value for ") + kOptions[i] + " (give --setting or all of --k1 --k2 --tau-e --eta)";
      return false;
    }
  }
  return true;
}

bool writeSynthesisFiles(const SynthesizedDrive& drive, const SynthesisOptions& options,
                         const std::string& setting_name, const SynthesisFiles& files, std::ostream& log)
{
  for (const std::string& warning : implausibilityWarnings(drive.truth.run))
    log << "warning: " << warning << "\n";
  std::string error;
  std::vector<std::string> written;  // removed again if a later one fails: a drive is whole or absent
  const auto wrote = [&written](bool ok, const std::string& path) {
    if (ok)
      written.push_back(path);
    return ok;
  };
  bool ok = wrote(writeNmeaLog(files.leader_log, drive.leader_fixes, "GN", error), files.leader_log) &&
            wrote(writeNmeaLog(files.follower_log, drive.follower_fixes, "GN", error), files.follower_log);
  if (ok && !files.truth_csv.empty())
    ok = wrote(writeTruthCsv(files.truth_csv, drive.truth.run, &error), files.truth_csv);
  if (ok && !files.parameters_json.empty())
    ok = writeTextFile(synthesisJson(options, setting_name), files.parameters_json, log);
  else if (!ok)
    log << "error: " << error << "\n";
  if (!ok)
  {
    for (const std::string& path : written)
      std::remove(path.c_str());
    if (!written.empty())
      log << "note: the files written before it were removed: a drive is written whole or not at all\n";
  }
  return ok;
}

}  // namespace acc
