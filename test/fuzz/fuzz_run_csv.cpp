// libFuzzer target for the run readers: the input written to a file and read as the tools read a
// RUN argument (a canonical CSV, or an OpenACC file of any layout with every pair). Built and run
// by scripts/test_hooks/fuzz_run_csv.sh with -fsanitize=fuzzer,address,undefined. A file that
// cannot be read at all throws RunReadError, its message the reason; anything else thrown is a
// crash. Besides crashes it checks the readers' promises: every run it gives can be simulated, and
// every data row is used or counted (data_rows = rejected + ACC off + alone + samples used).
#include <cstddef>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <unistd.h>

#include "acc_identification/io/input_account.h"
#include "acc_identification/io/run_csv.h"
#include "fuzz_support.h"

namespace
{
using fuzz_support::check;

/// One file per fuzzing process, rewritten for every input and removed when the process ends.
const std::string& inputPath()
{
  static const std::string path = "/tmp/acc_fuzz_run_csv_" + std::to_string(getpid()) + ".csv";
  static const bool removed_at_exit = std::atexit([] { std::remove(inputPath().c_str()); }) == 0;
  (void)removed_at_exit;
  return path;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size)
{
  {
    std::ofstream file(inputPath(), std::ios::binary | std::ios::trunc);
    file.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  acc::RunFileContents contents;
  try
  {
    contents = acc::readRunFile(inputPath(), acc::RunPlausibilityBounds{}, acc::OpenAccPairSelector::all());
  }
  catch (const acc::RunReadError&)
  {
    return 0;  // not a run file: said, not a crash
  }
  for (const acc::CarFollowingRun& run : contents.runs)
    check(acc::describeRunProblem(run).empty(), "every run can be simulated");
  check(contents.data_rows ==
            contents.rejected_rows + contents.acc_off_rows + contents.single_sample_rows + acc::sampleCount(contents.runs),
        "every data row is used or counted");
  check(contents.sawtooth_rows <= acc::sampleCount(contents.runs), "rebuilt rows are used rows");
  const acc::InputAccount account = acc::accountOfRunFile(inputPath(), contents);
  check(!account.counts.empty(), "the account has counts");
  acc::describeRowCounts(inputPath(), contents);
  return 0;
}
