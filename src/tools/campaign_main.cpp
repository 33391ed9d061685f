// campaign: every car of a set of OpenACC platoon runs identified per (vehicle, distance setting)
// with the paper's protocol, in parallel, and each run's platoon predicted from its real first car
// with models fitted without that run: where does the model's string (in)stability match the data?
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <mutex>
#include <sstream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "acc_identification/campaign/campaign.h"
#include "acc_identification/campaign/campaign_output.h"
#include "acc_identification/campaign/campaign_sumo_export.h"
#include "acc_identification/io/installed_beside.h"
#include "acc_identification/io/run_csv.h"

namespace
{
/// A progress bar on stderr: redrawn in place on a terminal, a line per tenth otherwise.
void showProgress(const std::string& stage, std::size_t done, std::size_t total)
{
  static const bool terminal = isatty(STDERR_FILENO) != 0;
  constexpr std::size_t kWidth = 30;
  if (terminal)
  {
    const std::size_t filled = total > 0 ? kWidth * done / total : kWidth;
    std::fprintf(stderr, "\r%-13s [%s%s] %zu/%zu", stage.c_str(), std::string(filled, '#').c_str(),
                 std::string(kWidth - filled, '.').c_str(), done, total);
    if (done == total)
      std::fprintf(stderr, "\n");
  }
  else if (done == total || (total >= 10 && done % (total / 10) == 0))
  {
    std::fprintf(stderr, "%s: %zu/%zu done\n", stage.c_str(), done, total);
  }
}

bool writeText(const std::string& text, const std::string& path)
{
  std::ofstream out(path);
  out << text;
  if (!out)
  {
    std::cerr << "error: cannot write " << path << "\n";
    return false;
  }
  return true;
}

/// report.md, campaign.json and (unless no_plots) the figures in DIR.
int writeReport(const std::string& dir, const nlohmann::json& json, const acc::CampaignResult& result,
                const std::vector<std::string>& paths, bool no_plots, const std::string& plot_script)
{
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error)
  {
    std::cerr << "error: cannot create " << dir << ": " << error.message() << "\n";
    return 1;
  }
  if (!writeText(json.dump(2) + "\n", dir + "/campaign.json") ||
      !writeText(acc::campaignReportMarkdown(result, paths, !no_plots), dir + "/report.md"))
    return 1;
  if (no_plots)
    return 0;
  if (!std::filesystem::exists(plot_script))
  {
    std::cerr << "error: no figure script at " << plot_script << " (--plot-script, or --no-plots); tables and JSON are in "
              << dir << "\n";
    return 1;
  }
  const std::string command = "/usr/bin/python3 '" + plot_script + "' '" + dir + "'";
  if (std::system(command.c_str()) != 0)
  {
    std::cerr << "error: the report figures failed (" << command << "); tables and JSON are in " << dir << "\n";
    return 1;
  }
  std::cerr << "report: " << dir << "/report.md\n";
  return 0;
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
      ->check(CLI::Range(std::size_t{1}, std::size_t{100000}))
      ->capture_default_str();
  app.add_option("--threads", options.threads, "worker threads (0: every core)")->capture_default_str();
  app.add_option("--alpha", options.group.alpha, "level of the string-stability test")
      ->check(CLI::Range(1e-9, 1.0 - 1e-9))
      ->capture_default_str();
  app.add_option("--seed", options.group.seed, "campaign seed (each group's bootstrap draws from its own stream)")
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
  CLI11_PARSE(app, argc, argv);
  options.platoon_check = !no_platoon_check;
  options.platoon_diagnosis = !no_platoon_diagnosis;
  if (!platoon_effects.empty())
  {
    options.effect_selection.force = true;
    if (!acc::parsePlatoonCandidate(platoon_effects, &options.effect_selection.forced))
    {
      std::cerr << "error: --platoon-effects: cannot read '" << platoon_effects
                << "' (effect names joined by commas, optionally @speed, @gap or @speed_and_gap)\n";
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
  if (!json_path.empty() && !writeText(json.dump(2) + "\n", json_path))
    return 1;
  if (!sumo_vtype_path.empty() && !acc::saveSumoVTypes(acc::campaignSumoExports(inputs, result), sumo_vtype_path,
                                                        acc::kSumoOpenAccProvenance, std::cerr))
    return 1;
  if (!report_dir.empty())
    return writeReport(report_dir, json, result, paths, no_plots, plot_script);
  return 0;
}
