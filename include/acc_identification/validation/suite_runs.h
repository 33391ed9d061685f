#pragma once

#include <cstdio>
#include <ostream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/diagnosis/diagnosis.h"
#include "acc_identification/validation/withheld_effect_suite.h"

namespace acc
{
/// What `diagnose --withheld-suite NAME` gives: its tables (stdout) and every case as JSON
/// ({"cases": [...]}, --json); a line per case goes to the progress stream as it is done.
struct SuiteReport
{
  std::string tables;
  nlohmann::json json;
};

/// The suites' names: small, large (synthetic runs, one effect withheld), combined (every pair of
/// effects withheld at once), semi-real (effects injected into real runs).
const std::vector<std::string>& suiteNames();

/// Runs one suite. semi_real_sets are the real runs of the semi-real suite (bundledSemiRealSets),
/// unused by the others. Throws std::invalid_argument for an unknown name.
SuiteReport runSuite(const std::string& name, const DiagnosisOptions& options,
                     const std::vector<SemiRealSet>& semi_real_sets, std::FILE* progress);

/// The semi-real suite's real runs: Casale parts 3-6 (one set) and the ZalaZone Toyota RAV4 runs
/// (another), read from the folders the bundled data are unpacked into. Throws as readRuns.
std::vector<SemiRealSet> bundledSemiRealSets(const std::string& casale_dir, const std::string& toyota_dir);

/// `diagnose --withheld-suite NAME`: the suite run (semi-real on the bundled runs in casale_dir and
/// toyota_dir), its tables on out, its JSON in json_path when one is given, progress on stderr.
/// The exit status: 0, or 1 after saying on errors what failed.
int runSuiteCommand(const std::string& name, const DiagnosisOptions& options, const std::string& casale_dir,
                    const std::string& toyota_dir, const std::string& json_path, std::ostream& out,
                    std::ostream& errors);

}  // namespace acc
