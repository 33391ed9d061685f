#pragma once

#include <cstddef>
#include <optional>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/io/run_csv.h"

namespace acc
{
/// What one RUN argument gave a tool, counted, for its JSON (`inputs_read`, docs/TOOLS.md): the
/// reader's log says each record not used and why; this says how many, so a script that reads only
/// the JSON still sees what the runs lost or had rebuilt.
struct InputAccount
{
  std::string path;
  std::string format;  ///< "csv" (the canonical columns), "openacc" or "bag"
  /// OpenACC: the pair(s) read ("BMW_I3 behind MERCEDES_GLE450, positions 3/2"); else empty.
  std::vector<std::string> openacc_pairs;
  /// The reader's counters by name, in its order; only those of the format (docs/TOOLS.md lists
  /// them). Empty when the runs did not come from a reader (a DataFrame changed after read_run).
  std::vector<std::pair<std::string, std::size_t>> counts;

  /// The count of that name, or none when the account has no such count.
  std::optional<std::size_t> count(const std::string& name) const;
};

/// The account of a CSV read by readRunFile: data_rows, samples_used, runs, rejected_rows (of
/// them implausible_rows and duplicate_rows), acc_off_rows, single_sample_rows, time_holes,
/// gap_rebuilt_rows. data_rows = rejected_rows + acc_off_rows + single_sample_rows +
/// samples_used. Take it before the runs are moved out of contents.
InputAccount accountOfRunFile(const std::string& path, const RunFileContents& contents);

/// "rejected_rows 92, gap_rebuilt_rows 66": the counts other than the totals (data_rows,
/// messages, samples_used, runs) that are not zero, in the account's order; "" when there are none.
std::string describeLossesAndRepairs(const InputAccount& account);

/// {name: n, ...}: the account's counts.
nlohmann::json countsJson(const InputAccount& account);

/// [{path, format, openacc_pairs (OpenACC only), counts: {name: n, ...}}, ...].
nlohmann::json inputAccountsJson(const std::vector<InputAccount>& accounts);

/// True when one of the accounts names an OpenACC pair (its data carry the database's attribution),
/// as openAccPairsJson lists them.
bool anyOpenAcc(const std::vector<InputAccount>& accounts);

/// [{path, pairs: [...]}] of each OpenACC file read (the JSON's `openacc_pairs`).
nlohmann::json openAccPairsJson(const std::vector<InputAccount>& accounts);

/// "OpenACC pair read: part3.csv: Hyundai behind Rexton, positions 2/1", one line per OpenACC file.
void printOpenAccPairs(const std::vector<InputAccount>& accounts, std::ostream& out);

}  // namespace acc
