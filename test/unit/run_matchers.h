#pragma once

// Comparing what two readings of the same drive give, for the unit tests of the readers.

#include <gtest/gtest.h>

#include "acc_identification/io/run_csv.h"

namespace acc_test
{
/// Both readings hold one run, sample for sample the same (a variant of a file read as the plain one).
inline void expectTheSameSingleRun(const acc::RunFileContents& a, const acc::RunFileContents& b)
{
  ASSERT_EQ(a.runs.size(), 1u);
  ASSERT_EQ(b.runs.size(), 1u);
  EXPECT_EQ(a.runs[0].time_s, b.runs[0].time_s);
  EXPECT_EQ(a.runs[0].space_gap_m, b.runs[0].space_gap_m);
  EXPECT_EQ(a.runs[0].follower_speed_mps, b.runs[0].follower_speed_mps);
  EXPECT_EQ(a.runs[0].leader_speed_mps, b.runs[0].leader_speed_mps);
}
}  // namespace acc_test
