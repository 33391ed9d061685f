#include "acc_identification/calibration/betting_e_process.h"

#include <algorithm>
#include <stdexcept>

namespace acc
{
namespace
{
/// The variance of the prior pseudo-observation: the largest a variable in [-1, 1] with mean 0
/// could have is 1; 1/4 bets moderately until the data say how spread the increments are.
constexpr double kPriorVariance = 0.25;
}  // namespace

BettingEProcess::BettingEProcess(double max_bet) : max_bet_(max_bet)
{
  if (!(max_bet >= 0.0 && max_bet < 1.0))
  {
    throw std::invalid_argument("BettingEProcess: max_bet must be in [0, 1)");
  }
}

double BettingEProcess::nextBet() const
{
  if (count_ == 0)
  {
    return 0.0;
  }
  const double n = static_cast<double>(count_) + 1.0;  // one pseudo-observation at (0, 1/4)
  const double mean = sum_ / n;
  const double variance = (kPriorVariance + sum_squared_deviation_) / n;
  return std::clamp(mean / (variance + mean * mean), 0.0, max_bet_);
}

void BettingEProcess::add(double x)
{
  x = std::clamp(x, -1.0, 1.0);
  const double bet = nextBet();
  e_value_ *= 1.0 + bet * x;
  max_e_value_ = std::max(max_e_value_, e_value_);
  // The deviation from the mean before x (Welford-like, with the prior's pseudo-observation).
  const double previous_mean = sum_ / (static_cast<double>(count_) + 1.0);
  sum_squared_deviation_ += (x - previous_mean) * (x - previous_mean);
  sum_ += x;
  ++count_;
}

double BettingEProcess::pValue() const
{
  return std::min(1.0, 1.0 / max_e_value_);
}

SignDecision::SignDecision(double alpha, double max_bet)
    : threshold_(1.0 / alpha), on_positive_(max_bet), on_negative_(max_bet)
{
  if (!(alpha > 0.0 && alpha < 1.0))
  {
    throw std::invalid_argument("SignDecision: alpha must be in (0, 1)");
  }
}

void SignDecision::add(double x, double time_s)
{
  on_positive_.add(x);
  on_negative_.add(-x);
  const bool positive_shown = on_positive_.maxEValue() >= threshold_;
  const bool negative_shown = on_negative_.maxEValue() >= threshold_;
  if (sign_ == Sign::Undecided)
  {
    if (positive_shown || negative_shown)
    {
      sign_ = positive_shown ? Sign::Positive : Sign::Negative;
      first_sign_ = sign_;
      decided_at_s_ = time_s;
    }
  }
  else if (!reversed_ && (sign_ == Sign::Positive ? negative_shown : positive_shown))
  {
    sign_ = sign_ == Sign::Positive ? Sign::Negative : Sign::Positive;
    reversed_ = true;
    reversed_at_s_ = time_s;
  }
}

}  // namespace acc
