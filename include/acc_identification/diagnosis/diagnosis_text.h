#pragma once

#include <cstdio>
#include <ostream>
#include <string>

#include "acc_identification/diagnosis/augmented_stability_verdict.h"
#include "acc_identification/diagnosis/diagnosis.h"

namespace acc
{
/// What `diagnose` prints: every model's errors and the point estimate's stability, the dominant
/// and plausible effects, what the training data determine, the test of the dominant model, the
/// forward selection's chain, and THE verdict with the model it belongs to.
void printDiagnosisSummary(const DiagnosisResult& result, std::FILE* out);

/// What `diagnose` says of the runs and parts it did not use: each note ("note: ..."), then how
/// many, so that nothing is left out silently (the tool's stderr, the Python API's).
void writeUnusedRunNotes(const DiagnosisResult& result, std::ostream& log);

}  // namespace acc
