// acc_identification._core: the package's tools as Python functions (pybind11). Each takes and
// gives plain data (numpy arrays, lists, JSON text) and runs the same library calls as its
// command-line tool, so that a notebook and `calibrate --json` give the same numbers; the
// DataFrames and dicts are made in python/acc_identification/__init__.py. Errors raise the
// tools' messages as Python exceptions; the GIL is released while the C++ solves.
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include "acc_identification/calibration/calibrate_runs.h"
#include "acc_identification/campaign/campaign.h"
#include "acc_identification/campaign/campaign_output.h"
#include "acc_identification/conversion/nmea_logs_to_csv.h"
#include "acc_identification/diagnosis/calibration_second_opinion.h"
#include "acc_identification/diagnosis/diagnosis.h"
#include "acc_identification/diagnosis/diagnosis_output.h"
#include "acc_identification/diagnosis/diagnosis_text.h"
#include "acc_identification/io/output_files.h"
#include "acc_identification/io/run_csv.h"
#include "acc_identification/ros/run_bag_reader.h"
#include "acc_identification/tools/bootstrap_options.h"
#include "acc_identification/tools/option_rules.h"

namespace py = pybind11;

namespace
{
py::array_t<double> toArray(const std::vector<double>& values)
{
  return py::array_t<double>(static_cast<py::ssize_t>(values.size()), values.data());
}

std::vector<double> column(const py::dict& run, const char* name)
{
  if (!run.contains(name))
    throw std::invalid_argument(std::string("a run needs the column ") + name);
  const auto array = run[name].cast<py::array_t<double, py::array::c_style | py::array::forcecast>>();
  return std::vector<double>(array.data(), array.data() + array.size());
}

/// A run as the Python side hands it: {name, path, input, time_s, space_gap_m, follower_speed_mps,
/// leader_speed_mps}, and `check` true when the rows are not read_run's rows as read (a DataFrame
/// of the user's own, or one changed after reading): those are judged row by row by the readers'
/// own rules (assembleRunColumns, with the frame's `max_gap_s` and each row's number `rows` as the
/// problems name it under `where`) and may become several runs; what the rules did goes to log,
/// as the tools print a file's problems. Rows as read are checked as the library checks a run.
struct PythonRuns
{
  std::vector<acc::CalibrationInput> inputs;
  std::vector<std::size_t> input_of;  ///< the number of the frame each run came from
};

void appendRun(const py::dict& run, PythonRuns& runs, std::ostream& log)
{
  acc::CarFollowingRun columns;
  columns.name = run["name"].cast<std::string>();
  columns.time_s = column(run, "time_s");
  columns.space_gap_m = column(run, "space_gap_m");
  columns.follower_speed_mps = column(run, "follower_speed_mps");
  columns.leader_speed_mps = column(run, "leader_speed_mps");
  const std::string path = run["path"].cast<std::string>();
  const std::size_t input = run["input"].cast<std::size_t>();
  if (!run["check"].cast<bool>())
  {
    const std::string problem = acc::describeRunProblem(columns);
    if (!problem.empty())
      throw std::invalid_argument("run '" + columns.name + "': " + problem);
    runs.inputs.push_back({std::move(columns), path});
    runs.input_of.push_back(input);
    return;
  }
  acc::RunPlausibilityBounds bounds;
  bounds.max_time_step_s = run["max_gap_s"].cast<double>();
  const std::string where = run["where"].cast<std::string>();
  acc::RunFileContents contents = acc::assembleRunColumns(where, columns.name, columns,
                                                          run["rows"].cast<std::vector<std::size_t>>(), bounds);
  std::vector<acc::CarFollowingRun> assembled;
  try
  {
    assembled = acc::reportAndTakeRuns(where, contents, log);
  }
  catch (const acc::RunReadError& error)
  {
    throw std::invalid_argument(error.what());  // rows handed over, not a file: bad input
  }
  for (acc::CarFollowingRun& piece : assembled)
  {
    runs.inputs.push_back({std::move(piece), path});
    runs.input_of.push_back(input);
  }
}

PythonRuns toInputs(const py::list& list, std::ostream& log)
{
  PythonRuns runs;
  for (const py::handle& run : list)
    appendRun(run.cast<py::dict>(), runs, log);
  if (runs.inputs.empty())
    throw std::invalid_argument("no run given");
  return runs;
}

/// Refuses runs of which one repeats a run of an earlier frame (io/repeated_recording.h: the same
/// recording given twice), as the tools' readers do.
void refuseRepeatedRuns(const std::vector<acc::CalibrationInput>& inputs, const std::vector<std::size_t>& input_of)
{
  if (const std::string repeat = acc::describeRepeatedInput(inputs, input_of); !repeat.empty())
    throw std::invalid_argument(repeat + ": give each recording once (a fit would count it twice, and a held-out "
                                         "run that repeats a fitted one is not held out)");
}

/// An account as accountDict gives it, back from the Python side ({path, format, openacc_pairs,
/// counts}; counts in their order).
acc::InputAccount toInputAccount(const py::dict& entry)
{
  acc::InputAccount account;
  account.path = entry["path"].cast<std::string>();
  account.format = entry["format"].cast<std::string>();
  account.openacc_pairs = entry["openacc_pairs"].cast<std::vector<std::string>>();
  for (const auto& [name, count] : entry["counts"].cast<py::dict>())
    account.counts.emplace_back(name.cast<std::string>(), count.cast<std::size_t>());
  return account;
}

std::vector<acc::InputAccount> toInputAccounts(const py::list& inputs_read)
{
  std::vector<acc::InputAccount> accounts;
  for (const py::handle& item : inputs_read)
    accounts.push_back(toInputAccount(item.cast<py::dict>()));
  return accounts;
}

py::dict accountDict(const acc::InputAccount& account)
{
  py::dict counts;
  for (const auto& [name, count] : account.counts)
    counts[py::str(name)] = count;
  py::dict entry;
  entry["path"] = account.path;
  entry["format"] = account.format;
  entry["openacc_pairs"] = account.openacc_pairs;
  entry["counts"] = counts;
  return entry;
}

/// read_run: the tools' reader of one RUN argument (CSV of any layout, or a bag).
py::dict readRun(const std::string& path, const std::string& follower, bool all_pairs, double max_gap_s,
                 const std::string& topic, const std::string& acc_engaged_topic, bool require_acc_engaged,
                 double acc_engaged_timeout_s, const std::string& acc_setting)
{
  if (!follower.empty() && all_pairs)
    throw std::invalid_argument("follower and all_pairs exclude each other (as --follower and --all-pairs): "
                                "all_pairs reads every pair of an OpenACC file, follower one");
  std::ostringstream log;
  acc::RunArgument argument;
  acc::BagTopics topics;
  topics.relative_state = topic;
  topics.acc_engaged = acc_engaged_topic;
  topics.engagement.required = require_acc_engaged;
  topics.engagement.timeout_s = acc_engaged_timeout_s;
  topics.only_setting = acc_setting;
  {
    py::gil_scoped_release unlocked;
    argument = acc::readRunArgument(path, topics, max_gap_s, log, acc::pairSelectorFromOptions(follower, all_pairs));
  }
  py::list runs;
  for (std::size_t k = 0; k < argument.runs.size(); ++k)
  {
    const acc::CarFollowingRun& run = argument.runs[k];
    py::dict entry;
    entry["name"] = run.name;
    entry["pair"] = k < argument.run_pairs.size() ? py::cast(argument.account.openacc_pairs[argument.run_pairs[k]])
                                                   : py::none();
    entry["time_s"] = toArray(run.time_s);
    entry["space_gap_m"] = toArray(run.space_gap_m);
    entry["follower_speed_mps"] = toArray(run.follower_speed_mps);
    entry["leader_speed_mps"] = toArray(run.leader_speed_mps);
    runs.append(entry);
  }
  py::dict result;
  result["runs"] = runs;
  result["account"] = accountDict(argument.account);
  result["log"] = log.str();
  return result;
}

py::dict calibrate(const py::list& runs, const py::list& inputs_read, bool split_half, std::size_t starts,
                   double alpha, const py::object& seed, bool stability_test, double verdict_every_s,
                   std::size_t grid_nodes, bool second_opinion, std::size_t bootstrap_replicates,
                   double bootstrap_below_s)
{
  std::ostringstream text, log;
  const PythonRuns given = toInputs(runs, log);
  const std::vector<acc::CalibrationInput>& inputs = given.inputs;
  refuseRepeatedRuns(inputs, given.input_of);
  const std::vector<acc::InputAccount> accounts = toInputAccounts(inputs_read);
  acc::CalibrateSettings settings;
  settings.split_half = split_half;
  settings.starts = starts;
  settings.alpha = alpha;
  if (!seed.is_none())
    settings.seed = seed.cast<std::uint64_t>();
  settings.stability_test = stability_test;
  settings.verdict_every_s = verdict_every_s;
  settings.grid_nodes = grid_nodes;
  settings.bootstrap_replicates = bootstrap_replicates;
  settings.bootstrap_below_s = bootstrap_below_s;
  settings.quiet = true;
  if (second_opinion)
    settings.second_opinion = acc::diagnosisSecondOpinion();  // as the calibrate tool
  acc::CalibrateOutcome outcome;
  {
    py::gil_scoped_release unlocked;
    outcome = acc::calibrateRuns(inputs, accounts, settings, text, log);
  }
  py::dict result;
  result["json"] = outcome.json.dump();
  result["text"] = text.str();
  result["log"] = log.str();
  result["exit_status"] = outcome.exit_status;
  return result;
}

/// nmea_to_csv's job: the counts its --json writes (JSON text) and its notes (the parameter file's
/// unread keys, the stream events). An option not given is NaN or "".
py::dict pairNmeaLogs(const std::string& leader_path, const std::string& follower_path, const std::string& out_path,
                      const std::string& params_path, double antenna_offset_m, double leader_antenna_to_rear_bumper_m,
                      double follower_antenna_to_front_bumper_m, const std::string& gap_mode, double dropout_gap_s)
{
  const acc::NmeaPairingOptions options{
      params_path,
      acc::AntennaOffsets{antenna_offset_m, leader_antenna_to_rear_bumper_m, follower_antenna_to_front_bumper_m},
      gap_mode, dropout_gap_s};
  std::ostringstream overwrite;
  std::vector<std::string> inputs{leader_path, follower_path};
  if (!params_path.empty())
    inputs.push_back(params_path);
  if (!acc::outputsLeaveInputsAlone(inputs, {out_path}, overwrite))
    throw std::invalid_argument(overwrite.str().substr(0, overwrite.str().find_last_not_of('\n') + 1));
  acc::RelativeStateSettings settings;
  std::string notes;
  const std::string refused = acc::pairingSettingsFrom(options, settings, notes);
  if (!refused.empty())
    throw std::invalid_argument(refused + (refused.find("antenna") == std::string::npos
                                               ? ""
                                               : "; the arguments: antenna_offset_m=M, or "
                                                 "leader_antenna_to_rear_bumper_m=A with "
                                                 "follower_antenna_to_front_bumper_m=B, or params= a file that "
                                                 "places them"));
  if (!notes.empty())
    notes = "warning: " + params_path + ": " + notes + "\n";
  acc::RelativeStateLogs logs;
  {
    py::gil_scoped_release unlocked;
    logs = acc::pairNmeaLogsToCsv(leader_path, follower_path, out_path, settings);
  }
  if (!logs.error.empty())
    throw std::runtime_error(logs.error);
  const std::string no_state = acc::noStateReason(logs);
  if (!no_state.empty())
    throw std::invalid_argument(no_state);
  for (const std::string& event : logs.stream_events)
    notes += "note: " + event + "\n";
  const std::string implausible = acc::describeImplausibleGaps(logs);
  if (!implausible.empty())
    notes += "warning: " + implausible + "\n";
  py::dict result;
  result["json"] = acc::relativeStateLogsJson(logs).dump();
  result["log"] = notes;
  return result;
}

/// The runs to fit and those kept aside, each list converted once (the readers' notes on log);
/// refused as the tools refuse them when one repeats a run of an earlier frame.
std::pair<std::vector<acc::CarFollowingRun>, std::vector<acc::CarFollowingRun>> fittedAndHeldOut(
    const py::list& runs, const py::list& held_out_runs, std::ostream& log)
{
  PythonRuns all = toInputs(runs, log);
  const std::size_t fitted = all.inputs.size();
  if (!held_out_runs.empty())
  {
    PythonRuns kept = toInputs(held_out_runs, log);
    all.inputs.insert(all.inputs.end(), kept.inputs.begin(), kept.inputs.end());
    all.input_of.insert(all.input_of.end(), kept.input_of.begin(), kept.input_of.end());
  }
  refuseRepeatedRuns(all.inputs, all.input_of);
  std::vector<acc::CarFollowingRun> every = acc::runsOf(all.inputs);
  std::vector<acc::CarFollowingRun> held_out(every.begin() + static_cast<long>(fitted), every.end());
  every.resize(fitted);
  return {std::move(every), std::move(held_out)};
}

/// held_out_runs empty: each run fitted on its first part and scored on the rest; otherwise the
/// runs fitted whole and these scored whole (diagnose --held-out). {json, log}: log the readers'
/// notes and the runs or parts not used, as the tool prints them.
py::dict diagnose(const py::list& runs, const py::list& inputs_read, const std::vector<std::string>& inputs,
                     double train_fraction, const std::vector<std::string>& effects, std::size_t threads,
                     const py::object& seed, bool forward_selection, const py::list& held_out_runs,
                     const std::vector<std::string>& held_out_inputs, std::size_t bootstrap_replicates,
                     double bootstrap_below_s)
{
  std::ostringstream log;
  const auto [plain, held_out] = fittedAndHeldOut(runs, held_out_inputs.empty() ? py::list() : held_out_runs, log);
  acc::DiagnosisOptions options;
  options.train_fraction = train_fraction;
  options.threads = threads;
  options.forward_selection = forward_selection;
  options.bootstrap_replicates = bootstrap_replicates;
  options.bootstrap_below_s = bootstrap_below_s;
  if (!seed.is_none())
  {
    options.selection.seed = seed.cast<std::uint32_t>();
    options.bootstrap.seed = options.selection.seed;  // as diagnose --seed
  }
  if (!effects.empty())
  {
    options.candidates.clear();
    for (const std::string& name : effects)
    {
      acc::EffectKind kind = acc::EffectKind::none;
      if (!acc::parseEffectName(name, &kind) || kind == acc::EffectKind::none)
        throw std::invalid_argument("unknown effect '" + name + "'");
      options.candidates.push_back(kind);
    }
  }
  acc::DiagnosisResult result;
  {
    py::gil_scoped_release unlocked;
    result = held_out_inputs.empty() ? acc::diagnoseRuns(plain, options)
                                     : acc::diagnoseHeldOutRuns(plain, held_out, options);
  }
  acc::writeUnusedRunNotes(result, log);
  py::dict out;
  out["json"] = acc::diagnosisToJson(result, inputs, held_out_inputs, toInputAccounts(inputs_read)).dump();
  out["log"] = log.str();
  return out;
}

/// {json, log}: log the inputs' notes and what was skipped, as the tool prints them.
py::dict campaign(const std::vector<std::string>& paths, std::size_t starts, std::size_t threads, double alpha,
                     std::uint64_t seed, bool platoon_check, bool platoon_diagnosis, std::size_t bootstrap_replicates,
                     double bootstrap_below_s)
{
  acc::CampaignOptions options;
  options.group.bootstrap = acc::ShortRunsBootstrapOptions{bootstrap_replicates, bootstrap_below_s};
  options.group.starts = starts;
  options.group.alpha = alpha;
  options.group.seed = seed;
  options.threads = threads;
  options.platoon_check = platoon_check;
  options.platoon_diagnosis = platoon_diagnosis;
  acc::CampaignInputs inputs;
  acc::CampaignResult result;
  {
    py::gil_scoped_release unlocked;
    inputs = acc::loadCampaign(paths);
    result = acc::runCampaign(inputs, options);
  }
  std::ostringstream log;
  for (const std::string& note : inputs.notes)
    log << "note: " << note << "\n";
  if (inputs.skipped_files + inputs.skipped_pairs > 0)
    log << inputs.describeSkipped() << "\n";
  py::dict out;
  out["json"] = acc::campaignToJson(inputs, result, paths, options).dump();
  out["log"] = log.str();
  return out;
}

/// Checks a keyword argument of the Python functions by the tools' own rule for the same option
/// (tools/option_rules.h, tools/number_checks.h), named by rule (the argument's name, or seed32
/// for diagnose's seed): ValueError "name: must be ..., not text".
void checkOption(const std::string& name, const std::string& rule_name, const std::string& value_text)
{
  static const std::map<std::string, CLI::Validator (*)()> rules{
      {"starts", acc::multistartStarts},
      {"alpha", acc::testLevel},
      {"grid", acc::gridNodesPerAxis},
      {"seed", [] { return acc::nonNegativeWholeNumber(); }},
      {"seed32", acc::seed32},
      {"verdict_every_s", acc::verdictEverySeconds},
      {"train_fraction", acc::trainFraction},
      {"threads", [] { return acc::nonNegativeWholeNumber(); }},
      {"bootstrap", acc::bootstrapReplicates},
      {"bootstrap_below_s", [] { return acc::nonNegativeNumber(); }},
      {"max_gap_s", [] { return acc::positiveNumber(); }},
      {"acc_engaged_timeout_s", [] { return acc::nonNegativeNumber(); }},
  };
  const auto rule = rules.find(rule_name);
  if (rule == rules.end())
    throw std::logic_error("check_option: no rule '" + rule_name + "'");
  std::string text = value_text;
  const std::string why = rule->second()(text);
  if (!why.empty())
    throw std::invalid_argument(name + ": " + why);
}
}  // namespace

/// The tools' defaults, read from the option structs themselves so that the Python functions
/// default to exactly what the command-line tools do.
py::dict defaults()
{
  const acc::CalibrateSettings calibrate;
  const acc::DiagnosisOptions diagnose;
  const acc::CampaignOptions campaign;
  py::dict all;
  all["calibrate"] = py::dict(py::arg("starts") = calibrate.starts, py::arg("alpha") = calibrate.alpha,
                              py::arg("bootstrap") = calibrate.bootstrap_replicates,
                              py::arg("bootstrap_below_s") = calibrate.bootstrap_below_s);
  all["diagnose"] = py::dict(py::arg("train_fraction") = diagnose.train_fraction,
                             py::arg("seed") = diagnose.selection.seed, py::arg("threads") = diagnose.threads,
                             py::arg("bootstrap") = acc::RefitBootstrapOptions{}.replicates,  // as the tool's
                             py::arg("bootstrap_below_s") = diagnose.bootstrap_below_s);
  all["campaign"] = py::dict(py::arg("starts") = campaign.group.starts, py::arg("alpha") = campaign.group.alpha,
                             py::arg("seed") = campaign.group.seed, py::arg("threads") = campaign.threads,
                             py::arg("bootstrap") = acc::RefitBootstrapOptions{}.replicates,  // as the tool's
                             py::arg("bootstrap_below_s") = campaign.group.bootstrap.below_s);
  return all;
}

PYBIND11_MODULE(_core, module)
{
  module.attr("DEFAULTS") = defaults();
  module.doc() = "acc_identification's tools as functions; use the package's own module (import acc_identification)";
  module.def("read_run", &readRun, py::arg("path"), py::arg("follower"), py::arg("all_pairs"), py::arg("max_gap_s"),
             py::arg("topic"), py::arg("acc_engaged_topic"), py::arg("require_acc_engaged"),
             py::arg("acc_engaged_timeout_s"), py::arg("acc_setting"));
  module.def("pair_nmea_logs", &pairNmeaLogs, py::arg("leader_path"), py::arg("follower_path"),
             py::arg("out_path"), py::arg("params_path"), py::arg("antenna_offset_m"), py::arg("leader_antenna_to_rear_bumper_m"),
             py::arg("follower_antenna_to_front_bumper_m"), py::arg("gap_mode"), py::arg("dropout_gap_s"));
  module.def("calibrate", &calibrate, py::arg("runs"), py::arg("inputs_read"), py::arg("split_half"), py::arg("starts"),
             py::arg("alpha"), py::arg("seed"), py::arg("stability_test"), py::arg("verdict_every_s"),
             py::arg("grid_nodes"), py::arg("second_opinion"), py::arg("bootstrap_replicates"),
             py::arg("bootstrap_below_s"));
  module.def("diagnose", &diagnose, py::arg("runs"), py::arg("inputs_read"), py::arg("inputs"),
             py::arg("train_fraction"), py::arg("effects"), py::arg("threads"), py::arg("seed"),
             py::arg("forward_selection"), py::arg("held_out_runs"), py::arg("held_out_inputs"),
             py::arg("bootstrap_replicates"), py::arg("bootstrap_below_s"));
  module.def("check_option", &checkOption, py::arg("name"), py::arg("rule_name"), py::arg("value_text"));
  module.def("campaign", &campaign, py::arg("paths"), py::arg("starts"), py::arg("threads"), py::arg("alpha"),
             py::arg("seed"), py::arg("platoon_check"), py::arg("platoon_diagnosis"), py::arg("bootstrap_replicates"),
             py::arg("bootstrap_below_s"));
}
