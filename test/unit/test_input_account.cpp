// The account of what a RUN argument gave (io/input_account.h): every row is used or counted, and
// the JSON says the counts a script cannot get from the log.
#include <gtest/gtest.h>

#include <cstddef>
#include <optional>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "acc_identification/io/input_account.h"
#include "acc_identification/io/run_csv.h"

namespace
{
const std::string kDataDir = ACC_TEST_DATA_DIR;

std::size_t countOf(const acc::InputAccount& account, const std::string& name)
{
  const std::optional<std::size_t> count = account.count(name);
  if (!count)
    ADD_FAILURE() << "no count " << name;
  return count.value_or(0);
}

/// Every data row is a sample of a run, or rejected, or off ACC, or alone between split points.
void expectEveryRowAccountedFor(const acc::RunFileContents& contents)
{
  EXPECT_EQ(contents.data_rows, contents.rejected_rows + contents.acc_off_rows + contents.single_sample_rows +
                                    acc::sampleCount(contents.runs));
}

TEST(InputAccount, EveryRowOfACanonicalFileIsUsedOrCounted)
{
  const acc::RunFileContents contents = acc::readRunFile(kDataDir + "/canonical_with_bad_rows.csv");
  // Three rejected rows, and the one sample (0.7 s) left between two of them.
  EXPECT_EQ(contents.single_sample_rows, 1u);
  expectEveryRowAccountedFor(contents);
  const acc::InputAccount account = acc::accountOfRunFile("bad.csv", contents);
  EXPECT_EQ(account.format, "csv");
  EXPECT_TRUE(account.openacc_pairs.empty());
  EXPECT_EQ(countOf(account, "data_rows"), 11u);
  EXPECT_EQ(countOf(account, "samples_used"), 7u);
  EXPECT_EQ(countOf(account, "runs"), 3u);
  EXPECT_EQ(countOf(account, "rejected_rows"), 3u);
  EXPECT_EQ(countOf(account, "single_sample_rows"), 1u);
  EXPECT_EQ(countOf(account, "gap_rebuilt_rows"), 0u);
}

TEST(InputAccount, RowsOffAccAreCountedAndThePairNamed)
{
  const acc::RunFileContents contents = acc::readRunFile(kDataDir + "/openacc_excerpt.csv");
  expectEveryRowAccountedFor(contents);
  const acc::InputAccount account = acc::accountOfRunFile("excerpt.csv", contents);
  EXPECT_EQ(account.format, "openacc");
  EXPECT_EQ(account.openacc_pairs, std::vector<std::string>{"Hyundai behind Rexton, positions 2/1"});
  EXPECT_EQ(countOf(account, "acc_off_rows"), 1u);
  EXPECT_EQ(countOf(account, "samples_used"), 5u);
}

TEST(InputAccount, ADuplicateAndARowAloneAreCountedApart)
{
  const std::string path = testing::TempDir() + "/input_account_rows.csv";
  {
    std::ofstream file(path);
    // Line 4 repeats line 3; line 5 is not a number; line 6 alone; line 7 goes back in time.
    file << "time_s,space_gap_m,follower_speed_mps,leader_speed_mps\n"
            "0.0,20.0,10.0,10.5\n0.1,20.05,10.01,10.5\n0.1,20.05,10.01,10.5\n0.2,x,10.02,10.5\n"
            "0.3,20.15,10.03,10.5\n0.25,20.2,10.04,10.5\n0.4,20.2,10.04,10.5\n0.5,20.25,10.05,10.5\n";
  }
  const acc::RunFileContents contents = acc::readRunFile(path);
  EXPECT_EQ(contents.duplicate_rows, 1u);
  EXPECT_EQ(contents.rejected_rows, 3u);
  EXPECT_EQ(contents.single_sample_rows, 1u);
  expectEveryRowAccountedFor(contents);
  EXPECT_NE(acc::describeRowCounts(path, contents).find("1 rows alone between split points not used"),
            std::string::npos)
      << acc::describeRowCounts(path, contents);
}

// An OpenACC file's exact repeats are dropped as the file is read; each pair read from it counts
// them as a canonical CSV does, so its counts still add up to the file's rows. Fails when the
// account leaves them out (2302 rows of a doubled file read as 1151 data rows, 0 duplicates).
TEST(InputAccount, AnOpenAccFilesDuplicateRowsAreCountedInThePairsAccount)
{
  const std::string path = testing::TempDir() + "/input_account_openacc_duplicates.csv";
  {
    std::ifstream excerpt(kDataDir + "/openacc_excerpt.csv");
    std::ofstream doubled(path);
    std::string line;
    for (int k = 0; std::getline(excerpt, line); ++k)
      doubled << line << "\n" << (k >= 6 && k < 9 ? line + "\n" : "");  // data lines 1-3 twice
  }
  const acc::RunFileContents once = acc::readRunFile(kDataDir + "/openacc_excerpt.csv");
  const acc::RunFileContents contents = acc::readRunFile(path);
  EXPECT_EQ(contents.duplicate_rows, 3u);
  EXPECT_EQ(contents.data_rows, once.data_rows + 3u);
  EXPECT_EQ(contents.rejected_rows, once.rejected_rows + 3u);
  EXPECT_EQ(acc::sampleCount(contents.runs), acc::sampleCount(once.runs));
  expectEveryRowAccountedFor(contents);
  EXPECT_EQ(countOf(acc::accountOfRunFile(path, contents), "duplicate_rows"), 3u);
}

TEST(InputAccount, JsonKeepsTheCountsAndNamesPairsOnlyForOpenAcc)
{
  acc::InputAccount csv{"a.csv", "csv", {}, {{"data_rows", 5}, {"samples_used", 4}}};
  acc::InputAccount openacc{"b.csv", "openacc", {"X behind Y, positions 2/1"}, {{"data_rows", 3}}};
  const nlohmann::json json = acc::inputAccountsJson({csv, openacc});
  ASSERT_EQ(json.size(), 2u);
  EXPECT_EQ(json[0]["counts"]["samples_used"], 4);
  EXPECT_FALSE(json[0].contains("openacc_pairs"));
  EXPECT_EQ(json[1]["openacc_pairs"][0], "X behind Y, positions 2/1");
  const nlohmann::json pairs = acc::openAccPairsJson({csv, openacc});
  ASSERT_EQ(pairs.size(), 1u);
  EXPECT_EQ(pairs[0]["path"], "b.csv");
  EXPECT_FALSE(acc::anyOpenAcc({csv}));
  EXPECT_TRUE(acc::anyOpenAcc({csv, openacc}));
  std::ostringstream text;
  acc::printOpenAccPairs({csv, openacc}, text);
  EXPECT_EQ(text.str(), "OpenACC pair read: b.csv: X behind Y, positions 2/1\n");
}
}  // namespace
