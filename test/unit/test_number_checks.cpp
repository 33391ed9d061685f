// The tools' number options say what they ask, in words. CLI11 2.1's own PositiveNumber and
// NonNegativeNumber printed their range's ends in full (0.000000 to 1797693134862315...).
#include <string>

#include <gtest/gtest.h>

#include <CLI/CLI.hpp>

#include "acc_identification/tools/bootstrap_options.h"
#include "acc_identification/tools/number_checks.h"

namespace
{
/// The error CLI11 gives for `arguments` ("" when they parse).
std::string parseError(const std::string& arguments)
{
  CLI::App app;
  double positive = 1.0, non_negative = 1.0, alpha = 0.05, below_s = 300.0;
  std::size_t replicates = 199, threads = 0;
  app.add_option("--threads", threads)->check(acc::nonNegativeWholeNumber());
  acc::addRefitBootstrapOptions(app, replicates, below_s, "the fit");
  app.add_option("--positive", positive)->check(acc::positiveNumber());
  app.add_option("--non-negative", non_negative)->check(acc::nonNegativeNumber());
  app.add_option("--alpha", alpha)->check(acc::openInterval(0.0, 1.0));
  double shift_s = 0.0;
  app.add_option("--shift", shift_s)->check(acc::closedInterval(-10.0, 10.0, "SECONDS"));
  try
  {
    app.parse(arguments, false);
  }
  catch (const CLI::ParseError& error)
  {
    return error.what();
  }
  return "";
}
}  // namespace

TEST(NumberChecks, SayWhatTheyAskInWords)
{
  EXPECT_EQ(parseError("--positive 2.5 --non-negative 0"), "");
  EXPECT_NE(parseError("--positive 0").find("must be above 0, not 0"), std::string::npos) << parseError("--positive 0");
  EXPECT_NE(parseError("--non-negative -5").find("must be 0 or more, not -5"), std::string::npos);
  EXPECT_NE(parseError("--positive inf").find("not a finite number: inf"), std::string::npos);
  EXPECT_NE(parseError("--non-negative nan").find("not a finite number: nan"), std::string::npos);
  EXPECT_NE(parseError("--positive abc").find("not a finite number: abc"), std::string::npos);
  EXPECT_EQ(parseError("--non-negative -5").find("1797693"), std::string::npos);
  EXPECT_EQ(parseError("--alpha 0.05"), "");
  EXPECT_NE(parseError("--alpha 0").find("must be above 0 and below 1, not 0"), std::string::npos)
      << parseError("--alpha 0");
  EXPECT_NE(parseError("--alpha 1").find("must be above 0 and below 1, not 1"), std::string::npos);
  // CLI11's Range passed nan (every comparison with NaN is false).
  EXPECT_EQ(parseError("--shift -10"), "");
  EXPECT_EQ(parseError("--shift 10"), "");
  EXPECT_NE(parseError("--shift nan").find("not a finite number: nan"), std::string::npos) << parseError("--shift nan");
  EXPECT_NE(parseError("--shift 10.5").find("must be from -10 to 10, not 10.5"), std::string::npos);
  // A count or seed held unsigned: -1 would wrap to the largest one.
  EXPECT_EQ(parseError("--threads 0"), "");
  EXPECT_EQ(parseError("--threads 2"), "");
  EXPECT_NE(parseError("--threads -1").find("must be a whole number 0 or more, not -1"), std::string::npos)
      << parseError("--threads -1");
  EXPECT_NE(parseError("--threads 1.5").find("must be a whole number 0 or more, not 1.5"), std::string::npos);
}

// A negative replicate count wrapped to a huge unsigned one, whose allocation failed every short
// group's fit ("3 NOT TESTED" where 1 was); fewer than 39 give no 95 % interval.
TEST(NumberChecks, BootstrapReplicatesAreNoneOrEnoughForAnInterval)
{
  EXPECT_EQ(parseError("--bootstrap 0"), "");
  EXPECT_EQ(parseError("--bootstrap 39"), "");
  EXPECT_EQ(parseError("--bootstrap 199"), "");
  for (const char* refused : {"-1", "1", "38", "2.5", "100001"})
    EXPECT_NE(parseError(std::string("--bootstrap ") + refused).find("must be 0 (none) or a whole number from 39 to 100000"),
              std::string::npos)
        << refused << ": " << parseError(std::string("--bootstrap ") + refused);
  EXPECT_NE(parseError("--bootstrap nan").find("not a finite number"), std::string::npos);
}
