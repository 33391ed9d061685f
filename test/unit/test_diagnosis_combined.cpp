// The combined-effect suite (combined_effect_suite.h): every pair of effects withheld at once, and
// how its outcomes are counted.
#include <gtest/gtest.h>

#include <cmath>
#include <set>

#include "acc_identification/validation/combined_effect_suite.h"

namespace
{
TEST(CombinedEffectSuite, TheGridHidesEveryPairOfEffectsOnceEachWithItsOwnSeed)
{
  const std::vector<acc::WithheldCase> grid = acc::combinedCaseGrid();
  ASSERT_EQ(grid.size(), 15u);  // 6 effects, choose 2
  std::set<std::set<acc::EffectKind>> pairs;
  std::set<std::uint32_t> seeds;
  for (const acc::WithheldCase& c : grid)
  {
    ASSERT_EQ(c.also_withheld.size(), 1u);
    EXPECT_NE(c.truth, c.also_withheld.front().first);
    EXPECT_FALSE(c.truth_values.empty());
    EXPECT_FALSE(c.also_withheld.front().second.empty());
    pairs.insert({c.truth, c.also_withheld.front().first});
    seeds.insert(c.seed);
  }
  EXPECT_EQ(pairs.size(), 15u);
  EXPECT_EQ(seeds.size(), 15u);
}

acc::CombinedOutcome outcome(std::vector<acc::EffectKind> chain, double fitted_lag, double fitted_limit)
{
  acc::CombinedOutcome o;
  o.withheld = {{acc::EffectKind::actuation_lag, 0.6}, {acc::EffectKind::acceleration_limits, 1.0}};
  o.fitted = {fitted_lag, fitted_limit};
  o.chain = std::move(chain);
  return o;
}

TEST(CombinedEffectSuite, CountsWhatTheChainNamesAndWhatItNamesWrongly)
{
  const double nan = std::nan("");
  const acc::CombinedOutcome both =
      outcome({acc::EffectKind::actuation_lag, acc::EffectKind::acceleration_limits}, 0.63, 0.9);
  const acc::CombinedOutcome one_and_wrong =
      outcome({acc::EffectKind::reaction_delay, acc::EffectKind::acceleration_limits}, nan, 1.0);
  const acc::CombinedOutcome none = outcome({}, nan, nan);
  EXPECT_EQ(both.named(), 2u);
  EXPECT_TRUE(both.extra().empty());
  EXPECT_EQ(one_and_wrong.named(), 1u);
  ASSERT_EQ(one_and_wrong.extra().size(), 1u);
  EXPECT_EQ(one_and_wrong.extra().front(), acc::EffectKind::reaction_delay);
  EXPECT_EQ(none.named(), 0u);

  const std::string tables = acc::formatCombinedTables({both, one_and_wrong, none});
  EXPECT_NE(tables.find("pairs: 3; both named: 1; one named: 1; neither: 1; chain names an effect not withheld: 1"),
            std::string::npos)
      << tables;
  // Per effect: the lag was withheld 3 times and named once (error 5 %); the delay never withheld,
  // named once wrongly.
  EXPECT_NE(tables.find("| actuation_lag | 1 of 3 | 0 of 0 | 5% |"), std::string::npos) << tables;
  EXPECT_NE(tables.find("| reaction_delay | 0 of 0 | 1 of 3 | - |"), std::string::npos) << tables;
  EXPECT_NE(tables.find("0.63 (+5%)"), std::string::npos) << tables;
}

// The suite itself (about 20 s): measured 13 of 15 pairs named whole, none named wrongly, and where
// whole every magnitude within 8 % but the gap slope behind a set speed. Held to 12, 0 and 10 %, so
// a change to the selection that loses pairs or invents effects fails here.
TEST(CombinedEffectSuite, TheChainNamesBothHiddenEffectsInMostPairsAndNeverOneNotHidden)
{
  std::size_t whole = 0, wrong = 0;
  for (const acc::WithheldCase& c : acc::combinedCaseGrid())
  {
    const acc::CombinedOutcome o = acc::runCombinedCase(c, acc::DiagnosisOptions{});
    const bool named_whole = o.named() == o.withheld.size();
    whole += named_whole ? 1 : 0;
    wrong += o.extra().size();
    // Magnitudes mean something where the chain holds both (one effect alone stands in for two).
    for (std::size_t i = 0; named_whole && i < o.withheld.size(); ++i)
    {
      if (std::isfinite(o.fitted[i]) && o.withheld[i].first != acc::EffectKind::speed_dependent_time_gap)
      {
        EXPECT_NEAR(o.fitted[i], o.withheld[i].second, 0.1 * std::abs(o.withheld[i].second))
            << acc::effectName(o.withheld[i].first) << " in case seed " << c.seed;
      }
    }
  }
  EXPECT_GE(whole, 12u);
  EXPECT_EQ(wrong, 0u);
}
}  // namespace
