// synthesize: a realistic pair of NMEA logs (and optionally a bag) of an ACC following a lead
// profile of the paper, with the truth as a canonical CSV and the parameters used as JSON, so that
// the identification pipeline can be checked against known answers.
#include <array>
#include <cmath>
#include <iostream>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "acc_identification/conversion/openacc_to_nmea.h"
#include "acc_identification/io/output_files.h"
#include "acc_identification/model/angles.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/reproduction/lead_profiles.h"
#include "acc_identification/ros/sentence_bag_writer.h"
#include "acc_identification/synthesis/synthesis.h"
#include "acc_identification/synthesis/synthesis_output.h"
#include "acc_identification/tools/number_checks.h"

namespace
{
/// What the command line asks for, beyond SynthesisOptions.
struct Outputs
{
  acc::SynthesisFiles files;
  std::string bag, compression = "lz4";
};

int run(const acc::SynthesisOptions& options, const std::string& setting_name, const Outputs& out)
{
  const acc::SynthesizedDrive drive = acc::synthesizeDrive(options);
  if (drive.truth.diverged)
  {
    std::cerr << "error: the follower's simulation diverged with these parameters; nothing written\n";
    return 1;
  }
  if (!acc::writeSynthesisFiles(drive, options, setting_name, out.files, std::cerr))
    return 1;
  std::cout << "synthesize: profile " << options.profile << ", setting " << setting_name << ", seed " << options.seed
            << ": " << drive.truth.run.size() << " epochs (" << drive.truth.run.durationS() << " s) -> "
            << out.files.leader_log << ", " << out.files.follower_log << "\n";
  if (out.bag.empty())
    return 0;
  // The bag is made from the logs just written, so that it holds exactly their lines.
  std::vector<acc::SentenceStream> streams = acc::leaderFollowerStreams();
  const std::string error = acc::loadSentenceStreams({out.files.leader_log, out.files.follower_log},
                                                     acc::NmeaLineTiming{}, streams, std::cerr);
  if (!error.empty())
  {
    std::cerr << "error: " << error << "\n";
    return 1;
  }
  const auto summary = acc::writeSentenceBag(out.bag, streams, out.compression);
  std::cout << "synthesize: " << summary.messages << " sentences -> " << out.bag << "\n";
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
  double heading_deg = options.start_heading_rad / acc::kDegToRad;
  std::vector<std::string> setting_names;
  for (const auto& named : acc::namedSettings())
    setting_names.push_back(named.name);
  app.add_option("--profile", profile, "lead profile of the paper, A..I")
      ->required()
      ->check(CLI::IsMember({"A", "B", "C", "D", "E", "F", "G", "H", "I"}, CLI::ignore_case));
  app.add_option("--setting", setting, "named parameter set")->check(CLI::IsMember(setting_names));
  const char* names[4] = {"--k1", "--k2", "--tau-e", "--eta"};
  CLI::Option* override_options[4];
  for (int i = 0; i < 4; ++i)
    override_options[i] = app.add_option(names[i], overrides[i], "overrides one value of --setting (or give all four)")
                              ->check(i < 3 ? acc::modelGainOrTimeGap() : acc::finiteNumber("NUMBER"));
  app.add_option("--effect", effects,
                 "unmodelled effect NAME=V[,V] (repeatable): actuation_lag=T_s, reaction_delay=d_s, "
                 "acceleration_limits=a_max,b_max, sensor_time_offset=delta_s, speed_dependent_time_gap=c_s2_per_m, "
                 "set_speed_cruise=v_set,gain");
  app.add_option("--seed", options.seed, "noise seed")->check(acc::nonNegativeWholeNumber())->capture_default_str();
  double rate_hz = 1.0 / options.epoch_step_s;
  auto* rate_option = app.add_option("--rate-hz", rate_hz, "the receivers' output rate, GGA + RMC epochs per second (1: "
                                     "many receivers' default; the truth is simulated ten times finer; calibrate such "
                                     "data with --max-gap above the step)")->check(acc::closedInterval(0.2, 50.0, "HZ"))->capture_default_str();
  app.add_option("--duration", options.duration_s, "keep the first S seconds of the profile (0: all of it)")
      ->check(acc::nonNegativeNumber());
  app.add_option("--leader-log", out.files.leader_log, "leader's NMEA log to write")->required();
  app.add_option("--follower-log", out.files.follower_log, "follower's NMEA log to write")->required();
  app.add_option("--truth-csv", out.files.truth_csv, "truth as time_s,space_gap_m,follower_speed_mps,leader_speed_mps");
  app.add_option("--parameters-json", out.files.parameters_json, "parameters, effects and settings used");
  app.add_option("--bag", out.bag, "also a bag of acc_identification/Sentence on /leader and /follower/nmea_sentence");
  app.add_option("--compression", out.compression, "of the bag")
      ->check(CLI::IsMember({"lz4", "bz2", "none"}))->capture_default_str();
  app.add_option("--start-time", start_time, "GNSS time of the first epoch, YYYY-MM-DDThh:mm:ss[Z] (UTC)");
  app.add_option("--start-lat", options.start_latitude_deg, "where the road starts [deg]")
      ->check(acc::closedInterval(-89.0, 89.0, "DEGREES"))->capture_default_str();
  app.add_option("--start-lon", options.start_longitude_deg, "[deg]")->check(acc::closedInterval(-180.0, 180.0, "DEGREES"))->capture_default_str();
  app.add_option("--start-alt", options.start_altitude_m, "[m]")
      ->check(acc::finiteNumber("METRES"))->capture_default_str();
  auto* heading_option = app.add_option("--start-heading-deg", heading_deg, "[deg]")
                             ->check(acc::finiteNumber("DEGREES"))->capture_default_str();
  app.add_option("--position-sigma", options.errors.horizontal_sigma_m, "GNSS position error [m]")
      ->check(acc::nonNegativeNumber())->capture_default_str();
  app.add_option("--speed-sigma", options.errors.speed_sigma_mps, "GNSS speed error [m/s]")
      ->check(acc::nonNegativeNumber())->capture_default_str();
  app.add_option("--correlation-time", options.errors.position_correlation_time_s, "of the position error [s]")
      ->check(acc::nonNegativeNumber())->capture_default_str();
  acc::AntennaOffsets antennas{NAN, options.geometry.leader_antenna_to_rear_bumper_m,
                               options.geometry.follower_antenna_to_front_bumper_m};
  app.add_option("--leader-antenna-to-rear-bumper", antennas.leader_antenna_to_rear_bumper_m, "[m]")
      ->check(acc::finiteNumber("METRES"))->capture_default_str();
  app.add_option("--follower-antenna-to-front-bumper", antennas.follower_antenna_to_front_bumper_m, "[m]")
      ->check(acc::finiteNumber("METRES"))->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  if (!acc::outputsLeaveInputsAlone(
          {}, {out.files.leader_log, out.files.follower_log, out.files.truth_csv, out.files.parameters_json, out.bag},
          std::cerr))
    return 2;

  std::array<std::optional<double>, 4> given;
  for (int i = 0; i < 4; ++i)
    if (override_options[i]->count() > 0)
      given[i] = overrides[i];
  std::string setting_name, error = acc::geometryFromOffsets(antennas, options.geometry);
  if (error.empty())
    acc::chooseParameters(setting, given, &options.parameters, &setting_name, &error);
  for (const std::string& effect : effects)
    if (error.empty())
      acc::addEffectOption(effect, &options.effects, &error);
  if (error.empty() && !start_time.empty())
    error = acc::readStartTime(start_time, &options.start_time_unix_s);
  if (!error.empty())
  {
    std::cerr << "error: " << error << "\n";
    return 2;
  }
  options.profile = static_cast<char>(std::toupper(static_cast<unsigned char>(profile[0])));
  if (rate_option->count() > 0)
    options.epoch_step_s = 1.0 / rate_hz;  // the default stays exactly the library's 0.1 s
  if (heading_option->count() > 0)
    options.start_heading_rad = heading_deg * acc::kDegToRad;  // the default stays exactly as the library has it
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
