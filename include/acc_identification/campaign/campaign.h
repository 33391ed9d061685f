#pragma once

#include <cstddef>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "acc_identification/campaign/campaign_inputs.h"
#include "acc_identification/campaign/gap_summary.h"
#include "acc_identification/campaign/group_identification.h"
#include "acc_identification/campaign/platoon_check.h"
#include "acc_identification/campaign/link_evidence.h"
#include "acc_identification/campaign/platoon_diagnosis.h"
#include "acc_identification/campaign/shape_transfer.h"

namespace acc
{
struct CampaignOptions
{
  GroupIdentificationOptions group;
  /// 0: std::thread::hardware_concurrency().
  std::size_t threads = 0;
  bool platoon_check = true;
  PlatoonCheckOptions platoon;
  /// The platoon diagnosis (platoon_diagnosis.h): every car's candidate effect models fitted like
  /// its base model, scored at pair level in the perturbation windows, one effect set chosen by
  /// the stated rule (for each run without that run), and the platoon predicted again with it.
  bool platoon_diagnosis = true;
  EffectSetSelectionOptions effect_selection;
  /// Called with (stage, done, total) after each task: stage "groups" then "platoon fits"; may
  /// be empty. Calls never overlap.
  std::function<void(const std::string&, std::size_t, std::size_t)> progress;
};

struct CampaignResult
{
  std::vector<GroupResult> groups;     ///< one per CampaignInputs::groups, same order
  std::vector<PlatoonCheck> platoons;  ///< one per file with at least two cars in a chain
  /// The platoon diagnosis: every car-perturbation's pair-level scores, the rule over all runs
  /// (what the campaign names), and for each platoon the choice made without its run (same order
  /// as platoons).
  std::vector<PairPerturbationScore> pair_scores;
  EffectSetSelection effect_selection;
  SelectionCriterion effect_selection_criterion = SelectionCriterion::platoon_dips;
  std::vector<EffectSetSelection> run_effect_selections;
  /// Per group (same order as groups), with the platoon diagnosis: model-free dip ratios and
  /// frequency response beside the base and diagnosed models, and the diagnosed model's stability.
  std::vector<LinkEvidence> links;
  /// With the platoon diagnosis: how much of the car ahead's braking and recovery the cars and
  /// their pair-level models pass on (shape_transfer.h), behind the real first car and further back.
  ShapeTransferSummary shapes_first_followers, shapes_further_back;
  /// With the platoon diagnosis: how far the gap shrinks, each kind of prediction against what the
  /// cars did (gap_summary.h), computed once for every output.
  std::vector<GapSummary> gap;
  std::size_t threads = 0;             ///< threads used
  double wall_time_s = 0.0;
};

/// The model of car (file, position) for the platoon check: identifyAcc on the car's group's
/// runs in every OTHER file (leave-one-run-out). When the group has no other run, on this file's
/// segments outside held_out [first, last] of the run's clock (leave one perturbation out: the
/// window of the perturbation the model predicts, perturbationWindowS), or without held_out (or
/// when the other runs' fit fails) on their first halves; said in source, and the stretches in
/// fitted_on_this_run_s. A prediction needs a fit, not identifiability: the excitation floor is the
/// stability test's (follower speed spread 0.1 m/s), not identifyAcc's 0.5 m/s. Not available
/// when the fit fails.
PlatoonCarModel fitPlatoonModel(const CampaignInputs& inputs, std::size_t file_index, int position,
                                std::size_t starts,
                                const std::optional<std::pair<double, double>>& held_out = std::nullopt);

/// Every group identified (identifyGroup) and, unless switched off, every multi-vehicle file's
/// platoon predicted with leave-one-run-out models (checkPlatoon); a file with a car that has no
/// other run at its setting gets one chain per perturbation, that car's model of each fitted
/// without its window (checkPlatoonByPerturbation). Groups and model fits run in
/// parallel (runTasksInParallel); every result is stored by index and seeded by group, so the
/// numbers are the same whatever the thread count.
CampaignResult runCampaign(const CampaignInputs& inputs, const CampaignOptions& options);

}  // namespace acc
