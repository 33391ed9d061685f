// The numbers of the package's texts (model/number_text.h), written one way everywhere.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "acc_identification/model/number_text.h"

TEST(NumberText, SignificantDigitsAsPercentG)
{
  EXPECT_EQ(acc::significant(0.123456), "0.1235");
  EXPECT_EQ(acc::significant(69.9), "69.9");
  EXPECT_EQ(acc::significant(80.0), "80");
  EXPECT_EQ(acc::significant(1.23456e-5), "1.235e-05");
  EXPECT_EQ(acc::significant(11073.94, 6), "11073.9");
}

TEST(NumberText, CellsSayNaNForWhatIsNotANumberAndInfForAnUnboundedEnd)
{
  EXPECT_EQ(acc::cellNumber("%.3f", 0.12345), "0.123");
  EXPECT_EQ(acc::cellNumber("%.3f", std::numeric_limits<double>::quiet_NaN()), "NaN");
  EXPECT_EQ(acc::cellNumber("%.1f", std::numeric_limits<double>::infinity()), "inf");
  EXPECT_EQ(acc::cellNumber("%.1f", -std::numeric_limits<double>::infinity()), "-inf");
  EXPECT_EQ(acc::printfText("%s at %.1f s", "dip", 12.25), "dip at 12.2 s");
}

// A reason longer than 255 characters comes out whole: printfText once cut it there, mid-word
// (nmea_to_csv's refusal of swapped logs lost its last words). Fails if the text is truncated.
TEST(NumberText, ALongReasonIsNotCut)
{
  const std::string words(300, 'w');
  const std::string text = acc::printfText("%s: slope %.2f, the end", words.c_str(), -0.97);
  EXPECT_EQ(text.size(), 300u + std::string(": slope -0.97, the end").size());
  EXPECT_EQ(text.substr(300), ": slope -0.97, the end");
  EXPECT_EQ(acc::printfText("%d s", 5), "5 s");
}
