// verdict_study: size and power of the sequential string-stability verdict (sequential_verdict.h)
// on seeded synthetic drives with a known margin, looked at as the identifier node looks at a
// drive. Per truth class: wrong decisions anywhere in a drive (the error the verdict bounds by
// alpha), withdrawn decisions (must be none), and the share decided right by each drive length.
#include <cstdio>
#include <fstream>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>
#include <nlohmann/json.hpp>

#include "acc_identification/calibration/sequential_verdict.h"
#include "acc_identification/synthesis/synthetic_runs.h"

namespace
{
/// The leader profiles the drives cycle through: synthesizeRun's oscillating leader with hard
/// brakes around these cruise speeds [m/s].
const std::vector<double> kCruiseSpeedsMps{15.0, 22.0, 30.0};

struct ClassResult
{
  double margin = 0.0;
  int drives = 0;
  int wrong = 0;      ///< a wrong verdict at any look
  int withdrawn = 0;  ///< a decision later gone (a reversal counts, said separately)
  int reversed = 0;
  std::vector<int> right_by_length;  ///< decided right at the look at each checkpoint
  double decided_at_sum_s = 0.0;
  int decided_right = 0;
};
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Size and power of the sequential string-stability verdict on seeded synthetic drives with known "
               "margins, looked at as the identifier node does."};
  int drives = 20;
  double duration_s = 1200.0, every_s = 10.0, alpha = 0.05;
  std::uint32_t first_seed = 1000;
  std::vector<double> margins{0.3, 1.0, 3.0, -0.3, -1.0};
  std::vector<double> checkpoints_s{300.0, 600.0, 900.0, 1200.0};
  std::string json_path;
  app.add_option("--drives", drives, "seeded drives per truth class")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--duration", duration_s, "length of each drive [s]")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--every", every_s, "data time between looks [s]")->check(CLI::PositiveNumber)->capture_default_str();
  app.add_option("--alpha", alpha, "level")->check(CLI::Range(1e-9, 1.0 - 1e-9))->capture_default_str();
  app.add_option("--margins", margins, "true margins, one class each")->capture_default_str();
  app.add_option("--checkpoints", checkpoints_s, "drive lengths at which power is read [s]")->capture_default_str();
  app.add_option("--first-seed", first_seed, "seed of the first drive of each class")->capture_default_str();
  app.add_option("--json", json_path, "write the table as JSON");
  CLI11_PARSE(app, argc, argv);

  acc::SequentialVerdictOptions options;
  options.alpha = alpha;
  options.look_period_s = every_s;
  std::vector<ClassResult> results;
  for (double margin : margins)
  {
    ClassResult r;
    r.margin = margin;
    r.right_by_length.assign(checkpoints_s.size(), 0);
    const acc::StabilityVerdict right = margin >= 0 ? acc::StabilityVerdict::Stable : acc::StabilityVerdict::Unstable;
    for (int i = 0; i < drives; ++i)
    {
      const std::uint32_t seed = first_seed + static_cast<std::uint32_t>(i);
      const acc::CarFollowingRun run = acc::synthesizeRun(acc::truthWithMargin(margin), duration_s, 0.1,
                                                          kCruiseSpeedsMps[i % kCruiseSpeedsMps.size()], seed);
      const std::vector<acc::SequentialLook> looks = acc::replaySequentialVerdict({run}, options);
      ++r.drives;
      bool wrong = false, withdrawn = false;
      acc::StabilityVerdict taken = acc::StabilityVerdict::Undecided;
      for (const acc::SequentialLook& look : looks)
      {
        wrong = wrong || (look.verdict != acc::StabilityVerdict::Undecided && look.verdict != right);
        withdrawn = withdrawn || (taken != acc::StabilityVerdict::Undecided && look.verdict != taken);
        taken = look.verdict;
      }
      for (std::size_t c = 0; c < checkpoints_s.size(); ++c)
      {
        // The look the node would show at that drive length: the last at or before it.
        const acc::SequentialLook* at = nullptr;
        for (const acc::SequentialLook& look : looks)
        {
          if (look.time_s - run.time_s.front() <= checkpoints_s[c] + 1e-9)
          {
            at = &look;
          }
        }
        r.right_by_length[c] += at != nullptr && at->verdict == right;
      }
      r.wrong += wrong;
      r.withdrawn += withdrawn;
      r.reversed += !looks.empty() && looks.back().reversed;
      if (!looks.empty() && looks.back().verdict == right && !looks.back().reversed)
      {
        ++r.decided_right;
        r.decided_at_sum_s += looks.back().decided_at_s - run.time_s.front();
      }
      std::fprintf(stderr, "m = %g, drive %d/%d: %s\n", margin, i + 1, drives,
                   looks.empty() ? "no look" : acc::toString(looks.back().verdict).c_str());
    }
    results.push_back(r);
  }

  std::printf("Sequential verdict on %d seeded synthetic drive(s) per class, %.0f s each, a look every %.0f s, "
              "alpha %.2f\n",
              drives, duration_s, every_s, alpha);
  std::printf("%8s %7s %7s %10s %9s", "margin", "drives", "wrong", "withdrawn", "reversed");
  for (double c : checkpoints_s)
    std::printf("  right@%4.0fs", c);
  std::printf("  mean decided at [s]\n");
  nlohmann::json json = nlohmann::json::array();
  for (const ClassResult& r : results)
  {
    std::printf("%8.2f %7d %7d %10d %9d", r.margin, r.drives, r.wrong, r.withdrawn, r.reversed);
    nlohmann::json power = nlohmann::json::array();
    for (std::size_t c = 0; c < checkpoints_s.size(); ++c)
    {
      const double share = static_cast<double>(r.right_by_length[c]) / r.drives;
      std::printf("  %11.2f", share);
      power.push_back({{"drive_length_s", checkpoints_s[c]}, {"decided_right", share}});
    }
    const double mean_decided = r.decided_right > 0 ? r.decided_at_sum_s / r.decided_right : 0.0;
    std::printf("  %8.0f\n", mean_decided);
    json.push_back({{"margin", r.margin},
                    {"drives", r.drives},
                    {"wrong_decisions", r.wrong},
                    {"withdrawn", r.withdrawn},
                    {"reversed", r.reversed},
                    {"power_by_length", power},
                    {"mean_decided_at_s", mean_decided}});
  }
  if (!json_path.empty())
  {
    std::ofstream file(json_path);
    file << nlohmann::json{{"drives_per_class", drives}, {"duration_s", duration_s}, {"look_every_s", every_s},
                           {"alpha", alpha}, {"classes", json}}
                .dump(2)
         << "\n";
    if (!file)
    {
      std::cerr << "error: cannot write " << json_path << "\n";
      return 1;
    }
  }
  return 0;
}
