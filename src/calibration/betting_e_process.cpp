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

}  // namespace acc
