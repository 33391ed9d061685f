#pragma once

#include <cstddef>
#include <limits>

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

/// The sign of E[x] decided by two BettingEProcess, one betting on x > 0, one on x < 0: "positive"
/// once the first reaches 1/alpha (max over time), "negative" once the second does; the decision is
/// kept, and should the other one reach 1/alpha later, the decision becomes its side and reversed()
/// says so (with both times): evidence meeting the same standard both ways is reported, never
/// silently withdrawn. Each side errs with probability at most alpha over all time (Ville).
class SignDecision
{
public:
  enum class Sign
  {
    Undecided,
    Positive,
    Negative
  };

  SignDecision(double alpha, double max_bet);

  /// One increment (clipped to [-1, 1]) observed at time_s.
  void add(double x, double time_s);

  Sign sign() const { return sign_; }
  Sign firstSign() const { return first_sign_; }
  bool reversed() const { return reversed_; }
  double decidedAtS() const { return decided_at_s_; }
  double reversedAtS() const { return reversed_at_s_; }
  const BettingEProcess& againstNonPositive() const { return on_positive_; }  ///< bets on x > 0
  const BettingEProcess& againstNonNegative() const { return on_negative_; }  ///< bets on x < 0

private:
  double threshold_;
  BettingEProcess on_positive_;
  BettingEProcess on_negative_;
  Sign sign_ = Sign::Undecided;
  Sign first_sign_ = Sign::Undecided;
  bool reversed_ = false;
  double decided_at_s_ = std::numeric_limits<double>::quiet_NaN();
  double reversed_at_s_ = std::numeric_limits<double>::quiet_NaN();
};

}  // namespace acc
