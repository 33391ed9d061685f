// sumo_replay: replays a run's real leader in SUMO (headless, TraCI) with an exported vType behind
// it, and reports SUMO's follower against the package's own simulation and the measured car; with
// several --id, a platoon of those vTypes behind the leader, dips by position (docs/SUMO.md).
#include <fstream>
#include <iostream>

#include <CLI/CLI.hpp>

#include "acc_identification/campaign/campaign_sumo_platoon.h"
#include "acc_identification/io/installed_beside.h"
#include "acc_identification/io/output_files.h"
#include "acc_identification/ros/run_bag_reader.h"
#include "acc_identification/sumo/sumo_replay_report.h"
#include "acc_identification/tools/number_checks.h"

int main(int argc, char** argv)
{
  CLI::App app{"Replays a run's leader in SUMO with an identified ACC's vType behind it (or a platoon of vTypes) "
               "and compares SUMO with the package's simulation and the measured car."};
  std::string path, vtype_file, json_path, follower, topic = "relative_state";
  std::vector<std::string> ids, listings;
  acc::SumoReplayOptions options;
  double max_gap_s = 0.5;
  bool platoon = false, diagnosed = false;
  app.add_option("RUN", path, "a canonical CSV, an OpenACC CSV or a bag of RelativeState")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("--vtype", vtype_file, "SUMO additional file with the vType(s) (calibrate/diagnose/campaign "
                                        "--sumo-vtype)")
      ->required()
      ->check(CLI::ExistingFile);
  auto* id_option = app.add_option("--id", ids, "the vType to replay (default: the file's first ACC vType); "
                                                "several: a platoon in this order behind the run's leader");
  app.add_option("--json", json_path, "write the comparison as JSON");
  auto* platoon_flag = app.add_flag("--platoon", platoon,
               "RUN is an OpenACC platoon file: replay its first car with every following car's vType "
               "(<VEHICLE>_<setting>, as campaign --sumo-vtype names them) behind it, from the measured starts; "
               "dips by position in SUMO, the package's chain and the real cars");
  // Options of one mode only are refused in the other, where they were silently ignored.
  app.add_flag("--diagnosed", diagnosed,
               "with --platoon: each car's <VEHICLE>_<setting>_diagnosed vType (the platoon diagnosis's model) "
               "where the file has one")
      ->needs(platoon_flag);
  app.add_option("--listing", listings,
                 "with --platoon: the database's listing of mixed-setting runs (header 'filename,Long timegap "
                 "setting'), so that each car of a listed mixed run gets its own setting's vType")
      ->check(CLI::ExistingFile)
      ->needs(platoon_flag);
  platoon_flag->excludes(id_option);
  platoon_flag->excludes(app.add_option("--follower", follower,
                                        "OpenACC files: the follower of the pair to read (its leader is replayed)"));
  platoon_flag->excludes(app.add_option("--topic", topic, "RelativeState topic in bags")->capture_default_str());
  platoon_flag->excludes(app.add_option("--max-gap", max_gap_s, "split runs at holes longer than this [s]")
                             ->check(acc::positiveNumber())
                             ->capture_default_str());
  app.add_option("--keep", options.work_dir, "keep SUMO's scenario, trace and log in this folder");
  app.add_option("--sumo", options.sumo, "the SUMO binary")->capture_default_str();
  CLI11_PARSE(app, argc, argv);
  std::vector<std::string> inputs = listings;
  inputs.insert(inputs.end(), {path, vtype_file});
  if (!acc::outputsLeaveInputsAlone(inputs, {json_path}, std::cerr))
    return 2;
  options.driver_script = acc::installedBeside("sumo_traci_replay.py");
  try
  {
    nlohmann::json json;
    if (platoon)
    {
      json = acc::replayFilePlatoonInSumo(path, listings, vtype_file, diagnosed, options, std::cout, std::cerr);
    }
    else
    {
      acc::BagTopics topics;  // the ACC's engagement reports read as calibrate reads them by default
      topics.relative_state = topic;
      const acc::RunArgument argument =
          acc::readRunArgument(path, topics, max_gap_s, std::cerr, acc::pairSelectorFromOptions(follower, false));
      json = acc::replayRunInSumo(argument.runs, vtype_file, ids, options, std::cout);
    }
    if (!json_path.empty() && !(std::ofstream(json_path) << json.dump(2) << "\n"))
    {
      std::cerr << "error: cannot write " << json_path << "\n";
      return 1;
    }
  }
  catch (const std::exception& failure)
  {
    std::cerr << "error: " << failure.what() << "\n";
    return 1;
  }
  return 0;
}
