#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/calibration/calibration_report.h"
#include "acc_identification/io/input_account.h"
#include "acc_identification/model/car_following_run.h"

namespace acc
{
/// One run (or segment) to calibrate and the RUN argument it came from (a drive for the
/// sequential verdict is the consecutive runs of one path).
struct CalibrationInput
{
  CarFollowingRun run;
  std::string path;
};

/// What a second look at runs the fitted model does not describe gives: its JSON and its text.
struct SecondOpinion
{
  nlohmann::json json;
  std::string text;
};

/// A second look at the runs (the diagnosis, which this library cannot call: it depends on it).
using SecondOpinionOf = std::function<SecondOpinion(const std::vector<CarFollowingRun>& runs)>;

/// What `calibrate` does, as options (docs/TOOLS.md).
struct CalibrateSettings
{
  bool split_half = false;         ///< --split half: train on first halves, report the second
  std::size_t starts = 100;        ///< Halton starts of every multistart
  std::size_t grid_nodes = 0;      ///< --grid N (0: no grid check)
  double alpha = 0.05;             ///< level of the string-stability tests
  std::optional<std::uint64_t> seed;  ///< the bootstraps' seed (default: each one's own fixed seed)
  /// The refitting bootstrap's replicates (refit_bootstrap.h; 0: none), made when the data the
  /// model is fitted on span less than bootstrap_below_s: on a minute of data value +- t se covers
  /// 72-88 %, the bootstrap 82-93 % (docs/RESULTS.md); from 300 s on value +- t se covers 90-98 %.
  std::size_t bootstrap_replicates = 199;
  double bootstrap_below_s = 300.0;
  bool stability_test = true;
  double verdict_every_s = 0.0;    ///< > 0: replay the sequential verdict look by look
  /// Called after each multistart start (done, total); may be empty.
  std::function<void(std::size_t, std::size_t)> progress;
  bool quiet = false;              ///< no progress lines on the log
  /// Asked when the model is assessed NOT ADEQUATE (and a stability test ran): its JSON becomes
  /// "diagnosed_verdict" and its text follows the report, so that the verdict a user reads comes
  /// from a model that describes the data where one exists (the tool and the Python API pass the
  /// diagnosis, diagnosis/calibration_second_opinion.h). Empty: not asked.
  SecondOpinionOf second_opinion;
};

/// Exit status for valid data that cannot be fitted (steady speed, too short): the JSON is still
/// made (fitted: false, the reason, what the data do decide), but there are no parameters to use,
/// so a script must not take the run for a fit (docs/TOOLS.md).
constexpr int kExitValidDataNoFit = 3;

struct CalibrateOutcome
{
  /// 0 (a fit), kExitValidDataNoFit, or 1 (the fit diverged).
  int exit_status = 0;
  std::optional<CalibrationReport> report;  ///< empty when there is no fit
  nlohmann::json json;                      ///< exactly what `calibrate --json` writes
  /// What the model was fitted on, and judged on with --split half (empty otherwise), and the
  /// names of their runs in the same order: with --split half a run too short to halve is left
  /// out of them (said on the log and in the JSON's runs_left_out).
  std::vector<CarFollowingRun> training, testing;
  std::vector<std::string> run_names;
};

/// The whole of `calibrate` after its inputs are read: the fit (the identifier node's
/// identifyAcc), the grid check, the fixed-sample string-stability test, the model's adequacy,
/// the dips' evidence, each run's scores, the report on out, the sequential verdict's replay, and
/// the JSON. Progress goes to log. With split_half a run too short to halve is left out, said on
/// log and in the JSON (no fit when none is left). The runs are taken in the natural order of
/// their names (naturalLess), whatever order they are given in, so that one set of runs gives
/// one answer (the resampling draws blocks over the runs in order). Throws std::invalid_argument
/// for a grid the objective refuses.
CalibrateOutcome calibrateRuns(const std::vector<CalibrationInput>& inputs, const std::vector<InputAccount>& inputs_read,
                               const CalibrateSettings& settings, std::ostream& out, std::ostream& log);

/// calibrate --report DIR: calibration.json, fit_traces.csv (every run measured and simulated,
/// each by its name) and, drawn by plot_script (plot_calibration.py), a figure per run and
/// report.md. False after saying on log what failed.
bool writeCalibrationReport(const std::string& dir, const CalibrateOutcome& outcome, const std::string& plot_script,
                            std::ostream& log);

/// The runs as read, whole.
std::vector<CarFollowingRun> runsOf(const std::vector<CalibrationInput>& inputs);

/// describeRepeatedRun (io/repeated_recording.h) of these runs, each named by its file,
/// `input_of[k]` numbering the input run k came from: "" when no run repeats one of an earlier input.
std::string describeRepeatedInput(const std::vector<CalibrationInput>& inputs,
                                  const std::vector<std::size_t>& input_of);

}  // namespace acc
