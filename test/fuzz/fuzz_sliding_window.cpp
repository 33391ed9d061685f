// libFuzzer target for the identifier's sliding window (calibration/sliding_window.h): the samples
// identifier_node takes from relative_state as a lossy link and a bad clock can deliver them (late,
// repeated, jumping back and ahead, with NaN or infinite times and values, marked invalid or
// already counted), under window settings drawn from their ranges, with the drive record's letGo
// in between. Built and run by scripts/test_hooks/fuzz_sliding_window.sh with
// -fsanitize=fuzzer,address,undefined. Besides crashes it checks the window's promises: its samples
// in time order and within its length, fewer samples held than confirm them, and every segment one
// the Euler simulation can run (finite, strictly increasing in time, long enough).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <limits>

#include <fuzzer/FuzzedDataProvider.h>

#include "acc_identification/calibration/sliding_window.h"
#include "fuzz_support.h"

namespace
{
using fuzz_support::check;
using fuzz_support::field;

/// The next sample's time: mostly 10 Hz steps, sometimes late, repeated, jumping or not a time.
double nextTime(FuzzedDataProvider& input, double& clock_s)
{
  switch (input.ConsumeIntegralInRange<int>(0, 11))
  {
    case 0:
      return clock_s;
    case 1:
      return clock_s - input.ConsumeFloatingPointInRange<double>(0.0, 100.0);  // late, or a jump back
    case 2:
      return clock_s += input.ConsumeFloatingPointInRange<double>(0.0, 200.0);  // an outage, a jump ahead
    case 3:
      return field(input, -1e6, 1e6);  // anything, the clock left as it was
    default:
      return clock_s += input.ConsumeFloatingPointInRange<double>(0.05, 0.15);
  }
}

void checkWindow(const acc::SlidingWindow& window, double length_s, std::size_t min_segment_samples)
{
  const auto& samples = window.samples();
  for (std::size_t k = 0; k < samples.size(); ++k)
  {
    check(std::isfinite(samples[k].time_s), "every sample in the window has a finite time");
    if (k > 0)
      check(samples[k].time_s >= samples[k - 1].time_s, "the window's samples are in time order");
  }
  if (!samples.empty())
    check(samples.back().time_s - samples.front().time_s <= length_s, "the window spans at most its length");
  check(window.heldSamples() < window.confirmSamples(), "fewer samples held than confirm a jump");
  for (const acc::CarFollowingRun& segment : window.segments())
  {
    check(acc::describeRunProblem(segment).empty(), "every segment can be simulated");
    check(segment.size() >= min_segment_samples, "every segment is long enough");
  }
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  FuzzedDataProvider input(data, size);
  const double length_s = input.ConsumeFloatingPointInRange<double>(1.0, 300.0);
  const double max_gap_s = input.ConsumeFloatingPointInRange<double>(0.01, 5.0);
  const std::size_t min_segment_samples = input.ConsumeIntegralInRange<std::size_t>(2, 20);
  acc::SlidingWindow window(length_s, max_gap_s, min_segment_samples,
                            input.ConsumeFloatingPointInRange<double>(0.0, 60.0),
                            input.ConsumeIntegralInRange<std::size_t>(1, 8));
  double clock_s = input.ConsumeFloatingPointInRange<double>(0.0, 2e9);
  while (input.remaining_bytes() > 0)
  {
    if (input.ConsumeIntegralInRange<int>(0, 40) == 0)
    {
      // The drive record bounds a window that never slides by letting samples go.
      const std::size_t first = input.ConsumeIntegralInRange<std::size_t>(0, window.size());
      window.letGo(first, input.ConsumeIntegralInRange<std::size_t>(0, window.size()));
    }
    else
    {
      acc::WindowSample sample;
      sample.time_s = nextTime(input, clock_s);
      sample.space_gap_m = field(input, -2.0, 200.0);
      sample.follower_speed_mps = field(input, 0.0, 50.0);
      sample.leader_speed_mps = field(input, 0.0, 50.0);
      sample.valid = input.ConsumeIntegralInRange<int>(0, 9) > 0;
      sample.counted = input.ConsumeIntegralInRange<int>(0, 9) == 0;
      window.add(sample);
    }
    checkWindow(window, length_s, min_segment_samples);
  }
  return 0;
}
