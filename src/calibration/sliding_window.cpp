#include "acc_identification/calibration/sliding_window.h"
#include "acc_identification/model/sample_statistics.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace acc
{
namespace
{
/// The samples among `samples` that no one has counted yet.
std::size_t uncounted(const std::vector<WindowSample>& samples)
{
  return static_cast<std::size_t>(
      std::count_if(samples.begin(), samples.end(), [](const WindowSample& s) { return !s.counted; }));
}
}  // namespace

SlidingWindow::SlidingWindow(double length_s, double max_gap_s, std::size_t min_segment_samples,
                             double max_forward_jump_s, std::size_t confirm_samples)
  : length_s_(length_s),
    max_gap_s_(max_gap_s),
    min_segment_samples_(std::max<std::size_t>(2, min_segment_samples)),
    max_forward_jump_s_(std::max(max_forward_jump_s, max_gap_s)),
    confirm_samples_(std::max<std::size_t>(1, confirm_samples))
{
}

SlidingWindow::AddResult SlidingWindow::append(const WindowSample& sample)
{
  AddResult result = AddResult::kAdded;
  WindowSample stored = sample;
  if (stored.valid && !(std::isfinite(stored.space_gap_m) && std::isfinite(stored.follower_speed_mps) &&
                        std::isfinite(stored.leader_speed_mps)))
  {
    stored.valid = false;
    result = AddResult::kNonFinite;
  }
  else if (!stored.valid)
  {
    result = AddResult::kInvalid;
  }
  samples_.push_back(stored);
  while (!samples_.empty() && samples_.front().time_s < stored.time_s - length_s_)
  {
    samples_.pop_front();
  }
  return result;
}

SlidingWindow::AddResult SlidingWindow::hold(const WindowSample& sample)
{
  const bool continues_held = !held_.empty() && sample.time_s > held_.back().time_s &&
                              sample.time_s - held_.back().time_s <= max_gap_s_;
  if (!held_.empty() && !continues_held)
  {
    counts_.time_outliers += uncounted(held_);  // neither base: the earlier jump was an outlier too
    held_.clear();
  }
  held_.push_back(sample);
  if (held_.size() < confirm_samples_)
  {
    return AddResult::kHeld;
  }
  const bool back = held_.front().time_s < samples_.back().time_s;
  if (back)
  {
    samples_.clear();
  }
  for (const WindowSample& confirmed : held_)
  {
    append(confirmed);
  }
  held_.clear();
  ++(back ? counts_.restarts : counts_.jumps_ahead);
  return back ? AddResult::kRestarted : AddResult::kJumpedAhead;
}

SlidingWindow::AddResult SlidingWindow::add(const WindowSample& sample)
{
  if (!std::isfinite(sample.time_s))
  {
    counts_.non_finite_times += sample.counted ? 0 : 1;
    return AddResult::kNonFinite;  // cannot even order it in time
  }
  if (samples_.empty())
  {
    return append(sample);
  }
  const double last_s = samples_.back().time_s;
  if (sample.time_s > last_s && sample.time_s - last_s <= max_forward_jump_s_)
  {
    // The time base goes on: anything held was an outlier.
    counts_.time_outliers += uncounted(held_);
    held_.clear();
    return append(sample);
  }
  if (sample.time_s <= last_s && sample.time_s >= last_s - max_gap_s_)
  {
    counts_.out_of_order += sample.counted ? 0 : 1;
    return AddResult::kOutOfOrder;  // late or duplicate, within the data's own jitter
  }
  return hold(sample);
}

std::vector<CarFollowingRun> SlidingWindow::segments(std::size_t* short_pieces) const
{
  std::vector<CarFollowingRun> result;
  std::size_t short_count = 0;
  CarFollowingRun current;
  auto close = [&]() {
    if (current.size() >= min_segment_samples_)
    {
      current.name = "segment " + std::to_string(result.size() + 1);
      result.push_back(std::move(current));
    }
    else if (current.size() > 0)
    {
      ++short_count;
    }
    current = CarFollowingRun{};
  };
  for (const WindowSample& sample : samples_)
  {
    if (!sample.valid)
    {
      close();
      continue;
    }
    if (!current.time_s.empty() && sample.time_s - current.time_s.back() > max_gap_s_)
    {
      close();
    }
    current.time_s.push_back(sample.time_s);
    current.space_gap_m.push_back(sample.space_gap_m);
    current.follower_speed_mps.push_back(sample.follower_speed_mps);
    current.leader_speed_mps.push_back(sample.leader_speed_mps);
  }
  close();
  if (short_pieces != nullptr)
  {
    *short_pieces = short_count;
  }
  return result;
}

std::string SlidingWindow::describeShortPieces(std::size_t short_pieces) const
{
  if (short_pieces == 0)
    return "";
  std::vector<double> steps;
  for (std::size_t k = 1; k < samples_.size(); ++k)
    steps.push_back(samples_[k].time_s - samples_[k - 1].time_s);
  const double median_step_s = interpolatedQuantile(steps, 0.5);
  std::ostringstream out;
  out << short_pieces << (short_pieces == 1 ? " piece" : " pieces") << " of fewer than " << min_segment_samples_
      << " samples between holes longer than " << max_gap_s_ << " s or invalid samples not simulated";
  if (median_step_s > max_gap_s_)
    out << ": the samples' median step, " << median_step_s << " s, is itself such a hole (a receiver at "
        << 1.0 / median_step_s << " Hz); max_gap_s must exceed the step";
  return out.str();
}

std::size_t SlidingWindow::letGo(std::size_t first, std::size_t count)
{
  if (samples_.size() < 2 || first >= samples_.size() - 1)
  {
    return 0;
  }
  count = std::min(count, samples_.size() - 1 - first);  // the newest sample stays
  const auto begin = samples_.begin() + static_cast<std::ptrdiff_t>(first);
  const bool joins_across = first > 0 && first + count < samples_.size() &&
                            samples_[first + count].time_s - samples_[first - 1].time_s <= max_gap_s_;
  samples_.erase(begin, begin + static_cast<std::ptrdiff_t>(count));
  if (joins_across)
  {
    // Too short a stretch to open a hole: mark the cut so no Euler step crosses it.
    WindowSample cut = samples_[first];
    cut.valid = false;
    samples_.insert(samples_.begin() + static_cast<std::ptrdiff_t>(first), cut);
    --count;
  }
  return count;
}

std::string SlidingWindow::describe(AddResult result)
{
  switch (result)
  {
    case AddResult::kAdded: return "added";
    case AddResult::kInvalid: return "invalid sample: splits the window";
    case AddResult::kNonFinite: return "non-finite value in a sample marked valid: treated as invalid";
    case AddResult::kOutOfOrder: return "sample not newer than the last one: rejected";
    case AddResult::kRestarted: return "time jumped back, confirmed by consistent samples: window cleared";
    case AddResult::kHeld: return "time jumped: held until consistent samples confirm it";
    case AddResult::kJumpedAhead: return "time jumped ahead, confirmed by consistent samples: older samples leave";
  }
  return "unknown";
}

}  // namespace acc
