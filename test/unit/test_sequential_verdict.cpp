// The sequential string-stability verdict (calibration/sequential_verdict.h): (a) the betting
// machinery alone keeps its level under H0 over long sequences, many seeds; (b) seeded synthetic
// drives with a known margin (acc::synthesizeRun: sinusoidal leader with hard brakes, truth
// integrated at a tenth of the data step, GNSS-like noise) are decided right and never withdrawn,
// with looks every 10 s, and drives near the boundary get no wrong decision; (c) the identifier
// node's path (a DriveRecord fed sample by sample, looks whenever the thread would be free) gives
// the same sequence as calibrate --verdict-every (replaySequentialVerdict).
#include <gtest/gtest.h>

#include <array>

#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "acc_identification/calibration/betting_e_process.h"
#include "acc_identification/calibration/drive_record.h"
#include "acc_identification/calibration/sequential_verdict.h"
#include "acc_identification/synthesis/synthetic_runs.h"
#include "acc_identification/synthesis/verdict_study.h"
#include "acc_identification/model/string_stability.h"

namespace
{
constexpr double kAlpha = 0.05;

/// Share of `sequences` sequences of `length` increments drawn by draw(rng) whose e-process ever
/// reaches 1/alpha.
template <typename Draw>
double everRejectedShare(int sequences, int length, Draw draw)
{
  int rejected = 0;
  for (int seed = 0; seed < sequences; ++seed)
  {
    std::mt19937_64 rng(static_cast<std::uint64_t>(seed) * 7919 + 1);
    acc::BettingEProcess e;
    for (int b = 0; b < length && e.maxEValue() < 1.0 / kAlpha; ++b)
    {
      e.add(draw(rng));
    }
    rejected += e.maxEValue() >= 1.0 / kAlpha;
  }
  return static_cast<double>(rejected) / sequences;
}

acc::CarFollowingRun drive(double margin, double duration_s, std::uint32_t seed, double cruise_mps = 22.0)
{
  return acc::synthesizeRun(acc::truthWithMargin(margin), duration_s, 0.1, cruise_mps, seed);
}

/// A decision, once taken, stays in every later look (a reversal would be said, and fails here).
void expectKept(const std::vector<acc::SequentialLook>& looks, const std::string& what)
{
  acc::StabilityVerdict taken = acc::StabilityVerdict::Undecided;
  double previous_p = 1.0;
  for (const acc::SequentialLook& look : looks)
  {
    EXPECT_LE(look.p_value_stable_rejected, 1.0);
    if (taken != acc::StabilityVerdict::Undecided)
    {
      EXPECT_EQ(look.verdict, taken) << what << " at " << look.time_s << " s: " << look.reason;
      EXPECT_LE(look.p_value, previous_p + 1e-15) << what << ": the anytime-valid p-value grew";
    }
    taken = look.verdict;
    previous_p = look.p_value;
    EXPECT_FALSE(look.reversed) << what << ": " << look.reason;
  }
}
}  // namespace

// (a) Under H0 (mean 0, the hardest case of E x <= 0) the e-process reaches 1/alpha in at most
// alpha of the sequences (Ville), whatever the distribution: Rademacher (the largest variance in
// [-1, 1]), uniform, and a skewed one. 2000 sequences of 400 increments each; the Monte-Carlo
// slack is three standard errors (0.015). And it has power: mean 0.3 is found in almost all.
TEST(SequentialVerdict, BettingKeepsItsLevelUnderTheNullAndFindsAMean)
{
  const int sequences = 2000, length = 400;
  const double slack = 3.0 * std::sqrt(kAlpha * (1 - kAlpha) / sequences);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::bernoulli_distribution coin(0.5), rare(0.1);
  const double rademacher = everRejectedShare(sequences, length, [&](auto& rng) { return coin(rng) ? 1.0 : -1.0; });
  const double flat = everRejectedShare(sequences, length, [&](auto& rng) { return uniform(rng); });
  // 0.9 at -1/9, 0.1 at +1: mean 0, rare large gains (a bet that waits for them loses slowly).
  const double skewed = everRejectedShare(sequences, length, [&](auto& rng) { return rare(rng) ? 1.0 : -1.0 / 9.0; });
  std::printf("  ever rejected under H0 (alpha %.2f): Rademacher %.4f, uniform %.4f, skewed %.4f\n", kAlpha,
              rademacher, flat, skewed);
  EXPECT_LE(rademacher, kAlpha + slack);
  EXPECT_LE(flat, kAlpha + slack);
  EXPECT_LE(skewed, kAlpha + slack);
  const double power = everRejectedShare(200, length, [&](auto& rng) { return std::clamp(0.3 + uniform(rng), -1.0, 1.0); });
  EXPECT_GE(power, 0.95);
  // The p-value is 1 / max E: it never grows.
  acc::BettingEProcess e;
  double p = 1.0;
  std::mt19937_64 rng(5);
  for (int b = 0; b < 200; ++b)
  {
    e.add(uniform(rng) + 0.1);
    EXPECT_LE(e.pValue(), p);
    p = e.pValue();
  }
  EXPECT_THROW(acc::BettingEProcess(1.0), std::invalid_argument);
}

// The decision the two e-processes take: kept once taken, and changed only when the other side
// reaches 1/alpha too, which is said (reversed, both times), never a silent withdrawal. Increments
// of +0.8 decide "positive"; a long run of -0.8 afterwards first only erodes the positive side's
// e-value (its max, and so the p-value, stays: still positive), then the negative side's e-process
// reaches 1/alpha and the decision reverses.
TEST(SequentialVerdict, ADecisionIsKeptAndOnlyReversedByEqualEvidence)
{
  acc::SignDecision decision(kAlpha, 0.5);
  double t = 0.0;
  while (decision.sign() == acc::SignDecision::Sign::Undecided && t < 1000.0)
  {
    decision.add(0.8, t += 10.0);
  }
  ASSERT_EQ(decision.sign(), acc::SignDecision::Sign::Positive);
  const double decided_at_s = decision.decidedAtS();
  EXPECT_DOUBLE_EQ(decided_at_s, t);
  const double p_positive = decision.againstNonPositive().pValue();
  EXPECT_LE(p_positive, kAlpha);
  int against = 0;
  while (!decision.reversed() && against < 1000)
  {
    decision.add(-0.8, t += 10.0);
    ++against;
    if (!decision.reversed())
    {
      EXPECT_EQ(decision.sign(), acc::SignDecision::Sign::Positive) << "withdrawn after " << against;
      EXPECT_DOUBLE_EQ(decision.againstNonPositive().pValue(), p_positive);  // monotone: 1 / max E
    }
  }
  ASSERT_TRUE(decision.reversed());
  EXPECT_GT(against, 3);  // one bad block is not enough
  EXPECT_EQ(decision.sign(), acc::SignDecision::Sign::Negative);
  EXPECT_EQ(decision.firstSign(), acc::SignDecision::Sign::Positive);
  EXPECT_DOUBLE_EQ(decision.decidedAtS(), decided_at_s);
  EXPECT_DOUBLE_EQ(decision.reversedAtS(), t);
  EXPECT_LE(decision.againstNonNegative().pValue(), kAlpha);
  EXPECT_THROW(acc::SignDecision(0.0, 0.5), std::invalid_argument);
}

// (b) A clearly stable (m = 3) and a clearly unstable (m = -1) truth, 900 s drives, looks every
// 10 s: decided right, and each decision kept to the end of the drive.
TEST(SequentialVerdict, ClearTruthsAreDecidedRightAndKept)
{
  acc::SequentialVerdictOptions options;
  options.look_period_s = 10.0;
  for (double margin : {3.0, -1.0})
  {
    for (std::uint32_t seed : {101u, 102u})
    {
      const auto looks = acc::replaySequentialVerdict({drive(margin, 900.0, seed)}, options);
      ASSERT_FALSE(looks.empty());
      const std::string what = "m = " + std::to_string(margin) + ", seed " + std::to_string(seed);
      expectKept(looks, what);
      const acc::SequentialLook& last = looks.back();
      std::printf("  %s: %s at %.0f s, final E_unstable %.3g E_stable %.3g, %zu blocks of %.1f s\n", what.c_str(),
                  acc::toString(last.verdict).c_str(), last.decided_at_s, last.e_value_unstable, last.e_value_stable,
                  last.blocks_scored, last.block_length_s);
      EXPECT_EQ(last.verdict, margin > 0 ? acc::StabilityVerdict::Stable : acc::StabilityVerdict::Unstable)
          << what << ": " << last.reason;
      EXPECT_GE(last.time_s, 900.0 - 1e-9);
    }
  }
}

// (b) Near the boundary (m = +-0.3): the data may not decide, but a decision must not be wrong.
TEST(SequentialVerdict, NoWrongDecisionNearTheBoundary)
{
  acc::SequentialVerdictOptions options;
  for (double margin : {0.3, -0.3})
  {
    for (std::uint32_t seed : {201u, 202u, 203u})
    {
      const auto looks = acc::replaySequentialVerdict({drive(margin, 600.0, seed)}, options);
      const std::string what = "m = " + std::to_string(margin) + ", seed " + std::to_string(seed);
      expectKept(looks, what);
      const acc::StabilityVerdict wrong = margin > 0 ? acc::StabilityVerdict::Unstable : acc::StabilityVerdict::Stable;
      for (const acc::SequentialLook& look : looks)
      {
        EXPECT_NE(look.verdict, wrong) << what << " at " << look.time_s << " s: " << look.reason;
      }
      std::printf("  %s: %s (final p %.3g)\n", what.c_str(), acc::toString(looks.back().verdict).c_str(),
                  looks.back().p_value);
    }
  }
}

// (c) The node's path: the drive kept by a DriveRecord fed sample by sample, the stability thread
// free only now and then (every 37 s of data, so scheduled looks are made late and several at a
// time), the data stopping at the end. Same looks, bit for bit, as calibrate --verdict-every.
TEST(SequentialVerdict, NodePathEqualsTheBatchReplay)
{
  acc::CarFollowingRun run = drive(-1.0, 400.0, 301);
  // A hole of 3 s: the drive has two segments and a block straddles the hole.
  for (auto* column : {&run.time_s, &run.space_gap_m, &run.follower_speed_mps, &run.leader_speed_mps})
  {
    column->erase(column->begin() + 2000, column->begin() + 2030);
  }
  acc::SequentialVerdictOptions options;
  options.look_period_s = 10.0;
  acc::DriveRecord record(0.5, 20, 30.0, 5, acc::DriveBound{0, 60.0, 2.0});
  acc::SequentialVerdict live(options);
  std::vector<acc::SequentialLook> live_looks;
  double next_free_s = run.time_s.front() + 37.0;
  for (std::size_t k = 0; k < run.size(); ++k)
  {
    record.add({run.time_s[k], run.space_gap_m[k], run.follower_speed_mps[k], run.leader_speed_mps[k], true});
    const bool last = k + 1 == run.size();
    if (run.time_s[k] >= next_free_s || last)
    {
      for (auto& look : live.lookLive(record.segments(), last))
      {
        live_looks.push_back(look);
      }
      next_free_s += 37.0;
    }
  }
  const auto batch = acc::replaySequentialVerdict(record.segments(), options);
  ASSERT_EQ(live_looks.size(), batch.size());
  ASSERT_GE(batch.size(), 40u);
  for (std::size_t i = 0; i < batch.size(); ++i)
  {
    EXPECT_DOUBLE_EQ(live_looks[i].time_s, batch[i].time_s);
    EXPECT_EQ(live_looks[i].samples, batch[i].samples);
    EXPECT_EQ(live_looks[i].verdict, batch[i].verdict);
    EXPECT_DOUBLE_EQ(live_looks[i].e_value_unstable, batch[i].e_value_unstable) << "look " << i;
    EXPECT_DOUBLE_EQ(live_looks[i].e_value_stable, batch[i].e_value_stable) << "look " << i;
    EXPECT_DOUBLE_EQ(live_looks[i].p_value, batch[i].p_value);
  }
  EXPECT_GE(batch.back().blocks_scored, 3u);
}

// Bad input: no data, a look back in time, flat data: an undecided verdict with the reason.
TEST(SequentialVerdict, BadInputIsUndecidedWithAReason)
{
  acc::SequentialVerdict verdict;
  EXPECT_TRUE(verdict.lookLive({}, true).empty());
  const acc::CarFollowingRun run = drive(1.0, 200.0, 7);
  const auto first = verdict.look({run}, 100.0);
  EXPECT_EQ(first.verdict, acc::StabilityVerdict::Undecided);
  const auto back = verdict.look({run}, 50.0);
  EXPECT_NE(back.reason.find("before the previous look"), std::string::npos) << back.reason;
  acc::CarFollowingRun flat = run;
  for (auto& v : flat.follower_speed_mps)
    v = 20.0;
  verdict.reset();
  const auto flat_look = verdict.look({flat}, 200.0);
  EXPECT_EQ(flat_look.verdict, acc::StabilityVerdict::Undecided);
  EXPECT_NE(flat_look.reason.find("flat data"), std::string::npos) << flat_look.reason;
  acc::CarFollowingRun short_run = run;
  short_run.time_s.resize(100);
  const auto short_look = acc::replaySequentialVerdict({short_run}, {});
  ASSERT_FALSE(short_look.empty());
  EXPECT_NE(short_look.back().reason.find("too few samples"), std::string::npos) << short_look.back().reason;
}

// The truths a study can have: their range is what verdict_study's --margins accepts, and every
// margin in it is reached exactly. --margins 10 once aborted the tool on truthWithMargin's throw.
TEST(VerdictStudy, TheTruthsMarginRangeIsReachedAndNothingBeyond)
{
  const std::array<double, 2> range = acc::truthMarginRange();
  EXPECT_DOUBLE_EQ(range[0], -2.0);
  EXPECT_DOUBLE_EQ(range[1], 7.225);
  for (const double margin : {range[0], -1.0, 0.0, 3.0, 5.5, 6.0, range[1]})
    EXPECT_NEAR(acc::stabilityMargin(acc::truthWithMargin(margin)), margin, 1e-9) << margin;
  EXPECT_THROW(acc::truthWithMargin(range[1] + 0.01), std::invalid_argument);
  EXPECT_THROW(acc::truthWithMargin(range[0] - 0.01), std::invalid_argument);
}

// Power is read only at drive lengths the study simulates: the default checkpoints are cut to a
// shorter drive and its end added; a given one beyond it is refused (it was printed as right@600s
// for drives of 60 s, the end's reading carried on).
TEST(VerdictStudy, CheckpointsLieWithinTheDrives)
{
  acc::VerdictStudyOptions short_drives;
  short_drives.duration_s = 700.0;
  EXPECT_EQ(acc::fitCheckpointsToDuration(&short_drives, false), "");
  EXPECT_EQ(short_drives.checkpoints_s, (std::vector<double>{300.0, 600.0, 700.0}));
  acc::VerdictStudyOptions whole;
  EXPECT_EQ(acc::fitCheckpointsToDuration(&whole, false), "");
  EXPECT_EQ(whole.checkpoints_s, (std::vector<double>{300.0, 600.0, 900.0, 1200.0}));
  acc::VerdictStudyOptions given;
  given.duration_s = 60.0;
  given.checkpoints_s = {30.0, 600.0};
  EXPECT_EQ(acc::fitCheckpointsToDuration(&given, true), "--checkpoints 600 s is longer than each drive (--duration 60 s)");
}

// verdict_study's study (synthesis/verdict_study.h): its tallies follow the looks, and its table
// and JSON say the same.
TEST(VerdictStudy, TalliesTheDrivesOfEachClassAsTheNodeWouldShowThem)
{
  acc::VerdictStudyOptions options;
  options.drives = 2;
  options.duration_s = 300.0;
  options.margins = {-1.0, 1.0};
  options.checkpoints_s = {150.0, 300.0};
  const std::vector<acc::VerdictStudyClass> classes = acc::runVerdictStudy(options, nullptr);
  ASSERT_EQ(classes.size(), 2u);
  for (const acc::VerdictStudyClass& c : classes)
  {
    EXPECT_EQ(c.drives, 2);
    EXPECT_EQ(c.wrong, 0) << "margin " << c.margin;
    EXPECT_EQ(c.withdrawn, 0) << "margin " << c.margin;
    ASSERT_EQ(c.right_by_length.size(), 2u);
    EXPECT_LE(c.right_by_length[0], c.right_by_length[1]);  // a decision kept is still right later
    EXPECT_EQ(c.right_by_length[1], c.decided_right);        // the last checkpoint is the drive's end
    if (c.decided_right > 0)
    {
      EXPECT_GT(c.meanDecidedAtS(), 0.0);
      EXPECT_LE(c.meanDecidedAtS(), 300.0);
    }
  }
  const nlohmann::json json = acc::verdictStudyJson(classes, options);
  EXPECT_EQ(json["classes"][0]["drives"], 2);
  EXPECT_DOUBLE_EQ(json["classes"][1]["power_by_length"][1]["decided_right"].get<double>(),
                   classes[1].right_by_length[1] / 2.0);
  const std::string table = acc::verdictStudyTable(classes, options);
  EXPECT_NE(table.find("right@ 300s"), std::string::npos) << table;
  acc::VerdictStudyClass undecided;  // no drive decided: no mean time, not 0
  undecided.drives = 2;
  undecided.right_by_length = {0, 0};
  EXPECT_TRUE(std::isnan(undecided.meanDecidedAtS()));
  EXPECT_TRUE(acc::verdictStudyJson({undecided}, options)["classes"][0]["mean_decided_at_s"].is_null());
  const std::string undecided_table = acc::verdictStudyTable({undecided}, options);
  EXPECT_EQ(undecided_table.substr(undecided_table.size() - 3), " -\n") << undecided_table;
  EXPECT_NE(table.find("   -1.00       2       0          0"), std::string::npos) << table;
}
