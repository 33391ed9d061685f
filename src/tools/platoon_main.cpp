// platoon: the numbers and data behind the figures of Gunter et al. (issue 7), for the paper's
// settings or any calibration. Writes the figure's data as CSV, prints the key numbers and, on
// request, writes them as JSON for scripts/plot_figures.py and for comparisons. The figures are
// the reproduction library's (paper_figures.h); this is their command line.
#include <nlohmann/json.hpp>

#include <fstream>
#include <iostream>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "acc_identification/io/output_files.h"
#include "acc_identification/reproduction/paper_figures.h"

namespace
{
/// The summary as JSON, with the CSV's path; throws when it cannot be written.
void writeSummary(nlohmann::json summary, const std::string& csv_path, const std::string& summary_path)
{
  summary["csv"] = csv_path;
  if (summary_path.empty())
  {
    return;
  }
  std::ofstream out(summary_path);
  out << summary.dump(2) << '\n';
  if (!out)
  {
    throw std::runtime_error("cannot write " + summary_path);
  }
}
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"The numbers and data behind the figures of Gunter et al.: one FIGURE per call, its data as CSV and "
               "a summary as JSON. Parameter sets (repeatable, in order; default min and max of Table II): "
               "--setting NAME, --params CALIBRATE.json, --k1 --k2 --tau-e [--eta] (one custom set)."};
  app.footer(acc::paperFiguresHelp());
  std::string figure, csv_path, summary_path;
  std::map<std::string, std::vector<std::string>> given;
  app.add_option("FIGURE", figure, "the figure")
      ->required()
      ->check(CLI::IsMember(acc::acceptedFigures()));
  app.add_option("--csv", csv_path, "the figure's data")->required();
  app.add_option("--summary-json", summary_path, "the figure's key numbers");
  for (const std::string& name : acc::figureValueOptions())
  {
    // One value per occurrence (a repeated option adds one): never the FIGURE after it.
    app.add_option("--" + name, given[name], "see the figures below")->expected(1)->allow_extra_args(false)->take_all();
  }
  CLI11_PARSE(app, argc, argv);
  if (!acc::outputsLeaveInputsAlone(given["params"], {csv_path, summary_path}, std::cerr))
    return 2;
  try
  {
    writeSummary(acc::runPaperFigure(figure, acc::FigureOptions(given), csv_path), csv_path, summary_path);
  }
  catch (const acc::FigureUsageError& error)
  {
    std::cerr << "error: " << error.what() << "\nRun with --help for more information.\n";
    return 2;
  }
  catch (const std::exception& error)
  {
    std::cerr << "error: " << error.what() << "\n";
    return 1;
  }
  return 0;
}
