#include "acc_identification/calibration/sequential_verdict.h"
#include "acc_identification/model/number_text.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>

#include "acc_identification/calibration/fit_statistics.h"
#include "acc_identification/calibration/held_out_side_comparison.h"
#include "acc_identification/model/sample_statistics.h"

namespace acc
{
namespace
{
StabilityVerdict verdictOf(SignDecision::Sign sign)
{
  switch (sign)
  {
    case SignDecision::Sign::Positive: return StabilityVerdict::Unstable;  // the stable model predicts worse
    case SignDecision::Sign::Negative: return StabilityVerdict::Stable;
    case SignDecision::Sign::Undecided: break;
  }
  return StabilityVerdict::Undecided;
}

/// The samples of each run with from_s <= t < to_s (to_s included when include_end), as runs of
/// at least two samples (a piece's first sample is its measured start, never scored).
std::vector<CarFollowingRun> piecesBetween(const std::vector<CarFollowingRun>& runs, double from_s, double to_s,
                                           bool include_end)
{
  std::vector<CarFollowingRun> pieces;
  for (const CarFollowingRun& run : runs)
  {
    const auto begin = std::lower_bound(run.time_s.begin(), run.time_s.end(), from_s);
    const auto end = include_end ? std::upper_bound(run.time_s.begin(), run.time_s.end(), to_s)
                                 : std::lower_bound(run.time_s.begin(), run.time_s.end(), to_s);
    if (end - begin < 2)
    {
      continue;
    }
    const std::size_t first = static_cast<std::size_t>(begin - run.time_s.begin());
    const std::size_t last = static_cast<std::size_t>(end - run.time_s.begin());
    CarFollowingRun piece;
    piece.name = run.name;
    auto copy = [&](const std::vector<double>& from, std::vector<double>& to) {
      to.assign(from.begin() + static_cast<std::ptrdiff_t>(first), from.begin() + static_cast<std::ptrdiff_t>(last));
    };
    copy(run.time_s, piece.time_s);
    copy(run.space_gap_m, piece.space_gap_m);
    copy(run.follower_speed_mps, piece.follower_speed_mps);
    copy(run.leader_speed_mps, piece.leader_speed_mps);
    pieces.push_back(std::move(piece));
  }
  return pieces;
}

/// Data times are clock times (e.g. 56738.0 s of the day): fixed, to the tenth of a second.
std::string formatTime(double time_s)
{
  std::ostringstream out;
  out.setf(std::ios::fixed);
  out.precision(1);
  out << time_s;
  return out.str();
}

}  // namespace

MultistartOptions SequentialVerdictOptions::defaultFirstMultistart()
{
  MultistartOptions options;
  options.starts = 8;
  return options;
}

ConstrainedFitOptions SequentialVerdictOptions::defaultFirstConstrained()
{
  ConstrainedFitOptions options;
  options.starts = 8;
  options.max_local_solves = 2;
  return options;
}

MultistartOptions SequentialVerdictOptions::defaultRefitMultistart()
{
  MultistartOptions options;
  options.starts = 0;
  options.max_evaluations_per_start = 60;
  // The previous look's optimum moved only by ten seconds of data: stop once the mean squared
  // error changes by less than 1e-8 of itself, far below what a block's score can tell apart.
  options.relative_f_tolerance = 1e-8;
  return options;
}

ConstrainedFitOptions SequentialVerdictOptions::defaultRefitConstrained()
{
  return ConstrainedFitOptions::warmStartsOnly(2, 60);
}

SequentialVerdict::SequentialVerdict(SequentialVerdictOptions options)
    : options_(std::move(options)), decision_(options_.alpha, options_.max_bet)
{
}

void SequentialVerdict::reset()
{
  *this = SequentialVerdict(options_);
}

std::vector<SequentialLook> SequentialVerdict::lookUpTo(const std::vector<CarFollowingRun>& drive_so_far, double last_s)
{
  std::vector<SequentialLook> looks;
  if (!drive_start_s_)
  {
    for (const CarFollowingRun& run : drive_so_far)
    {
      if (!run.time_s.empty())
      {
        drive_start_s_ = std::min(drive_start_s_.value_or(run.time_s.front()), run.time_s.front());
      }
    }
  }
  if (!drive_start_s_ || !(options_.look_period_s > 0.0) || !std::isfinite(last_s))
  {
    return looks;
  }
  for (;;)
  {
    const double t = *drive_start_s_ + static_cast<double>(scheduled_looks_made_ + 1) * options_.look_period_s;
    if (t > last_s)
    {
      break;
    }
    ++scheduled_looks_made_;
    if (last_look_s_ && t <= *last_look_s_)
    {
      continue;  // an unscheduled look (the data stopped) already went past it
    }
    looks.push_back(look(drive_so_far, t));
  }
  return looks;
}

SequentialLook SequentialVerdict::look(const std::vector<CarFollowingRun>& drive_so_far, double now_s)
{
  const auto started = std::chrono::steady_clock::now();
  std::vector<CarFollowingRun> valid;
  for (const CarFollowingRun& run : drive_so_far)
  {
    if (describeRunProblem(run).empty())
    {
      valid.push_back(run);
    }
  }
  const std::vector<CarFollowingRun> segments = piecesBetween(valid, -std::numeric_limits<double>::infinity(), now_s, true);
  std::string note;
  std::size_t evaluations = 0;
  if (!std::isfinite(now_s) || (last_look_s_ && now_s < *last_look_s_))
  {
    note = "look at " + formatTime(now_s) + " s before the previous look (" +
           formatTime(last_look_s_.value_or(0.0)) + " s) or not finite: nothing changed";
  }
  else
  {
    if (!drive_start_s_ && !segments.empty())
    {
      drive_start_s_ = segments.front().time_s.front();
    }
    last_look_s_ = now_s;
    scoreCompleteBlocks(segments, now_s);
    evaluations = refit(segments, now_s, note);
  }
  SequentialLook result = summarize(now_s, sampleCount(segments), note);
  result.evaluations = evaluations;
  result.solve_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  latest_ = result;
  return result;
}

void SequentialVerdict::scoreCompleteBlocks(const std::vector<CarFollowingRun>& segments, double now_s)
{
  while (next_block_start_s_ && *next_block_start_s_ + block_length_s_ <= now_s)
  {
    const double start_s = *next_block_start_s_;
    // The latest fits made at or before the block's start: none of its data trained them.
    const FitsAt* fits = nullptr;
    for (const FitsAt& candidate : fits_)
    {
      if (candidate.trained_until_s <= start_s)
      {
        fits = &candidate;
      }
    }
    if (fits != nullptr)
    {
      scoreBlock(segments, start_s, *fits);
    }
    else
    {
      ++blocks_skipped_;
    }
    next_block_start_s_ = start_s + block_length_s_;
    // Fits older than the latest one made before the next block are needed no more.
    while (fits_.size() > 1 && fits_[1].trained_until_s <= *next_block_start_s_)
    {
      fits_.pop_front();
    }
  }
}

void SequentialVerdict::scoreBlock(const std::vector<CarFollowingRun>& segments, double start_s, const FitsAt& fits)
{
  const double end_s = start_s + block_length_s_;
  const std::vector<CarFollowingRun> pieces = piecesBetween(segments, start_s - options_.warm_up_s, end_s, false);
  const HeldOutErrors stable = heldOutErrors(fits.fits.stable.parameters, pieces, start_s);
  const HeldOutErrors unstable = heldOutErrors(fits.fits.unstable.parameters, pieces, start_s);
  const double full_block_samples = block_length_s_ / mean_step_s_;
  if (static_cast<double>(stable.error.size()) < options_.min_block_coverage * full_block_samples ||
      (stable.diverged && unstable.diverged))
  {
    ++blocks_skipped_;
    return;
  }
  double x = 0.0;
  if (stable.diverged != unstable.diverged)
  {
    x = stable.diverged ? 1.0 : -1.0;  // the model that cannot follow the block predicts it worse
  }
  else
  {
    double d = 0.0;
    for (std::size_t i = 0; i < stable.error.size(); ++i)
    {
      d += stable.error[i] * stable.error[i] - unstable.error[i] * unstable.error[i];
    }
    d /= static_cast<double>(stable.error.size());
    // Predictable scale: the past blocks' d's and one pseudo-block at the fits' training MSE.
    const double past = static_cast<double>(blocks_scored_);
    const double rms = std::sqrt((fits.training_mse_m2ps2 * fits.training_mse_m2ps2 + sum_squared_d_) / (past + 1.0));
    const double scale = std::max(options_.min_scale_m2ps2, options_.scale_multiple * rms);
    x = std::clamp(d / scale, -1.0, 1.0);
    sum_squared_d_ += d * d;
  }
  decision_.add(x, end_s);
  ++blocks_scored_;
}

std::size_t SequentialVerdict::refit(const std::vector<CarFollowingRun>& segments, double now_s, std::string& note)
{
  const std::size_t samples = sampleCount(segments);
  if (samples < options_.min_training_samples)
  {
    note = "too few samples for the side fits (" + std::to_string(samples) + " < " +
           std::to_string(options_.min_training_samples) + ")";
    return 0;
  }
  const double speed_std = followerSpeedStdMps(segments);
  if (fits_.empty() && speed_std < options_.min_training_speed_std_mps)
  {
    note = "flat data so far: the follower speed varies by " + significant(speed_std) +
           " m/s (std); without speed changes the data pin only eta + tau_e v, not the margin";
    return 0;
  }
  std::optional<CalibrationObjective> objective;
  try
  {
    objective.emplace(segments, options_.bounds);
  }
  catch (const std::exception& error)
  {
    note = std::string("the drive cannot be simulated: ") + error.what();
    return 0;
  }
  SideFits fits;
  if (fits_.empty())
  {
    fits = fitBothSides(*objective, options_.first_multistart, options_.first_constrained, {});
  }
  else
  {
    const SideFits& previous = fits_.back().fits;
    const SideFit& previous_other = previous.unconstrained_stable ? previous.unstable : previous.stable;
    // U is one of the two sides: both sides' fits are the warm starts, U's first.
    const SideFit& previous_u = previous.unconstrained_stable ? previous.stable : previous.unstable;
    fits = fitBothSides(*objective, options_.refit_multistart, options_.refit_constrained,
                        {previous_u.parameters}, {previous_other.parameters});
  }
  const std::size_t evaluations = fits.unconstrained_evaluations + fits.constrained_evaluations;
  if (!fits.failure.empty())
  {
    note = "side fits at " + formatTime(now_s) + " s failed (" + fits.failure + "); the previous ones stay";
    return evaluations;
  }
  FitsAt made;
  made.trained_until_s = now_s;
  made.fits = fits;
  const HeldOutErrors residual = heldOutErrors(fits.unconstrained, segments);
  made.training_mse_m2ps2 = meanOf(squared(residual.error));
  if (!next_block_start_s_)
  {
    // The first fits: fix L once, from their residual's correlation, and start the blocks.
    const HeldOutSegments scored = heldOutSegmentsOf(segments);
    mean_step_s_ = scored.duration_s / static_cast<double>(std::max<std::size_t>(1, scored.scored_samples));
    block_length_s_ = options_.block_length_s > 0.0
                          ? options_.block_length_s
                          : correlationBlockLengthS(residual.error, scored.scored_lengths, mean_step_s_,
                                                    options_.correlation_times, options_.min_block_length_s,
                                                    options_.max_block_length_s);
    next_block_start_s_ = now_s;
  }
  fits_.push_back(std::move(made));
  return evaluations;
}

SequentialLook SequentialVerdict::summarize(double now_s, std::size_t samples, const std::string& note) const
{
  SequentialLook look;
  look.time_s = now_s;
  look.samples = samples;
  look.blocks_scored = blocks_scored_;
  look.blocks_skipped = blocks_skipped_;
  look.block_length_s = block_length_s_;
  look.alpha = options_.alpha;
  const BettingEProcess& against_stable = decision_.againstNonPositive();
  const BettingEProcess& against_unstable = decision_.againstNonNegative();
  look.verdict = verdictOf(decision_.sign());
  look.e_value_unstable = against_stable.eValue();
  look.e_value_stable = against_unstable.eValue();
  look.p_value_stable_rejected = against_stable.pValue();
  look.p_value_unstable_rejected = against_unstable.pValue();
  look.p_value = look.verdict == StabilityVerdict::Unstable ? look.p_value_stable_rejected
                 : look.verdict == StabilityVerdict::Stable ? look.p_value_unstable_rejected
                                                            : std::min(look.p_value_stable_rejected,
                                                                       look.p_value_unstable_rejected);
  look.decided_at_s = decision_.decidedAtS();
  look.reversed = decision_.reversed();
  look.first_verdict = verdictOf(decision_.firstSign());
  look.reversed_at_s = decision_.reversedAtS();
  if (!fits_.empty())
  {
    look.stable_fit_margin = fits_.back().fits.stable.margin;
    look.unstable_fit_margin = fits_.back().fits.unstable.margin;
  }
  std::ostringstream why;
  why << "sequential (anytime-valid) over " << blocks_scored_ << " block(s)";
  if (block_length_s_ > 0.0)
  {
    why << " of " << significant(block_length_s_) << " s";
  }
  if (blocks_skipped_ > 0)
  {
    why << " (" << blocks_skipped_ << " skipped: holes)";
  }
  why << ", each predicted by side fits made before it; max E against stable "
      << significant(against_stable.maxEValue()) << ", against unstable " << significant(against_unstable.maxEValue())
      << " (decides at 1/alpha = " << significant(1.0 / options_.alpha) << ")";
  if (look.reversed)
  {
    why << ": first " << toString(look.first_verdict) << " at " << formatTime(look.decided_at_s) << " s, then "
        << toString(look.verdict) << " at " << formatTime(look.reversed_at_s)
        << " s: both e-processes crossed 1/alpha, the evidence meets the same standard both ways (REVERSED)";
  }
  else if (look.verdict != StabilityVerdict::Undecided)
  {
    why << ": " << toString(look.verdict) << " since " << formatTime(look.decided_at_s) << " s (data time), kept";
  }
  else
  {
    why << ": neither reached it yet";
  }
  if (!note.empty())
  {
    why << "; " << note;
  }
  look.reason = why.str();
  return look;
}

std::vector<SequentialLook> SequentialVerdict::lookLive(const std::vector<CarFollowingRun>& drive_so_far,
                                                        bool data_stopped)
{
  double last_s = -std::numeric_limits<double>::infinity();
  for (const CarFollowingRun& run : drive_so_far)
  {
    if (!run.time_s.empty())
    {
      last_s = std::max(last_s, run.time_s.back());
    }
  }
  std::vector<SequentialLook> looks = lookUpTo(drive_so_far, last_s);
  if (data_stopped && std::isfinite(last_s) && (!last_look_s_ || *last_look_s_ < last_s))
  {
    looks.push_back(look(drive_so_far, last_s));
  }
  return looks;
}

std::vector<SequentialLook> replaySequentialVerdict(const std::vector<CarFollowingRun>& drive,
                                                    const SequentialVerdictOptions& options)
{
  SequentialVerdict verdict(options);
  return verdict.lookLive(drive, true);
}

}  // namespace acc
