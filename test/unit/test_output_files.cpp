// The tools' output helpers (io/output_files.h): written files, folders that cannot be made, a
// missing figure script, each said on the error stream rather than failing silently.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>

#include "acc_identification/io/csv_fields.h"
#include "acc_identification/io/output_files.h"

namespace
{
std::string scratchDir(const std::string& name)
{
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / ("acc_output_files_" + name);
  std::filesystem::remove_all(dir);
  return dir.string();
}
}  // namespace

TEST(OutputFiles, JsonIsWrittenIndentedWithANewline)
{
  const std::string dir = scratchDir("json");
  std::ostringstream errors;
  ASSERT_TRUE(acc::makeOutputFolder(dir + "/a/b", errors)) << errors.str();
  ASSERT_TRUE(acc::writeJsonFile({{"k1", 0.1}}, dir + "/a/b/x.json", errors));
  std::ifstream in(dir + "/a/b/x.json");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_EQ(text, "{\n  \"k1\": 0.1\n}\n");
  EXPECT_TRUE(errors.str().empty());
  std::filesystem::remove_all(dir);
}

TEST(OutputFiles, WhatCannotBeWrittenIsSaid)
{
  std::ostringstream errors;
  EXPECT_FALSE(acc::makeOutputFolder("/proc/acc_nope/report", errors));
  EXPECT_NE(errors.str().find("error: cannot create /proc/acc_nope/report"), std::string::npos) << errors.str();
  errors.str("");
  EXPECT_FALSE(acc::writeTextFile("x", "/proc/acc_nope/x.txt", errors));
  EXPECT_NE(errors.str().find("error: cannot write /proc/acc_nope/x.txt"), std::string::npos) << errors.str();
}

TEST(OutputFiles, AMissingFigureScriptIsNamedAndWhatWasWrittenToo)
{
  const std::string dir = scratchDir("figures");
  std::ostringstream errors;
  ASSERT_TRUE(acc::makeOutputFolder(dir, errors));
  EXPECT_FALSE(acc::drawReportFigures(dir + "/no_such_plot.py", dir, "tables and JSON", errors));
  EXPECT_NE(errors.str().find("no figure script at " + dir + "/no_such_plot.py"), std::string::npos) << errors.str();
  EXPECT_NE(errors.str().find("tables and JSON are in " + dir), std::string::npos) << errors.str();
  // A script that fails: the command is named.
  std::ofstream(dir + "/fails.py") << "import sys\nsys.exit(3)\n";
  errors.str("");
  EXPECT_FALSE(acc::drawReportFigures(dir + "/fails.py", dir, "tables and JSON", errors));
  EXPECT_NE(errors.str().find("the report figures failed"), std::string::npos) << errors.str();
  // One that works: the report is pointed to.
  std::ofstream(dir + "/works.py") << "import sys\nopen(sys.argv[1] + '/report.md', 'w').write('# r\\n')\n";
  errors.str("");
  EXPECT_TRUE(acc::drawReportFigures(dir + "/works.py", dir, "tables and JSON", errors)) << errors.str();
  EXPECT_TRUE(std::filesystem::exists(dir + "/report.md"));
  EXPECT_NE(errors.str().find("report: " + dir + "/report.md"), std::string::npos);
  std::filesystem::remove_all(dir);
}

TEST(OutputFiles, AReportFolderWithSpacesAndQuotesGetsItsFigures)
{
  const std::string dir = scratchDir("quotes") + "/Bob's \"field\" day $HOME";
  std::ostringstream errors;
  ASSERT_TRUE(acc::makeOutputFolder(dir, errors));
  std::ofstream(dir + "/works.py") << "import sys\nopen(sys.argv[1] + '/report.md', 'w').write('# r\\n')\n";
  EXPECT_TRUE(acc::drawReportFigures(dir + "/works.py", dir, "tables and JSON", errors)) << errors.str();
  EXPECT_TRUE(std::filesystem::exists(dir + "/report.md"));
  std::filesystem::remove_all(std::filesystem::path(dir).parent_path());
}

TEST(OutputFiles, AnOutputOverAnInputOrAnotherOutputIsRefusedBeforeAnythingIsWritten)
{
  const std::string dir = scratchDir("over_input");
  std::ostringstream errors;
  ASSERT_TRUE(acc::makeOutputFolder(dir + "/sub", errors));
  std::ofstream(dir + "/run.csv") << "time_s\n";
  // The same file however it is spelled, and through a link.
  std::filesystem::create_symlink(dir + "/run.csv", dir + "/link.csv");
  for (const std::string& spelled : {dir + "/run.csv", dir + "/sub/../run.csv", dir + "/./run.csv", dir + "/link.csv"})
  {
    errors.str("");
    EXPECT_FALSE(acc::outputsLeaveInputsAlone({dir + "/other.csv", dir + "/run.csv"}, {"", spelled}, errors)) << spelled;
    EXPECT_NE(errors.str().find("error: " + spelled + " would overwrite the input " + dir + "/run.csv"),
              std::string::npos)
        << errors.str();
  }
  // Two outputs that are one file, whether it exists yet or not.
  errors.str("");
  EXPECT_FALSE(acc::outputsLeaveInputsAlone({}, {dir + "/new.nmea", dir + "/sub/../new.nmea"}, errors));
  EXPECT_NE(errors.str().find("two outputs name the same file"), std::string::npos) << errors.str();
  EXPECT_FALSE(std::filesystem::exists(dir + "/new.nmea"));
  // Different files, outputs not asked for (empty), and an output in the inputs' folder are fine.
  errors.str("");
  EXPECT_TRUE(acc::outputsLeaveInputsAlone({dir + "/run.csv", dir}, {dir + "/fit.json", "", "", dir + "/sub/x.json"},
                                           errors))
      << errors.str();
  EXPECT_TRUE(errors.str().empty());
  std::ifstream kept(dir + "/run.csv");
  EXPECT_EQ(std::string((std::istreambuf_iterator<char>(kept)), std::istreambuf_iterator<char>()), "time_s\n");
  std::filesystem::remove_all(dir);
}

// A run name as the tools write it into their CSVs (fit_traces, residuals, train_fit, spectrum,
// the equilibrium figure) reads back whole, commas and quotes in it included, as spreadsheet and
// Python's csv read it. Fails if a quote is not doubled or a comma splits the name.
TEST(OutputFiles, ARunNameWrittenIntoACsvReadsBackWhole)
{
  for (const std::string& name : {std::string("part3 Hyundai"), std::string("com,ma"), std::string("end\""),
                                   std::string("\"quoted\", and more"), std::string("")})
  {
    const std::vector<std::string> fields = acc::splitCsvFields(acc::csvQuoted(name) + ",train,1.5");
    ASSERT_EQ(fields.size(), 3u) << name;
    EXPECT_EQ(fields[0], name);
    EXPECT_EQ(fields[1], "train");
  }
  EXPECT_EQ(acc::csvQuoted("end\""), "\"end\"\"\"");
}
