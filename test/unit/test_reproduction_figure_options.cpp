// The figures' sizes (reproduction/figure_options.h, simulated_figures.cpp): a platoon, a step or a
// map too large for the machine is refused with the options that make it so, before anything is
// allocated, where it once ran until the allocator failed (9 GB for --time-step 1e-9).
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "acc_identification/reproduction/figure_options.h"
#include "acc_identification/reproduction/paper_figures.h"

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
