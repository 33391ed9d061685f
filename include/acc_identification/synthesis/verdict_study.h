#pragma once

#include <cstdint>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace acc
{
/// Size and power of the sequential string-stability verdict (calibration/sequential_verdict.h)
/// on seeded synthetic drives with a known margin (synthesizeRun of truthWithMargin), each looked
/// at as the identifier node looks at a drive: what `verdict_study` prints (docs/SEQUENTIAL_VERDICT.md).
struct VerdictStudyOptions
{
  int drives = 20;  ///< per truth class
  double duration_s = 1200.0;
  double look_every_s = 10.0;
  double alpha = 0.05;
  std::uint32_t first_seed = 1000;  ///< of each class's first drive
  std::vector<double> margins{0.3, 1.0, 3.0, -0.3, -1.0};  ///< one truth class each
  std::vector<double> checkpoints_s{300.0, 600.0, 900.0, 1200.0};  ///< drive lengths power is read at
  /// The leaders the drives cycle through: synthesizeRun's oscillating leader with hard brakes
  /// around these cruise speeds [m/s].
  std::vector<double> cruise_speeds_mps{15.0, 22.0, 30.0};
};

/// One truth class: its drives' outcomes.
struct VerdictStudyClass
{
  double margin = 0.0;
  int drives = 0;
  int wrong = 0;      ///< a wrong verdict at any look (the error the verdict bounds by alpha)
  int withdrawn = 0;  ///< a decision later gone (a reversal counts, said separately)
  int reversed = 0;
  std::vector<int> right_by_length;  ///< decided right at the look shown at each checkpoint
  int decided_right = 0;             ///< right at the drive's end
  double decided_at_sum_s = 0.0;     ///< over those, the drive time of the decision

  /// NaN when no drive was decided right: there is no time to average (0 would read as "at once").
  double meanDecidedAtS() const
  {
    return decided_right > 0 ? decided_at_sum_s / decided_right : std::numeric_limits<double>::quiet_NaN();
  }
};

/// The checkpoints fitted to the drives' length: given ones (checkpoints_given) must lie within it,
/// else why not (read there, the power would be the drive's end's carried on: a length never
/// simulated); the default ones are cut to it and the drive's end added. "" when they fit.
std::string fitCheckpointsToDuration(VerdictStudyOptions* options, bool checkpoints_given);

/// Every class's drives replayed (a line per drive on progress, may be null).
std::vector<VerdictStudyClass> runVerdictStudy(const VerdictStudyOptions& options, std::FILE* progress);

/// The table: a row per class (drives, wrong, withdrawn, reversed, right at each checkpoint, mean
/// decision time).
std::string verdictStudyTable(const std::vector<VerdictStudyClass>& classes, const VerdictStudyOptions& options);

/// {drives_per_class, duration_s, look_every_s, alpha, classes: [{margin, drives, wrong_decisions,
/// withdrawn, reversed, power_by_length: [{drive_length_s, decided_right}], mean_decided_at_s}]}.
nlohmann::json verdictStudyJson(const std::vector<VerdictStudyClass>& classes, const VerdictStudyOptions& options);

}  // namespace acc
