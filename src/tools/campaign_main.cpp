// campaign: every car of a set of OpenACC platoon runs identified per (vehicle, distance setting)
// with the paper's protocol, in parallel, and each run's platoon predicted from its real first car
// with models fitted without that run: where does the model's string (in)stability match the data?
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "acc_identification/campaign/campaign.h"
#include "acc_identification/campaign/campaign_output.h"
#include "acc_identification/campaign/campaign_sumo_export.h"
#include "acc_identification/io/installed_beside.h"
#include "acc_identification/io/output_files.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/tools/bootstrap_options.h"
#include "acc_identification/tools/number_checks.h"
#include "acc_identification/tools/option_rules.h"

namespace
{
/// report.md, campaign.json and (unless no_plots) the figures in DIR.
bool writeReport(const std::string& dir, const nlohmann::json& json, const acc::CampaignInputs& inputs,
                 const acc::CampaignResult& result, const std::vector<std::string>& paths, bool no_plots,
                 const std::string& plot_script)
{
  return acc::makeOutputFolder(dir, std::cerr) && acc::writeJsonFile(json, dir + "/campaign.json", std::cerr) &&
         acc::writeTextFile(acc::campaignReportMarkdown(inputs, result, paths, !no_plots), dir + "/report.md", std::cerr) &&
         (no_plots || acc::drawReportFigures(plot_script, dir, "tables and JSON", std::cerr));
}
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Identifies every car of OpenACC platoon runs per (vehicle, distance setting) with the paper's protocol "
               "(fit, standard errors, what the data determine, string-stability test on held-out halves), in "
               "parallel, and predicts each run's platoon from its real first car with models fitted without that "
               "run."};
  std::vector<std::string> paths;
  std::string json_path, report_dir, plot_script = acc::installedBeside("plot_campaign.py");
  acc::CampaignOptions options;
  bool quiet = false, no_platoon_check = false, no_plots = false;
  app.add_option("FILE_OR_DIR", paths, "OpenACC CSV files, or folders: every *.csv OpenACC file in them")
      ->required()
      ->check(CLI::ExistingPath);
  app.add_option("--starts", options.group.starts, "Halton starts of every multistart fit (at least one)")
      ->check(acc::multistartStarts())
      ->capture_default_str();
  app.add_option("--threads", options.threads, "worker threads (0: every core)")
      ->check(acc::nonNegativeWholeNumber())
      ->capture_default_str();
  app.add_option("--alpha", options.group.alpha, "level of the string-stability test")
      ->check(acc::testLevel())
      ->capture_default_str();
  app.add_option("--seed", options.group.seed, "campaign seed (each group's bootstrap draws from its own stream)")
      ->check(acc::nonNegativeWholeNumber())
      ->capture_default_str();
  app.add_option("--json", json_path, "write vehicles, platoons, inputs and attribution as JSON");
  app.add_option("--report", report_dir, "write report.md, campaign.json and PNG figures into DIR");
  app.add_option("--plot-script", plot_script, "figure script")->capture_default_str();
  std::string sumo_vtype_path;
  app.add_option("--sumo-vtype", sumo_vtype_path,
                 "also write every fitted car (and setting) as a SUMO vType into this additional file");
  app.add_flag("--no-platoon-check", no_platoon_check, "identify the cars only");
  app.add_flag("--no-plots", no_plots, "write the report's tables and JSON but draw nothing");
  app.add_flag("--quiet", quiet, "no progress bar");
  bool no_platoon_diagnosis = false;
  std::string platoon_effects;
  app.add_flag("--no-platoon-diagnosis", no_platoon_diagnosis,
               "predict the platoons with the base models only (no candidate effects fitted)");
  app.add_option("--platoon-effects", platoon_effects,
                 "use this candidate for the diagnosed platoon (e.g. asymmetric_response,reaction_delay or "
                 "reaction_delay@speed_and_gap; none: the base model) instead of the rule's choice; the comparisons "
                 "are still reported");
  options.group.bootstrap.replicates = acc::RefitBootstrapOptions{}.replicates;
  acc::addRefitBootstrapOptions(app, options.group.bootstrap.replicates, options.group.bootstrap.below_s,
                                "each car's fit and diagnosed model");
  CLI11_PARSE(app, argc, argv);
  if (!acc::outputsLeaveInputsAlone(paths, {json_path, sumo_vtype_path}, std::cerr))
    return 2;
  options.platoon_check = !no_platoon_check;
  if (!quiet)
    options.progress = acc::showProgress;
  options.platoon_diagnosis = !no_platoon_diagnosis;
  if (!platoon_effects.empty())
  {
    options.effect_selection.force = true;
    if (!acc::parsePlatoonCandidate(platoon_effects, &options.effect_selection.forced))
    {
      std::cerr << "error: --platoon-effects: cannot read '" << platoon_effects
                << "' (effect names joined by commas, optionally @speed, @gap, @speed_and_gap or @speed_and_windows)\n";
      return 2;
    }
    // Said before the fits, not after a minute of them.
    if (!acc::isPlatoonCandidate(options.effect_selection.forced))
    {
      std::cerr << "error: --platoon-effects: " << options.effect_selection.forced.name()
                << " is not among the platoon diagnosis's candidates:";
      for (const acc::PlatoonCandidate& candidate : acc::platoonCandidates())
        std::cerr << (&candidate == &acc::platoonCandidates().front() ? " " : ", ") << acc::platoonCandidateText(candidate);
      std::cerr << "\n";
      return 2;
    }
  }

  acc::CampaignInputs inputs;
  try
  {
    inputs = acc::loadCampaign(paths);
  }
  catch (const std::exception& error)
  {
    std::cerr << "error: " << error.what() << "\n";
    return 1;
  }
  for (const std::string& note : inputs.notes)
    std::cerr << "note: " << note << "\n";
  if (!quiet)
    std::cerr << inputs.files.size() << " file(s), " << inputs.groups.size() << " (vehicle, setting) group(s); "
              << inputs.describeSkipped() << "\n";
  acc::CampaignResult result;
  try
  {
    result = acc::runCampaign(inputs, options);
  }
  catch (const std::exception& error)
  {
    std::cerr << "error: " << error.what() << "\n";
    return 1;
  }
  if (!quiet)
    std::fprintf(stderr, "done in %.1f s on %zu thread(s)\n", result.wall_time_s, result.threads);
  acc::printCampaignTables(result, std::cout);
  const nlohmann::json json = acc::campaignToJson(inputs, result, paths, options);
  if (!json_path.empty() && !acc::writeJsonFile(json, json_path, std::cerr))
    return 1;
  if (!sumo_vtype_path.empty() && !acc::saveSumoVTypes(acc::campaignSumoExports(inputs, result), sumo_vtype_path,
                                                        acc::kSumoOpenAccProvenance, std::cerr))
    return 1;
  return report_dir.empty() || writeReport(report_dir, json, inputs, result, paths, no_plots, plot_script) ? 0 : 1;
}
