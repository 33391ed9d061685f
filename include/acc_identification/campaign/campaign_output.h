#pragma once

#include <iosfwd>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "acc_identification/campaign/campaign.h"

namespace acc
{
/// The credit every campaign output carries (JRC OpenACC, CC BY 4.0; data/openacc/README.md).
extern const char* const kOpenAccAttribution;

/// The campaign document: {inputs, attribution, options, vehicles: [{name, setting, runs, samples,
/// run_files, parameters, standard_errors, identifiable, note, fit_rmse_speed_mps, quantities,
/// stability: {lambda2, string_stable, band_upper_rad_s, peak_gain_db}, stability_test: {verdict,
/// p_value, ...}}], platoons: [{run, setting, positions (first perturbation), data_show_growth,
/// disagreements, perturbations: [...], cars: [...], notes}]}. No wall times: the same inputs and
/// options give the same document. NaN as null.
nlohmann::json campaignToJson(const CampaignInputs& inputs, const CampaignResult& result,
                              const std::vector<std::string>& input_paths, const CampaignOptions& options);

/// The table per (vehicle, setting), then the platoon table and the disagreements.
void printCampaignTables(const CampaignResult& result, std::ostream& out);

/// report.md of a report folder: the tables above in Markdown, the figures when with_figures
/// (drawn by scripts/plot_campaign.py), the pairs whose rows were not all used as read, and the
/// attribution.
std::string campaignReportMarkdown(const CampaignInputs& inputs, const CampaignResult& result,
                                   const std::vector<std::string>& input_paths, bool with_figures);

}  // namespace acc
