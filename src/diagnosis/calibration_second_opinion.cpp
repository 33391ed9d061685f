#include "acc_identification/diagnosis/calibration_second_opinion.h"

#include <sstream>
#include <stdexcept>

#include "acc_identification/calibration/model_adequacy.h"
#include "acc_identification/diagnosis/diagnosis_output.h"
#include "acc_identification/diagnosis/diagnosis_text.h"

namespace acc
{
namespace
{
SecondOpinion opinionOf(const DiagnosisResult& result)
{
  SecondOpinion opinion;
  opinion.json = verdictJson(result);
  opinion.json["effects"] = effectNames(selectedChain(result));
  opinion.json["model_adequacy"] = toJson(result.final_adequacy);
  const DiagnosisVerdict verdict = statedVerdict(result);
  std::ostringstream text;
  text << "\nThe model is not adequate, so calibrate asked the diagnosis (each run fitted on its first half, judged "
          "on the second; `diagnose` gives the whole of it):\n"
       << "  model: " << verdict.model << "; adequacy: " << describeAdequacy(result.final_adequacy) << "\n"
       << "  verdict of that model: " << (verdict.test ? verdictText(*verdict.test) : std::string("not tested"))
       << "\n  why this model: " << verdict.why << "\n";
  opinion.text = text.str();
  return opinion;
}
}  // namespace

SecondOpinionOf diagnosisSecondOpinion(const DiagnosisOptions& options)
{
  return [options](const std::vector<CarFollowingRun>& runs) {
    try
    {
      return opinionOf(diagnoseRuns(runs, options));
    }
    catch (const std::invalid_argument& error)
    {
      return SecondOpinion{{{"error", error.what()}},
                           std::string("\nThe model is not adequate; the diagnosis cannot use these runs: ") +
                               error.what() + "\n"};
    }
  };
}

}  // namespace acc
