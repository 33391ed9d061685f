// verdict_study: size and power of the sequential string-stability verdict (sequential_verdict.h)
// on seeded synthetic drives with a known margin, looked at as the identifier node looks at a
// drive. Per truth class: wrong decisions anywhere in a drive (the error the verdict bounds by
// alpha), withdrawn decisions (must be none), and the share decided right by each drive length.
// The study is synthesis/verdict_study.h.
#include <array>
#include <cstdio>
#include <iostream>

#include <CLI/CLI.hpp>

#include "acc_identification/io/output_files.h"
#include "acc_identification/synthesis/synthetic_runs.h"
#include "acc_identification/synthesis/verdict_study.h"
#include "acc_identification/tools/number_checks.h"
#include "acc_identification/tools/option_rules.h"

namespace
{
constexpr double kLongestDriveS = 86400.0;
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Size and power of the sequential string-stability verdict on seeded synthetic drives with known "
               "margins, looked at as the identifier node does."};
  acc::VerdictStudyOptions options;
  std::string json_path;
  app.add_option("--drives", options.drives, "seeded drives per truth class")
      ->check(acc::positiveNumber())
      ->capture_default_str();
  // A drive is simulated whole and looked at as it grows: a day of it holds 864,000 samples (about
  // 0.4 GB); --duration 1e6 took 5 GB before its first look.
  app.add_option("--duration", options.duration_s, "length of each drive [s]")
      ->check(acc::closedInterval(0.1, kLongestDriveS, "SECONDS"))
      ->capture_default_str();
  app.add_option("--every", options.look_every_s, "data time between looks [s]")
      ->check(acc::positiveNumber())
      ->capture_default_str();
  app.add_option("--alpha", options.alpha, "level")->check(acc::openInterval(0.0, 1.0))->capture_default_str();
  const std::array<double, 2> margins = acc::truthMarginRange();  // what a truth of the study can have
  app.add_option("--margins", options.margins, "true margins, one class each")
      ->check(acc::closedInterval(margins[0], margins[1], "MARGIN"))
      ->capture_default_str();
  app.add_option("--checkpoints", options.checkpoints_s, "drive lengths at which power is read [s], up to --duration")
      ->check(acc::positiveNumber())
      ->capture_default_str();
  app.add_option("--first-seed", options.first_seed, "seed of the first drive of each class")
      ->check(acc::seed32())
      ->capture_default_str();
  app.add_option("--json", json_path, "write the table as JSON");
  auto* checkpoints = app.get_option("--checkpoints");
  CLI11_PARSE(app, argc, argv);
  if (const std::string why = acc::fitCheckpointsToDuration(&options, checkpoints->count() > 0); !why.empty())
  {
    std::cerr << "error: " << why << "\n";
    return 2;
  }

  const std::vector<acc::VerdictStudyClass> classes = acc::runVerdictStudy(options, stderr);
  std::cout << acc::verdictStudyTable(classes, options);
  return json_path.empty() || acc::writeJsonFile(acc::verdictStudyJson(classes, options), json_path, std::cerr) ? 0 : 1;
}
