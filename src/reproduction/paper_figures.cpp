#include "acc_identification/reproduction/paper_figures.h"

#include <algorithm>
#include <cstdio>
#include <functional>
#include <map>

#include "acc_identification/reproduction/measured_figures.h"
#include "acc_identification/reproduction/parameter_file.h"
#include "acc_identification/reproduction/simulated_figures.h"

namespace acc
{
namespace
{
const char* kFigures = R"(FIGURE: a name or the paper's figure number (fig1 to fig8), with each option's default:
  lambda2-map  (fig1)  lambda2 over (k1, k2) for several tau_e; --map-tau-e 0.5,1,1.5,2,3
                       --k1-max 1 --k2-max 1 --grid 100
  step         (fig2)  platoon behind a lead speed step down and back up; --vehicles 9 --speed 25
                       --step 5 --step-down-at 20 --step-up-at 60 --duration 200
                       (default settings: fig2-unstable, fig2-stable)
  bode         (fig6)  |Gamma(jw)| in dB; --min-frequency 0.001 --max-frequency 10 --points 400
  sinusoid     (fig7)  platoon behind a sinusoidal lead; --vehicles 10 --speed 20 --amplitude 1
                       --frequency 0.204 --lead-in 20 --duration 620 --fit-periods 5
  lead-profile (fig8)  platoon behind lead profile A..I of Sec. III; --profile I --vehicles 60
                       --short-platoon 15 --tail 600 [--lead-accel 1.5 --lead-decel 2.0]
  equilibrium  (fig5)  space gap against speed of runs with the equilibrium lines eta + tau_e v;
                       --run RUN.csv (repeatable) --max-relative-speed 0.5 --max-acceleration 0.1
  timeseries   (fig3, fig4) measured against simulated speed and gap of one run, split into
                       train and test parts; --run RUN.csv --train-fraction 0.5
settings (repeatable, in order; default min and max of Table II):
  --setting min|max|fig2-unstable|fig2-stable   --params CALIBRATE.json
  --k1 K1 --k2 K2 --tau-e TAU [--eta ETA]       (one custom set, named "custom")
step, bode, sinusoid, lead-profile: --time-step 0.1 (their simulations' Euler step, 0.001 to 1 s)
An option the figure does not read, or a single-valued option given twice, is an error.
RUN.csv: canonical (time_s,space_gap_m,follower_speed_mps,leader_speed_mps) or OpenACC two-vehicle CSV.
)";

/// The paper's figure numbers, as a reader types them, for the names the figures have here.
const std::map<std::string, std::string> kFigureNumbers{
    {"fig1", "lambda2-map"}, {"fig2", "step"}, {"fig3", "timeseries"}, {"fig4", "timeseries"},
    {"fig5", "equilibrium"}, {"fig6", "bode"}, {"fig7", "sinusoid"},   {"fig8", "lead-profile"}};

/// The options of the figures that draw parameter sets (resolveSettings).
const std::vector<std::string> kSettingOptions{"setting", "params", "k1", "k2", "tau-e", "eta"};

/// Each figure's own value options, by its name (the test of the figures holds these to what each
/// one reads).
const std::map<std::string, std::vector<std::string>> kFigureOwnOptions{
    {"lambda2-map", {"map-tau-e", "k1-max", "k2-max", "grid"}},
    {"step", {"time-step", "vehicles", "speed", "step", "step-down-at", "step-up-at", "duration"}},
    {"bode", {"time-step", "min-frequency", "max-frequency", "points"}},
    {"sinusoid", {"time-step", "vehicles", "speed", "amplitude", "frequency", "lead-in", "duration", "fit-periods"}},
    {"lead-profile", {"time-step", "profile", "vehicles", "short-platoon", "tail", "lead-accel", "lead-decel"}},
    {"equilibrium", {"run", "max-relative-speed", "max-acceleration"}},
    {"timeseries", {"run", "train-fraction"}}};

std::string canonicalFigure(const std::string& figure)
{
  const auto alias = kFigureNumbers.find(figure);
  return alias == kFigureNumbers.end() ? figure : alias->second;
}

/// Each figure by its name.
const std::map<std::string, std::function<nlohmann::json(const FigureRequest&)>> kFigureMakers{
    {"lambda2-map", lambda2MapFigure}, {"step", stepFigure},
    {"bode", bodeFigure},               {"sinusoid", sinusoidFigure},
    {"lead-profile", leadProfileFigure}, {"equilibrium", equilibriumFigure},
    {"timeseries", timeseriesFigure}};
}  // namespace

const char* paperFiguresHelp()
{
  return kFigures;
}

std::vector<std::string> acceptedFigures()
{
  std::vector<std::string> accepted{"lambda2-map",  "step",        "bode",      "sinusoid",
                                    "lead-profile", "equilibrium", "timeseries"};
  for (const auto& number : kFigureNumbers)
    accepted.push_back(number.first);
  return accepted;
}

std::vector<std::string> figureOptionNames(const std::string& figure)
{
  const auto own = kFigureOwnOptions.find(canonicalFigure(figure));
  if (own == kFigureOwnOptions.end())
    return {};
  std::vector<std::string> names = own->second;
  if (own->first != "lambda2-map")
    names.insert(names.end(), kSettingOptions.begin(), kSettingOptions.end());
  return names;
}

nlohmann::json runPaperFigure(const std::string& figure, const FigureOptions& options, const std::string& csv_path,
                              const FigureStreams& streams)
{
  const auto found = kFigureMakers.find(canonicalFigure(figure));
  if (found == kFigureMakers.end())
  {
    throw FigureUsageError("unknown figure '" + figure + "'");
  }
  const std::vector<std::string> accepted = figureOptionNames(figure);
  for (const std::string& name : options.namesGiven())
  {
    if (std::find(accepted.begin(), accepted.end(), name) == accepted.end())
    {
      std::string list;
      for (const std::string& option : accepted)
        list += (list.empty() ? "--" : ", --") + option;
      throw FigureUsageError("--" + name + " is not an option of " + figure +
                             ", which would not use it (its options: " + list + ")");
    }
  }
  for (const std::string& path : options.texts("params"))
    if (const std::string why = describeUndeterminedParameterFile(path); !why.empty() && streams.notes != nullptr)
      std::fprintf(streams.notes, "warning: %s\n", why.c_str());
  const bool steps = std::find(accepted.begin(), accepted.end(), "time-step") != accepted.end();
  const FigureRequest request{options, csv_path, steps ? options.between("time-step", 0.1, 1e-3, 1.0) : 0.1, streams};
  try
  {
    return found->second(request);
  }
  catch (const std::invalid_argument& error)
  {
    // The libraries' refusal of a value (a frequency range upside down, a negative time gap in
    // --map-tau-e) is the user's option, as the figures' own checks are: usage, exit 2.
    throw FigureUsageError(error.what());
  }
}

}  // namespace acc
