// synthesize: a realistic pair of NMEA logs (and optionally a bag) of an ACC following a lead
// profile of the paper, with the truth as a canonical CSV and the parameters used as JSON, so that
// the identification pipeline can be checked against known answers.
#include <cmath>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>

#include <CLI/CLI.hpp>

#include "acc_identification/conversion/openacc_to_nmea.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/reproduction/lead_profiles.h"
#include "acc_identification/ros/sentence_bag_writer.h"
#include "acc_identification/synthesis/synthesis.h"
#include "acc_identification/synthesis/synthesis_output.h"


namespace
{
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

/// Parameters far from a real ACC can make the follower drive into the leader or backwards; the
/// files are still written (they may be wanted for tests) but the user is told, with counts.
void warnImplausible(const acc::CarFollowingRun& run)
{
  std::size_t collisions = 0, reversing = 0;
  double first_collision_s = -1.0, first_reversing_s = -1.0;
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    if (run.space_gap_m[k] < 0.0 && collisions++ == 0)
      first_collision_s = run.time_s[k];
    if (run.follower_speed_mps[k] < 0.0 && reversing++ == 0)
      first_reversing_s = run.time_s[k];
  }
  if (collisions > 0)
    std::cerr << "warning: the gap is negative (a collision) in " << collisions << " epochs, first at t = "
              << first_collision_s << " s\n";
  if (reversing > 0)
    std::cerr << "warning: the follower's speed is negative in " << reversing << " epochs, first at t = "
              << first_reversing_s << " s (the receiver reports speed 0 there)\n";
}

bool writeText(const std::string& path, const std::string& text, std::string* error)
{
  std::ofstream out(path);
  out << text;
  out.flush();
  if (!out)
    *error = "cannot write " + path;
  return static_cast<bool>(out);
}

/// What the command line asks for, beyond SynthesisOptions.
struct Outputs
{
  std::string leader_log, follower_log, truth_csv, parameters_json, bag, compression = "lz4";
};

int run(const acc::SynthesisOptions& options, const std::string& setting_name, const Outputs& out)
{
  std::string error;
  const acc::SynthesizedDrive drive = acc::synthesizeDrive(options);
  if (drive.truth.diverged)
  {
    std::cerr << "error: the follower's simulation diverged with these parameters; nothing written\n";
    return 1;
  }
  warnImplausible(drive.truth.run);
  bool ok = acc::writeNmeaLog(out.leader_log, drive.leader_fixes, "GN", error) &&
            acc::writeNmeaLog(out.follower_log, drive.follower_fixes, "GN", error);
  if (ok && !out.truth_csv.empty())
    ok = acc::writeTruthCsv(out.truth_csv, drive.truth.run, &error);
  if (ok && !out.parameters_json.empty())
    ok = writeText(out.parameters_json, acc::synthesisJson(options, setting_name), &error);
  if (!ok)
  {
    std::cerr << "error: " << error << "\n";
    return 1;
  }
  std::cout << "synthesize: profile " << options.profile << ", setting " << setting_name << ", seed " << options.seed
            << ": " << drive.truth.run.size() << " epochs (" << drive.truth.run.durationS() << " s) -> "
            << out.leader_log << ", " << out.follower_log << "\n";
  if (!out.bag.empty())
  {
    // The bag is made from the logs just written, so that it holds exactly their lines.
    std::vector<acc::SentenceStream> streams{{"/leader/nmea_sentence", "leader_gnss", {}},
                                             {"/follower/nmea_sentence", "follower_gnss", {}}};
    const std::string* logs[2] = {&out.leader_log, &out.follower_log};
    for (int i = 0; i < 2; ++i)
    {
      acc::TimedNmeaLog timed = acc::readTimedNmeaLog(*logs[i]);
      if (!timed.error.empty())
      {
        std::cerr << "error: " << timed.error << "\n";
        return 1;
      }
      streams[i].lines = std::move(timed.lines);
    }
    const auto summary = acc::writeSentenceBag(out.bag, streams, out.compression);
    std::cout << "synthesize: " << summary.messages << " sentences -> " << out.bag << "\n";
  }
  return 0;
}
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"A realistic pair of NMEA logs (and optionally a bag) of an ACC following a lead profile of the "
               "paper, with the truth as a canonical CSV and the parameters as JSON. The follower obeys the paper's "
               "OVRV model; both cars drive along a road of straights and arcs; each receiver adds its own GNSS "
               "errors (Gauss-Markov position error, white speed noise). Same options and seed, same bytes."};
  acc::SynthesisOptions options;
  Outputs out;
  std::string profile, setting, start_time;
  std::vector<std::string> effects;
  double overrides[4] = {0, 0, 0, 0};
  double heading_deg = options.start_heading_rad / kDegToRad;
  std::vector<std::string> setting_names;
  for (const auto& named : acc::namedSettings())
    setting_names.push_back(named.name);
  app.add_option("--profile", profile, "lead profile of the paper, A..I")
      ->required()
      ->check(CLI::IsMember({"A", "B", "C", "D", "E", "F", "G", "H", "I"}, CLI::ignore_case));
  auto* setting_option = app.add_option("--setting", setting, "named parameter set")->check(CLI::IsMember(setting_names));
  const char* names[4] = {"--k1", "--k2", "--tau-e", "--eta"};
  CLI::Option* override_options[4];
  for (int i = 0; i < 4; ++i)
    override_options[i] = app.add_option(names[i], overrides[i], "overrides one value of --setting (or give all four)");
  app.add_option("--effect", effects,
                 "unmodelled effect NAME=V[,V] (repeatable): actuation_lag=T_s, reaction_delay=d_s, "
                 "acceleration_limits=a_max,b_max, sensor_time_offset=delta_s, speed_dependent_time_gap=c_s2_per_m, "
                 "set_speed_cruise=v_set,gain");
  app.add_option("--seed", options.seed, "noise seed")->capture_default_str();
  app.add_option("--duration", options.duration_s, "keep the first S seconds of the profile (0: all of it)")
      ->check(CLI::NonNegativeNumber);
  app.add_option("--leader-log", out.leader_log, "leader's NMEA log to write")->required();
  app.add_option("--follower-log", out.follower_log, "follower's NMEA log to write")->required();
  app.add_option("--truth-csv", out.truth_csv, "truth as time_s,space_gap_m,follower_speed_mps,leader_speed_mps");
  app.add_option("--parameters-json", out.parameters_json, "parameters, effects and settings used");
  app.add_option("--bag", out.bag, "also a bag of acc_identification/Sentence on /leader and /follower/nmea_sentence");
  app.add_option("--compression", out.compression, "of the bag")
      ->check(CLI::IsMember({"lz4", "bz2", "none"}))
      ->capture_default_str();
  app.add_option("--start-time", start_time, "GNSS time of the first epoch, YYYY-MM-DDThh:mm:ss[Z] (UTC)");
  app.add_option("--start-lat", options.start_latitude_deg, "where the road starts [deg]")
      ->check(CLI::Range(-89.0, 89.0))
      ->capture_default_str();
  app.add_option("--start-lon", options.start_longitude_deg, "[deg]")->check(CLI::Range(-180.0, 180.0))->capture_default_str();
  app.add_option("--start-alt", options.start_altitude_m, "[m]")->capture_default_str();
  auto* heading_option = app.add_option("--start-heading-deg", heading_deg, "[deg]")->capture_default_str();
  app.add_option("--position-sigma", options.errors.horizontal_sigma_m, "GNSS position error [m]")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--speed-sigma", options.errors.speed_sigma_mps, "GNSS speed error [m/s]")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--correlation-time", options.errors.position_correlation_time_s, "of the position error [s]")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  app.add_option("--leader-antenna-to-rear-bumper", options.geometry.leader_antenna_to_rear_bumper_m, "[m]")
      ->capture_default_str();
  app.add_option("--follower-antenna-to-front-bumper", options.geometry.follower_antenna_to_front_bumper_m, "[m]")
      ->capture_default_str();
  CLI11_PARSE(app, argc, argv);

  // The parameters: a named setting, single values overriding it, or all four values.
  std::string setting_name = setting;
  bool have[4] = {false, false, false, false};
  if (setting_option->count() > 0)
  {
    options.parameters = acc::findNamedSetting(setting)->parameters;
    have[0] = have[1] = have[2] = have[3] = true;
  }
  double* fields[4] = {&options.parameters.k1_per_s2, &options.parameters.k2_per_s, &options.parameters.tau_e_s,
                       &options.parameters.eta_m};
  for (int i = 0; i < 4; ++i)
    if (override_options[i]->count() > 0)
    {
      *fields[i] = overrides[i];
      have[i] = true;
      setting_name = "custom";
    }
  for (int i = 0; i < 4; ++i)
    if (!have[i])
    {
      std::cerr << "error: no value for " << names[i] << " (give --setting or all of --k1 --k2 --tau-e --eta)\n";
      return 2;
    }
  options.profile = static_cast<char>(std::toupper(static_cast<unsigned char>(profile[0])));
  if (heading_option->count() > 0)
    options.start_heading_rad = heading_deg * kDegToRad;  // the default stays exactly as the library has it
  std::string error;
  for (const std::string& effect : effects)
    if (!acc::addEffectOption(effect, &options.effects, &error))
    {
      std::cerr << "error: " << error << "\n";
      return 2;
    }
  if (!start_time.empty() && !acc::parseUtcTime(start_time, &options.start_time_unix_s))
  {
    std::cerr << "error: --start-time '" << start_time << "' is not YYYY-MM-DDThh:mm:ss[Z] (UTC)\n";
    return 2;
  }
  try
  {
    return run(options, setting_name, out);
  }
  catch (const std::exception& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
