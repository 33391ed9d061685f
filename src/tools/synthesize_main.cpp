// synthesize: a realistic pair of NMEA logs (and optionally a bag) of an ACC following a lead
// profile of the paper, with the truth as a canonical CSV and the parameters used as JSON, so that
// the identification pipeline can be checked against known answers.
#include <cmath>
#include <fstream>
#include <iostream>
#include <stdexcept>
#include <string>

#include "acc_identification/command_line.h"
#include "acc_identification/conversion/openacc_to_nmea.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/reproduction/lead_profiles.h"
#include "acc_identification/ros/sentence_bag_writer.h"
#include "acc_identification/synthesis/synthesis.h"
#include "acc_identification/synthesis/synthesis_output.h"


namespace
{
const char* kUsage =
    "usage: synthesize --profile A..I (--setting min|max | --k1 K1 --k2 K2 --tau-e TAU --eta ETA)\n"
    "                  --leader-log LEADER.nmea --follower-log FOLLOWER.nmea [options]\n"
    "  The follower obeys the paper's OVRV model (explicit Euler at 10 Hz); --k1/--k2/--tau-e/--eta\n"
    "  override single values of --setting. Both cars drive along a road of straights and arcs;\n"
    "  each receiver adds its own GNSS errors (Gauss-Markov position error, white speed noise).\n"
    "  --effect NAME=V[,V]      unmodelled effect (repeatable): actuation_lag=T_s, reaction_delay=d_s,\n"
    "                           acceleration_limits=a_max,b_max, sensor_time_offset=delta_s,\n"
    "                           speed_dependent_time_gap=c_s2_per_m, set_speed_cruise=v_set,gain\n"
    "  --seed N                 noise seed (default 1): same options and seed, same bytes\n"
    "  --duration S             keep the first S seconds of the profile (default: all of it)\n"
    "  --truth-csv T.csv        truth as time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n"
    "  --parameters-json P.json parameters, effects and settings used\n"
    "  --bag OUT.bag            also a bag of acc_identification/Sentence on /leader/nmea_sentence\n"
    "                           and /follower/nmea_sentence (as nmea_to_bag does); --compression\n"
    "                           lz4|bz2|none (default lz4)\n"
    "  --start-time 2026-05-12T10:00:00Z  GNSS time of the first epoch (UTC)\n"
    "  --start-lat DEG --start-lon DEG --start-alt M --start-heading-deg DEG   where the road starts\n"
    "  --position-sigma M (0.30) --speed-sigma MPS (0.053) --correlation-time S (20)   GNSS errors\n"
    "  --leader-antenna-to-rear-bumper M (2.6) --follower-antenna-to-front-bumper M (3.0)\n";

constexpr double kDegToRad = 3.14159265358979323846 / 180.0;

/// The ACC parameters from --setting and the single overrides; "" and a message when incomplete.
bool readParameters(acc::CommandLine& cli, acc::AccParameters* p, std::string* setting_name, std::string* error)
{
  bool have[4] = {false, false, false, false};
  if (auto setting = cli.value("setting"))
  {
    const auto named = acc::findNamedSetting(*setting);
    if (!named)
    {
      *error = "unknown --setting '" + *setting + "' (min, max, fig2-unstable, fig2-stable)";
      return false;
    }
    *p = named->parameters;
    *setting_name = *setting;
    have[0] = have[1] = have[2] = have[3] = true;
  }
  const char* names[4] = {"k1", "k2", "tau-e", "eta"};
  double* fields[4] = {&p->k1_per_s2, &p->k2_per_s, &p->tau_e_s, &p->eta_m};
  for (int i = 0; i < 4; ++i)
  {
    if (auto value = cli.number(names[i]))
    {
      *fields[i] = *value;
      have[i] = true;
      *setting_name = "custom";
    }
  }
  if (!cli.error().empty())
  {
    *error = cli.error();
    return false;
  }
  for (int i = 0; i < 4; ++i)
    if (!have[i])
    {
      *error = std::string("no value for --") + names[i] + " (give --setting or all of --k1 --k2 --tau-e --eta)";
      return false;
    }
  return true;
}

bool readOptions(acc::CommandLine& cli, acc::SynthesisOptions* options, std::string* setting_name, std::string* error)
{
  const std::string profile = cli.value("profile").value_or("");
  if (profile.size() != 1 || !acc::isLeadProfileId(profile[0]))
  {
    *error = "--profile must be one of A..I";
    return false;
  }
  options->profile = static_cast<char>(std::toupper(static_cast<unsigned char>(profile[0])));
  if (!readParameters(cli, &options->parameters, setting_name, error))
    return false;
  for (const std::string& effect : cli.values("effect"))
    if (!acc::addEffectOption(effect, &options->effects, error))
      return false;
  if (auto seed = cli.value("seed"))
  {
    try
    {
      std::size_t used = 0;
      options->seed = std::stoull(*seed, &used);
      if (used != seed->size() || (*seed)[0] == '-')
        throw std::invalid_argument("trailing characters");
    }
    catch (const std::exception&)
    {
      *error = "--seed '" + *seed + "' is not a non-negative integer";
      return false;
    }
  }
  if (auto start = cli.value("start-time"); start && !acc::parseUtcTime(*start, &options->start_time_unix_s))
  {
    *error = "--start-time '" + *start + "' is not YYYY-MM-DDThh:mm:ss[Z] (UTC)";
    return false;
  }
  auto set = [&cli](const char* name, double* field, double scale = 1.0) {
    if (auto value = cli.number(name))
      *field = *value * scale;
  };
  set("duration", &options->duration_s);
  set("start-lat", &options->start_latitude_deg);
  set("start-lon", &options->start_longitude_deg);
  set("start-alt", &options->start_altitude_m);
  set("start-heading-deg", &options->start_heading_rad, kDegToRad);
  set("position-sigma", &options->errors.horizontal_sigma_m);
  set("speed-sigma", &options->errors.speed_sigma_mps);
  set("correlation-time", &options->errors.position_correlation_time_s);
  set("leader-antenna-to-rear-bumper", &options->geometry.leader_antenna_to_rear_bumper_m);
  set("follower-antenna-to-front-bumper", &options->geometry.follower_antenna_to_front_bumper_m);
  if (!cli.error().empty())
  {
    *error = cli.error();
    return false;
  }
  if (options->errors.horizontal_sigma_m < 0.0 || options->errors.speed_sigma_mps < 0.0 ||
      options->errors.position_correlation_time_s < 0.0 || options->duration_s < 0.0 ||
      std::abs(options->start_latitude_deg) > 89.0 || std::abs(options->start_longitude_deg) > 180.0)
  {
    *error = "sigmas, correlation time and duration must not be negative; --start-lat within +-89, --start-lon +-180";
    return false;
  }
  return true;
}

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

int run(acc::CommandLine& cli)
{
  acc::SynthesisOptions options;
  std::string setting_name, error;
  const auto leader_log = cli.value("leader-log");
  const auto follower_log = cli.value("follower-log");
  if (!leader_log || !follower_log)
    error = "--leader-log and --follower-log are required";
  if (!error.empty() || !readOptions(cli, &options, &setting_name, &error))
  {
    std::cerr << "error: " << error << "\n" << kUsage;
    return 2;
  }
  const acc::SynthesizedDrive drive = acc::synthesizeDrive(options);
  if (drive.truth.diverged)
  {
    std::cerr << "error: the follower's simulation diverged with these parameters; nothing written\n";
    return 1;
  }
  warnImplausible(drive.truth.run);
  bool ok = acc::writeNmeaLog(*leader_log, drive.leader_fixes, "GN", error) &&
            acc::writeNmeaLog(*follower_log, drive.follower_fixes, "GN", error);
  if (ok && cli.has("truth-csv"))
    ok = acc::writeTruthCsv(*cli.value("truth-csv"), drive.truth.run, &error);
  if (ok && cli.has("parameters-json"))
    ok = writeText(*cli.value("parameters-json"), acc::synthesisJson(options, setting_name), &error);
  if (!ok)
  {
    std::cerr << "error: " << error << "\n";
    return 1;
  }
  std::cout << "synthesize: profile " << options.profile << ", setting " << setting_name << ", seed " << options.seed
            << ": " << drive.truth.run.size() << " epochs (" << drive.truth.run.durationS() << " s) -> " << *leader_log
            << ", " << *follower_log << "\n";
  if (auto bag = cli.value("bag"))
  {
    // The bag is made from the logs just written, so that it holds exactly their lines.
    std::vector<acc::SentenceStream> streams{{"/leader/nmea_sentence", "leader_gnss", {}},
                                             {"/follower/nmea_sentence", "follower_gnss", {}}};
    const std::string* logs[2] = {&*leader_log, &*follower_log};
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
    const auto summary = acc::writeSentenceBag(*bag, streams, cli.value("compression").value_or("lz4"));
    std::cout << "synthesize: " << summary.messages << " sentences -> " << *bag << "\n";
  }
  return 0;
}
}  // namespace

int main(int argc, char** argv)
{
  acc::CommandLine cli({"profile", "setting", "k1", "k2", "tau-e", "eta", "effect", "seed", "duration", "leader-log",
                        "follower-log", "truth-csv", "parameters-json", "bag", "compression", "start-time", "start-lat",
                        "start-lon", "start-alt", "start-heading-deg", "position-sigma", "speed-sigma",
                        "correlation-time", "leader-antenna-to-rear-bumper", "follower-antenna-to-front-bumper"},
                       {"help"});
  if (!cli.parse(argc, argv) || cli.has("help") || !cli.positional().empty())
  {
    std::cerr << (cli.error().empty() ? (cli.positional().empty() ? "" : "error: unexpected argument '" +
                                                                              cli.positional().front() + "'\n")
                                      : "error: " + cli.error() + "\n")
              << kUsage;
    return cli.has("help") ? 0 : 2;
  }
  try
  {
    return run(cli);
  }
  catch (const std::exception& e)
  {
    std::cerr << "error: " << e.what() << "\n";
    return 1;
  }
}
