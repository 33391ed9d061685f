// The campaign on the shipped JRC OpenACC ZalaZone dynamic-platform runs (CC BY 4.0, see
// data/openacc/README.md): grouping of the real files and one group's verdict, checked by hand
// with `calibrate --follower TOYOTA_RAV4 dynamic_part5/6/12/14.csv` (unstable, p 0.001).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "acc_identification/campaign/campaign.h"
#include "acc_identification/campaign/campaign_output.h"
#include "acc_identification/campaign/group_identification.h"

namespace
{
/// The cells of a Markdown table line: split at every '|' that is not escaped as "\|".
std::size_t markdownCells(const std::string& line)
{
  std::size_t pipes = 0;
  for (std::size_t i = 0; i < line.size(); ++i)
    pipes += line[i] == '|' && (i == 0 || line[i - 1] != '\\') ? 1 : 0;
  return pipes - 1;
}

/// Every row of every table in the report has as many cells as its header ("median |error|" in a
/// header once made the rows one cell short of it).
void expectEveryMarkdownTableRectangular(const std::string& markdown)
{
  std::istringstream lines(markdown);
  std::string line;
  std::size_t header_cells = 0, tables = 0;
  while (std::getline(lines, line))
  {
    if (line.empty() || line[0] != '|')
    {
      header_cells = 0;
      continue;
    }
    if (header_cells == 0)
    {
      header_cells = markdownCells(line);
      ++tables;
    }
    EXPECT_EQ(markdownCells(line), header_cells) << line;
  }
  EXPECT_GE(tables, 3u);
}
}  // namespace

TEST(CampaignZalaZone, GroupsTheNineRunsAndFindsTheRav4AtSUnstable)
{
  const acc::CampaignInputs inputs = acc::loadCampaign({ACC_ZALAZONE_DYNAMIC_DIR});
  ASSERT_EQ(inputs.files.size(), 9u);
  const acc::CampaignGroup* rav4 = inputs.findGroup("TOYOTA_RAV4", "S");
  ASSERT_NE(rav4, nullptr);
  ASSERT_EQ(rav4->runs.size(), 4u);
  EXPECT_EQ(inputs.files[rav4->runs[0].file_index].name, "dynamic_part5");
  acc::GroupIdentificationOptions options;
  options.starts = 20;
  const acc::GroupResult result = acc::identifyGroup(*rav4, options);
  ASSERT_TRUE(result.fitted()) << result.reason;
  EXPECT_EQ(acc::toString(result.stability_test.verdict), "unstable") << result.stability_test.reason;
  EXPECT_LE(result.stability_test.p_value, 0.01);
}

// A group whose runs are short (the Audi A4 at L: one run, 139 s) gets calibrate's refitting
// bootstrap of its fit; the Toyota RAV4 at S (four runs, over 600 s) does not, nor any group when
// no replicates are asked for.
TEST(CampaignZalaZone, AShortGroupsFitGetsItsRefittingBootstrap)
{
  const acc::CampaignInputs inputs = acc::loadCampaign({ACC_ZALAZONE_DYNAMIC_DIR});
  const acc::CampaignGroup* audi = inputs.findGroup("AUDI_A4", "L");
  const acc::CampaignGroup* rav4 = inputs.findGroup("TOYOTA_RAV4", "S");
  ASSERT_TRUE(audi != nullptr && rav4 != nullptr);
  acc::GroupIdentificationOptions options;
  options.starts = 20;
  EXPECT_FALSE(acc::identifyGroup(*audi, options).refit_bootstrap.has_value());
  options.bootstrap.replicates = 49;
  const acc::GroupResult short_group = acc::identifyGroup(*audi, options);
  ASSERT_TRUE(short_group.fitted()) << short_group.reason;
  ASSERT_TRUE(short_group.refit_bootstrap.has_value());
  EXPECT_EQ(short_group.refit_bootstrap->note, "");
  EXPECT_GE(short_group.refit_bootstrap->refitted, 45u);
  EXPECT_NE(short_group.refit_bootstrap->find("stability_margin"), nullptr);
  EXPECT_FALSE(acc::identifyGroup(*rav4, options).refit_bootstrap.has_value());
}

// The platoon diagnosis on the real runs (docs/PLATOON_DIAGNOSIS.md): six perturbations establish a
// timing effect and nothing on top. The rule (the wild cluster bootstrap-t, max-t over a stage)
// names the reaction delay (p = 0.0215 within its stage when this was written) and the actuation
// lag beside it, and chooses the delay; the anticipation of the leader's braking on top lowers the
// loss by three quarters (-76 %) yet stays above the level (0.0525): the test that keeps its level
// with six clusters cannot tell it from chance, where the percentile bootstrap the rule used until
// 2026-11-29 said p = 0.0005. Every run's choice made without that run holds a timing effect. The
// platoons predicted with the choice are closer to the measured dips than with the base models
// (-45 % -> -26 % in the median when this was written, every car-perturbation out of sample).
// Fails when the rule names something else, names the anticipation on six perturbations, or the
// diagnosed platoons are no better.
TEST(CampaignZalaZone, ThePlatoonDiagnosisNamesATimingEffectAndNotTheBrakingTermsOnTopOfIt)
{
  const acc::CampaignInputs inputs = acc::loadCampaign({ACC_ZALAZONE_DYNAMIC_DIR});
  acc::CampaignOptions options;
  options.threads = 2;
  const acc::CampaignResult result = acc::runCampaign(inputs, options);
  const std::string named = "leader_braking_anticipation + reaction_delay";
  EXPECT_EQ(result.effect_selection.model.name(), "reaction_delay");
  for (const acc::EffectSetSelection& selection : result.run_effect_selections)
  {
    const std::vector<acc::EffectKind>& effects = selection.model.effects;
    EXPECT_TRUE(std::find(effects.begin(), effects.end(), acc::EffectKind::reaction_delay) != effects.end() ||
                std::find(effects.begin(), effects.end(), acc::EffectKind::actuation_lag) != effects.end())
        << "without " << selection.excluded_run << ": " << selection.model.name();
  }
  const auto on_top = std::find_if(result.effect_selection.comparisons.begin(),
                                   result.effect_selection.comparisons.end(),
                                   [&](const acc::EffectSetComparison& c) { return c.candidate.name() == named; });
  ASSERT_NE(on_top, result.effect_selection.comparisons.end());
  EXPECT_EQ(on_top->against.name(), "reaction_delay");
  EXPECT_GT(on_top->relative_improvement, 0.5);
  EXPECT_FALSE(on_top->significant);
  EXPECT_GE(on_top->p_value, on_top->p_value_alone);
  const auto base = acc::summarizeDipPredictions(result.platoons, acc::DipPrediction::chain_base);
  const auto diagnosed = acc::summarizeDipPredictions(result.platoons, acc::DipPrediction::chain_diagnosed);
  ASSERT_EQ(diagnosed.car_perturbations, base.car_perturbations);
  EXPECT_LT(diagnosed.median_abs_dip_error, base.median_abs_dip_error - 0.1);
  // Deeper dips are not the links' direction: growth or decay right at 65 % of the links against
  // the base chains' 80 % when this was written (55 % with the three effects the percentile rule
  // chose; PLATOON_DIAGNOSIS.md says it); a guard against losing more.
  EXPECT_GE(diagnosed.share_links_growth_right, 0.5);
  // Without a model, each car's own link ratio from its other runs: unbiased (-3 % in the median
  // when this was written) but right about fewer than half of the links' direction (41 % of 17):
  // a car does not carry one ratio from braking to braking (PLATOON_DIAGNOSIS.md).
  const auto own_ratios = acc::summarizeDipPredictions(result.platoons, acc::DipPrediction::link_ratio_chain);
  EXPECT_GE(own_ratios.car_perturbations, 25u);
  EXPECT_LT(std::abs(own_ratios.median_dip_error), 0.1);
  EXPECT_LT(own_ratios.share_links_growth_right, 0.5);
  // The base chains lose far less distance in a braking than the cars did (-37 % in the median
  // when this was written); the diagnosed chains a little more (-28 %; the three effects forced,
  // about as much as the cars).
  ASSERT_GE(base.distance_lost_scored, base.car_perturbations - 2);
  EXPECT_LT(base.median_distance_lost_error, -0.2);
  EXPECT_LT(std::abs(diagnosed.median_distance_lost_error), std::abs(base.median_distance_lost_error));
  ASSERT_EQ(result.links.size(), result.groups.size());
  // Every car with a model, in the runs without a perturbation too (their cars get only the
  // candidate the run's choice needs, fitted once that choice is made), is predicted by its fit of
  // the run's choice: fails when those cars keep their base models.
  const nlohmann::json json = acc::campaignToJson(inputs, result, {ACC_ZALAZONE_DYNAMIC_DIR}, options);
  std::size_t diagnosed_cars = 0;
  for (const nlohmann::json& platoon : json["platoons"])
  {
    for (const nlohmann::json& car : platoon["cars"])
    {
      if (!car["model_available"].get<bool>())
        continue;
      ASSERT_TRUE(car["diagnosed_effects"].is_object()) << platoon["run"] << " " << car["name"];
      EXPECT_EQ(car["diagnosed_effects"]["effects"], platoon["effect_selection"]["model"]["effects"])
          << platoon["run"] << " " << car["name"] << ": " << car["diagnosed_model_source"];
      ++diagnosed_cars;
    }
  }
  EXPECT_GE(diagnosed_cars, 60u);
  // Every row of every pair read is used or counted in the JSON; run 26's saw-tooth (16 resets
  // behind the target car) is rebuilt, 66 rows.
  std::size_t rebuilt_in_run26 = 0;
  for (const nlohmann::json& file : json["inputs"]["files"])
    for (const nlohmann::json& pair : file["pairs_read"])
    {
      const nlohmann::json& c = pair["counts"];
      EXPECT_EQ(c["data_rows"], c["rejected_rows"].get<std::size_t>() + c["acc_off_rows"].get<std::size_t>() +
                                    c["single_sample_rows"].get<std::size_t>() + c["samples_used"].get<std::size_t>())
          << file["run"] << " " << pair["pair"];
      if (file["run"] == "dynamic_part26")
        rebuilt_in_run26 += c["gap_rebuilt_rows"].get<std::size_t>();
    }
  EXPECT_EQ(rebuilt_in_run26, 66u);
  // Every fitted car carries its model adequacy, in the result and the JSON; the cars that follow in
  // the platoon runs got the dip check from their pair-level predictions (issue 23).
  std::size_t dip_checked = 0;
  for (std::size_t g = 0; g < result.groups.size(); ++g)
  {
    const acc::GroupResult& group = result.groups[g];
    const nlohmann::json& adequacy = json["vehicles"][g]["model_adequacy"];
    ASSERT_TRUE(adequacy.is_object()) << group.vehicle;
    EXPECT_EQ(adequacy["assessed"], group.fitted()) << group.vehicle;
    EXPECT_EQ(json["vehicles"][g]["fitted"], group.fitted());
    if (group.fitted())
    {
      EXPECT_EQ(adequacy["adequate"], group.model_adequacy.adequate);
      EXPECT_EQ(adequacy["adequate"], adequacy["reasons"].empty()) << adequacy.dump();
      EXPECT_GT(adequacy["checks"]["gap_spread_m"].get<double>(), 0.0);
      EXPECT_TRUE(json["vehicles"][g]["unfitted_data"].is_null());
    }
    else
    {
      // Valid data without a fit (three steady groups here) still say what they hold.
      const nlohmann::json& data = json["vehicles"][g]["unfitted_data"];
      EXPECT_GT(data["samples"].get<std::size_t>(), 0u) << group.vehicle;
      EXPECT_LE(data["samples"].get<std::size_t>(), group.samples);
      EXPECT_GT(data["duration_s"].get<double>(), 0.0);
      EXPECT_TRUE(adequacy["adequate"].is_null());
    }
    dip_checked += group.model_adequacy.checks.dip_perturbations > 0 ? 1 : 0;
    const nlohmann::json& hypothesis = json["vehicles"][g]["stability_test"]["p_value_hypothesis"];
    if (group.stability_test.tested)
      EXPECT_TRUE(hypothesis == "stable" || hypothesis == "unstable") << hypothesis;
    else
      EXPECT_TRUE(hypothesis.is_null());
  }
  EXPECT_GT(dip_checked, result.groups.size() / 2);
  // Each car-perturbation's distances lost reach the JSON beside its dips (the first run with a
  // perturbation, its first follower).
  const auto perturbed = std::find_if(result.platoons.begin(), result.platoons.end(),
                                      [](const acc::PlatoonCheck& check) { return !check.perturbations.empty(); });
  ASSERT_NE(perturbed, result.platoons.end());
  const std::size_t p = static_cast<std::size_t>(perturbed - result.platoons.begin());
  ASSERT_GE(perturbed->perturbations[0].positions.size(), 2u);
  const acc::DipComparison& dips = perturbed->perturbations[0].positions[1];
  const nlohmann::json& row = json.at("platoons").at(p).at("perturbations").at(0).at("positions").at(1);
  ASSERT_TRUE(std::isfinite(dips.measured.distance_lost_m) && std::isfinite(dips.pair_diagnosed.distance_lost_m));
  EXPECT_EQ(row["measured_distance_lost_m"].get<double>(), dips.measured.distance_lost_m);
  EXPECT_EQ(row["predicted_distance_lost_m_diagnosed"].get<double>(), dips.chain_diagnosed.distance_lost_m);
  EXPECT_EQ(row["pair_predicted_distance_lost_m_diagnosed"].get<double>(), dips.pair_diagnosed.distance_lost_m);
  EXPECT_EQ(json.at("platoon_diagnosis").at("how_far_the_gap_shrinks").at("chain_base").at("median_distance_lost_error").get<double>(),
            base.median_distance_lost_error);
  // Where the rest of the gap enters (docs/PLATOON_DIAGNOSIS.md): the first followers' models lose
  // far too little distance (-31 % in the median when this was written), the cars' further back
  // about what they lost (-1 %); the two rows split the pair-level row.
  const nlohmann::json& gap = json.at("platoon_diagnosis").at("how_far_the_gap_shrinks");
  const nlohmann::json& first = gap.at("pair_diagnosed_first_follower");
  const nlohmann::json& back = gap.at("pair_diagnosed_further_back");
  EXPECT_EQ(first.at("car_perturbations").get<std::size_t>() + back.at("car_perturbations").get<std::size_t>(),
            gap.at("pair_diagnosed").at("car_perturbations").get<std::size_t>());
  EXPECT_LT(first.at("median_distance_lost_error").get<double>(), -0.15);
  EXPECT_LT(std::abs(back.at("median_distance_lost_error").get<double>()), 0.15);
  // The first followers' diagnosed dips are a little narrower at half depth than the cars' (-5 %
  // when this was written, -18 % with the three effects the percentile rule chose): their models
  // stay down for less time; further back +2 %.
  EXPECT_LT(first.at("median_dip_width_error").get<double>(), 0.0);
  EXPECT_LT(std::abs(back.at("median_dip_width_error").get<double>()), 0.15);
  // What the cars pass on of the car ahead's dip shape, and what the models pass on
  // (the same leaders driving both). When this was written: behind other ACC cars the cars passed
  // on 0.92 [0.85, 0.98] of the recovery rate, the diagnosed models 0.73 and the base 0.67; the
  // first followers 0.65 [0.51, 0.82] of the lead car's. The JSON carries the struct's values.
  const acc::ShapeTransferSummary& behind_acc = result.shapes_further_back;
  const acc::ShapeTransferSummary& behind_lead = result.shapes_first_followers;
  EXPECT_EQ(behind_acc.cars.recovery.observations, back.at("car_perturbations").get<std::size_t>());
  EXPECT_EQ(behind_lead.cars.recovery.observations, first.at("car_perturbations").get<std::size_t>());
  EXPECT_GT(behind_acc.cars.recovery.lower, 0.8);
  EXPECT_LT(behind_acc.pair_diagnosed.recovery.ratio, behind_acc.cars.recovery.lower);
  EXPECT_LT(behind_acc.pair_base.recovery.ratio, behind_acc.cars.recovery.lower);
  EXPECT_LT(behind_lead.cars.recovery.upper, behind_acc.cars.recovery.ratio);
  // The dips: behind other ACC cars the cars passed on 0.97 [0.90, 1.04] of the car ahead's when
  // this was written, the base models 0.85 and the diagnosed 0.90, both below that interval.
  EXPECT_LT(behind_acc.dip_cars.lower, 1.0);
  EXPECT_GT(behind_acc.dip_cars.upper, 1.0);
  EXPECT_LT(behind_acc.dip_pair_base.ratio, behind_acc.dip_cars.lower);
  EXPECT_LT(behind_acc.dip_pair_diagnosed.ratio, behind_acc.dip_cars.lower);

  // The first followers come back later than they went down, behind the lead car: their dips
  // widen by a median 1.5 s, their diagnosed models' by 1.3 when this was written. Further back
  // the cars widen them by 0.5 s, the models by 0.9-1.1.
  EXPECT_GT(behind_lead.cars.median_widening_s, 1.0);
  EXPECT_LT(behind_lead.pair_diagnosed.median_widening_s, behind_lead.cars.median_widening_s);
  EXPECT_LT(behind_acc.cars.median_widening_s, behind_acc.pair_diagnosed.median_widening_s);
  EXPECT_LT(behind_acc.cars.median_widening_s, behind_acc.pair_base.median_widening_s);
  const nlohmann::json& shapes = json.at("platoon_diagnosis").at("shape_passed_on");
  EXPECT_EQ(shapes.at("further_back").at("cars").at("recovery").at("ratio").get<double>(), behind_acc.cars.recovery.ratio);
  EXPECT_EQ(shapes.at("further_back").at("dip").at("cars").at("ratio").get<double>(), behind_acc.dip_cars.ratio);
  EXPECT_EQ(shapes.at("first_follower").at("pair_diagnosed").at("braking").at("upper").get<double>(),
            behind_lead.pair_diagnosed.braking.upper);
  EXPECT_EQ(shapes.at("first_follower").at("cars").at("median_widening_s").get<double>(),
            behind_lead.cars.median_widening_s);
  const std::string report = acc::campaignReportMarkdown(inputs, result, {ACC_ZALAZONE_DYNAMIC_DIR}, false);
  expectEveryMarkdownTableRectangular(report);
  // The answer first: the platoon line under the headline holds the gap table's two chain rows.
  const auto gap_row = [&](const std::string& key) {
    return std::find_if(result.gap.begin(), result.gap.end(), [&](const acc::GapSummary& g) { return g.key == key; })
        ->summary;
  };
  char platoon_line[256];
  std::snprintf(platoon_line, sizeof platoon_line,
                "**Platoons:** over %zu car-perturbations the base models' median dip error is %+.0f %%, the "
                "diagnosed models' %+.0f %%",
                gap_row("chain_base").car_perturbations, 100.0 * gap_row("chain_base").median_dip_error,
                100.0 * gap_row("chain_diagnosed").median_dip_error);
  EXPECT_LT(report.find(platoon_line), report.find("## Models by vehicle")) << platoon_line;
  // A terminal's last lines are the same answer, in plain text.
  std::ostringstream terminal;
  acc::printCampaignTables(result, terminal);
  const std::string printed = terminal.str();
  const std::string plain_line = std::string(platoon_line).substr(std::string("**Platoons:**").size());
  EXPECT_NE(printed.rfind("\nPlatoons:" + plain_line), std::string::npos);
  EXPECT_GT(printed.rfind("\nVerdict: "), printed.rfind("Where model and data disagree"));
  EXPECT_EQ(printed.find("**"), std::string::npos);
  // A quantity the data do not determine shows its fit in parentheses, a group without a fit "-"
  // (the Mercedes GLE450 at M and the Tesla Model X at S and M drive at a steady speed); no NaN.
  std::size_t undetermined = 0, unfitted = 0, held = 0, material = 0, open_at_boundary = 0;
  for (const acc::GroupResult& g : result.groups)
  {
    const std::size_t at = report.find("| " + g.vehicle + " | " + g.setting + " | ");
    ASSERT_NE(at, std::string::npos) << g.vehicle << "/" << g.setting;
    const std::string row = report.substr(at, report.find('\n', at) - at);
    EXPECT_EQ(row.find("NaN"), std::string::npos) << row;
    // A test that did not run is "not tested" in its row, as in the headline's count, not "undecided".
    EXPECT_EQ(row.find("| not tested | - (not run) |") != std::string::npos, !g.stability_test.tested) << row;
    // An undecided verdict beside a small p says why the p decides nothing: m = 0 is still allowed.
    const acc::StabilityTestResult& test = g.stability_test;
    const bool side_rejected_yet_open =
        test.tested && test.verdict == acc::StabilityVerdict::Undecided &&
        std::min(test.p_value_stable_rejected, test.p_value_unstable_rejected) <= test.alpha;
    open_at_boundary += side_rejected_yet_open;
    EXPECT_EQ(row.find("| undecided (m = 0 allowed) |") != std::string::npos, side_rejected_yet_open) << row;
    if (!g.fitted() || !g.identification.quantities)
    {
      ++unfitted;
      EXPECT_NE(row.find("| - | - | - | - | - |"), std::string::npos) << row;
      continue;
    }
    const acc::QuantityEstimate* tau = g.identification.quantities->find("tau_e");
    ASSERT_NE(tau, nullptr);
    // tau_e held at its bound 0 (the short settings' one speed band) shows its one-sided interval.
    char cell[64];
    if (tau->held_by_bound.empty())
      std::snprintf(cell, sizeof cell, "%.2f+-%.2f", tau->value, tau->standard_error);
    else
      std::snprintf(cell, sizeof cell, "%.2f to %.2f", tau->boundInterval().first, tau->boundInterval().second);
    held += !tau->held_by_bound.empty();
    undetermined += !tau->determined;
    // Every fit gets the Euler step check; where the step moves it by half a standard error, a note.
    ASSERT_TRUE(g.euler_step_bias && g.euler_step_bias->assessed) << g.vehicle << "/" << g.setting;
    EXPECT_NEAR(g.euler_step_bias->median_step_s, 0.1, 1e-6);
    material += g.euler_step_bias->material;
    EXPECT_EQ(report.find("- " + g.vehicle + "/" + g.setting + ": the Euler step") != std::string::npos,
              g.euler_step_bias->material)
        << g.vehicle << "/" << g.setting;
    EXPECT_NE(row.find(tau->determined ? "| " + std::string(cell) + " |" : "| (" + std::string(cell) + ") |"),
              std::string::npos)
        << row;
  }
  EXPECT_GE(undetermined, 5u);
  EXPECT_GE(held, 5u);
  EXPECT_GE(material, 1u);  // MAZDA_3 at L: its margin moves by one standard error at 10 Hz
  EXPECT_EQ(unfitted, 3u);
  // The Jaguar I-Pace and Mercedes GLE450 at L, the Tesla Model 3 at S and L, Model S at M, RAV4 at L.
  EXPECT_EQ(open_at_boundary, 6u);
  // Data too steady to fit get no verdict either, as from calibrate: the campaign once called the
  // Tesla Model X at S and M unstable (p = 0.001 and 0.025) from two models on the ridge of
  // eta + tau_e v that the held-out halves cannot tell apart but by their steady stretches.
  for (const char* steady : {"MERCEDES_GLE450/M", "TESLA_MODELX/S", "TESLA_MODELX/M"})
  {
    const acc::GroupResult* g = nullptr;
    for (const acc::GroupResult& one : result.groups)
      if (one.vehicle + "/" + one.setting == steady)
        g = &one;
    ASSERT_NE(g, nullptr) << steady;
    EXPECT_FALSE(g->fitted()) << steady;
    EXPECT_FALSE(g->stability_test.tested) << steady;
    EXPECT_EQ(g->stability_test.verdict, acc::StabilityVerdict::Undecided) << steady;
    EXPECT_NE(report.find(std::string("- ") + steady + ": steady speed (follower speed std "), std::string::npos);
    EXPECT_NE(report.find("0.5 m/s): the data pin only eta + tau_e v, not k1, k2, tau_e and eta apart: no parameters "
                          "and no verdict (a verdict needs the data a fit needs)"),
              std::string::npos);
    EXPECT_EQ(report.find(std::string("- ") + steady + ": not tested"), std::string::npos) << "said once";
  }
  // The pairs not used row for row are named, run 26's BMW i3 with its rejected and rebuilt rows.
  EXPECT_NE(report.find("| dynamic_part26 | BMW_I3 behind SMART_TARGET, positions 2/1 | 699 | 607 | 2 | "
                        "rejected_rows 92, gap_rebuilt_rows 66 |"),
            std::string::npos);
  // The report says where the choice does not hold without a run (PLATOON_DIAGNOSIS.md, "Named").
  // Without run 25 the closing response on top of the delay was named at a drawn p of 0.0495 until
  // the six perturbations' weight patterns were enumerated (exactly above 0.05).
  EXPECT_NE(report.find("the same for 7 of 9 runs; without dynamic_part8, dynamic_part26: actuation_lag"),
            std::string::npos);
  EXPECT_EQ(report.find("without dynamic_part25: "), std::string::npos);
  // A car without a base fit (the Tesla Model X at S drives at a steady speed) has no |Gamma| that
  // could leave the data's band: "no model", not "nowhere"; a link without a dip says so. No link
  // row prints a NaN.
  EXPECT_NE(report.find("| TESLA_MODELX | S | 0 | no dip | - | insufficient | no model | no model | no model | no model |"),
            std::string::npos);
  const std::size_t links = report.find("| vehicle | set | dips | dip ratio [CI] |");
  ASSERT_NE(links, std::string::npos);
  // No table prints NaN: "-" where a number does not exist (the first car's amplification, run 26's
  // cars without data, a model-free prediction's distance lost), with the reason beside the table.
  std::istringstream report_lines(report);
  for (std::string line; std::getline(report_lines, line);)
  {
    if (line.rfind("|", 0) == 0)
    {
      EXPECT_EQ(line.find("NaN"), std::string::npos) << line;
    }
  }
  EXPECT_NE(report.find("| dynamic_part26/S | 1 | 1 | SMART_TARGET | 2.33 | 2.33 | 2.33 | - |"), std::string::npos);
  EXPECT_EQ(printed.find("NaN"), std::string::npos);
}
