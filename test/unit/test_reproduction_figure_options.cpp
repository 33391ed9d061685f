// The figures' options (reproduction/figure_options.h, paper_figures.cpp, simulated_figures.cpp): a
// platoon, a step or a map too large for the machine is refused with the options that make it so,
// before anything is allocated, where it once ran until the allocator failed (9 GB for --time-step
// 1e-9); options a figure does not read, values outside the model's domain, a step outside its run
// and a platoon that runs away are refused or flagged.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "acc_identification/reproduction/figure_options.h"
#include "acc_identification/reproduction/measured_figures.h"
#include "acc_identification/reproduction/paper_figures.h"
#include "acc_identification/reproduction/simulated_figures.h"

namespace
{
/// The FigureUsageError's message of making the figure with these options, or "" when it is made.
std::string refusalOf(const std::string& figure, const std::map<std::string, std::vector<std::string>>& given)
{
  const std::string csv = testing::TempDir() + "/figure_options_test.csv";
  static std::FILE* const quiet = std::fopen("/dev/null", "w");
  try
  {
    acc::runPaperFigure(figure, acc::FigureOptions(given), csv, acc::FigureStreams{quiet, quiet});
  }
  catch (const acc::FigureUsageError& error)
  {
    return error.what();
  }
  std::filesystem::remove(csv);
  return "";
}
}  // namespace

TEST(FigureOptions, APlatoonTooLargeToHoldIsRefusedNamingWhatToChange)
{
  const std::string long_drive = refusalOf("sinusoid", {{"duration", {"1e9"}}});
  EXPECT_NE(long_drive.find("11 cars over 1e+09 s at a 0.1 s step"), std::string::npos) << long_drive;
  EXPECT_NE(long_drive.find("fewer --vehicles, a shorter --duration or --tail"), std::string::npos) << long_drive;
  EXPECT_NE(refusalOf("step", {{"vehicles", {"1000000"}}}).find("1000001 cars"), std::string::npos);
  EXPECT_NE(refusalOf("lead-profile", {{"tail", {"1e9"}}}).find("61 cars"), std::string::npos);
  EXPECT_NE(refusalOf("lead-profile", {{"lead-decel", {"1e-9"}}}).find("--lead-decel must be from 0.01 to 20"),
            std::string::npos);
}

TEST(FigureOptions, TheStepAndTheMapGridAreBounded)
{
  EXPECT_EQ(refusalOf("step", {{"time-step", {"1e-9"}}}), "--time-step must be from 0.001 to 1, not 1e-09");
  EXPECT_EQ(refusalOf("step", {{"time-step", {"2"}}}), "--time-step must be from 0.001 to 1, not 2");
  EXPECT_NE(refusalOf("lambda2-map", {{"grid", {"100000"}}}).find("--grid must be at most 2000"), std::string::npos);
  // Within the bounds a figure is made.
  EXPECT_EQ(refusalOf("step", {{"time-step", {"0.05"}}, {"duration", {"100"}}, {"vehicles", {"3"}}}), "");
}

// An option the figure does not read is refused rather than ignored (a typo, or --duration given to
// lead-profile, whose length is --tail), as is a single-valued option given twice (the last one
// silently won).
TEST(FigureOptions, AnOptionTheFigureDoesNotReadOrOneGivenTwiceIsRefused)
{
  const std::string unused = refusalOf("bode", {{"vehicles", {"3"}}});
  EXPECT_NE(unused.find("--vehicles is not an option of bode"), std::string::npos) << unused;
  EXPECT_NE(unused.find("--min-frequency"), std::string::npos) << unused;  // what it does take
  EXPECT_NE(refusalOf("lead-profile", {{"duration", {"100"}}}).find("--duration is not an option of lead-profile"),
            std::string::npos);
  EXPECT_NE(refusalOf("fig1", {{"setting", {"min"}}}).find("--setting is not an option of fig1"), std::string::npos);
  const std::string twice = refusalOf("step", {{"k1", {"0.1", "0.3"}}, {"k2", {"0.2"}}, {"tau-e", {"1"}}});
  EXPECT_EQ(twice, "--k1 given 2 times: which value is meant is not said (it takes one)");
  EXPECT_EQ(refusalOf("bode", {{"setting", {"min", "max"}}}), "");  // repeatable
}

// The model's domain (gains and time gap of 0 or more) and a step inside its run.
TEST(FigureOptions, NegativeGainsAndAStepOutsideItsRunAreRefused)
{
  EXPECT_EQ(refusalOf("bode", {{"k1", {"-0.1"}}, {"k2", {"0.4"}}, {"tau-e", {"1"}}}),
            "--k1 must be from 0 to 1e+06, not -0.1");
  EXPECT_NE(refusalOf("step", {{"step-down-at", {"100"}}, {"step-up-at", {"50"}}}).find("0 < down < up"),
            std::string::npos);
  EXPECT_NE(refusalOf("step", {{"step-down-at", {"-10"}}}).find("0 < down < up"), std::string::npos);
  EXPECT_NE(refusalOf("step", {{"step", {"30"}}}).find("must be below --speed"), std::string::npos);
  EXPECT_NE(refusalOf("sinusoid", {{"amplitude", {"25"}}}).find("--amplitude must be below --speed"),
            std::string::npos);
  EXPECT_NE(refusalOf("fig8", {{"tail", {"-100"}}}).find("--tail must be from 0"), std::string::npos);
}

// A platoon whose Euler recursion runs away is said, and flagged in the summary, where its speeds of
// 1e200 m/s were printed as a figure's numbers.
TEST(FigureOptions, APlatoonThatRunsAwayIsFlagged)
{
  const std::string csv = testing::TempDir() + "/runaway_step.csv";
  static std::FILE* const quiet = std::fopen("/dev/null", "w");
  const nlohmann::json summary = acc::runPaperFigure(
      "step", acc::FigureOptions({{"k1", {"2"}}, {"k2", {"3"}}, {"tau-e", {"5"}}, {"time-step", {"1"}}}), csv,
      acc::FigureStreams{quiet, quiet});
  ASSERT_EQ(summary["settings"].size(), 1u);
  EXPECT_FALSE(summary["settings"][0]["runaway"].is_null()) << summary.dump();
  const nlohmann::json calm = acc::runPaperFigure("step", acc::FigureOptions({}), csv, acc::FigureStreams{quiet, quiet});
  EXPECT_TRUE(calm["settings"][0]["runaway"].is_null());
  std::filesystem::remove(csv);
}

// Each figure's list of options (figureOptionNames, what the tool accepts for it) is what the figure
// reads: a figure that starts reading an option must list it, and a listed option must be read.
TEST(FigureOptions, EachFiguresListIsWhatItReads)
{
  const std::string run = testing::TempDir() + "/steady_run.csv";
  {
    std::FILE* out = std::fopen(run.c_str(), "w");
    std::fprintf(out, "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n");
    for (int k = 0; k < 600; ++k)
      std::fprintf(out, "%.1f,%.3f,%.3f,%.3f\n", 0.1 * k, 30.0 + 0.01 * k, 20.0 + 0.001 * k, 20.0 + 0.001 * k);
    std::fclose(out);
  }
  static std::FILE* const quiet = std::fopen("/dev/null", "w");
  const std::string csv = testing::TempDir() + "/figure_reads.csv";
  const std::map<std::string, nlohmann::json (*)(const acc::FigureRequest&)> makers{
      {"lambda2-map", acc::lambda2MapFigure}, {"step", acc::stepFigure},
      {"bode", acc::bodeFigure},               {"sinusoid", acc::sinusoidFigure},
      {"lead-profile", acc::leadProfileFigure}, {"equilibrium", acc::equilibriumFigure},
      {"timeseries", acc::timeseriesFigure}};
  for (const auto& [figure, make] : makers)
  {
    std::map<std::string, std::vector<std::string>> given;
    if (figure == "equilibrium" || figure == "timeseries")
      given["run"] = {run};
    if (figure == "lambda2-map")
      given["grid"] = {"3"};
    const acc::FigureRequest request{acc::FigureOptions(given), csv, 0.1, acc::FigureStreams{quiet, quiet}};
    make(request);
    std::set<std::string> listed;
    for (const std::string& name : acc::figureOptionNames(figure))
      if (name != "time-step")  // read by runPaperFigure for the figures that simulate at a step
        listed.insert(name);
    EXPECT_EQ(request.options.namesRead(), listed) << figure;
  }
  std::filesystem::remove(csv);
  std::filesystem::remove(run);
}
