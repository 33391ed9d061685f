#pragma once

#include <cstddef>

namespace acc
{
/// Testing by betting (Shafer 2021; Waudby-Smith & Ramdas 2023, JRSS-B 86(1)): an e-process
/// against H0: E[x_b | x_1..x_{b-1}] <= 0 for every b, for increments x_b in [-1, 1].
///
/// E_t = prod_{b <= t} (1 + lambda_b x_b) with the bet lambda_b in [0, max_bet] chosen from
/// x_1..x_{b-1} only (predictable). Under H0, E[1 + lambda_b x_b | past] <= 1, so E_t is a
/// nonnegative supermartingale with E_0 = 1 and, by Ville's inequality,
/// P(sup_t E_t >= 1/alpha) <= alpha: the test may be looked at after every increment. max_bet < 1
/// keeps every factor >= 1 - max_bet > 0, so one bad block never wipes the wealth out.
///
/// The bet is aGRAPA (approximate growth-rate adaptive to the particular alternative, ibid.
/// Section 5.3): lambda = mu / (sigma^2 + mu^2), the Kelly bet for a mean mu and variance sigma^2,
/// from running estimates shrunk towards mu = 0, sigma^2 = 1/4 by one pseudo-observation, clipped
/// to [0, max_bet]. Before any increment the bet is 0: the first block only teaches.
class BettingEProcess
{
public:
  explicit BettingEProcess(double max_bet = 0.5);

  /// The bet on the next increment (from the past ones only).
  double nextBet() const;
  /// Takes x (clipped to [-1, 1]) at the bet nextBet() gave before it.
  void add(double x);

  double eValue() const { return e_value_; }
  /// max_{s <= t} E_s: 1 / this is the anytime-valid p-value (monotone: never grows).
  double maxEValue() const { return max_e_value_; }
  double pValue() const;
  std::size_t increments() const { return count_; }

private:
  double max_bet_;
  double e_value_ = 1.0;
  double max_e_value_ = 1.0;
  double sum_ = 0.0;
  double sum_squared_deviation_ = 0.0;
  std::size_t count_ = 0;
};

}  // namespace acc
