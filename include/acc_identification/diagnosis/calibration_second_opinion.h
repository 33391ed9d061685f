#pragma once

#include "acc_identification/calibration/calibrate_runs.h"
#include "acc_identification/diagnosis/diagnosis.h"

namespace acc
{
/// calibrate's second opinion when its model is NOT ADEQUATE (calibrate_runs.h): the diagnosis of
/// the same runs (each split in halves as --split half does), and THE verdict of the model it ends
/// with (statedVerdict), as JSON {verdict..., effects, adequacy} and as text. Data the diagnosis
/// cannot use (too short to split) give {"error": why}.
SecondOpinionOf diagnosisSecondOpinion(const DiagnosisOptions& options = {});

}  // namespace acc
