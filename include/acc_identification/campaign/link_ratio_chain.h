#pragma once

#include <vector>

#include "acc_identification/campaign/platoon_check.h"

namespace acc
{
/// A prediction of the platoons' dips without a car-following model: each car dips as deep as
/// the car ahead times the car's own link ratio (its dip over the dip of the car directly ahead,
/// summed over its perturbations, as links[].dip_ratio) measured in its OTHER runs at its setting;
/// with no other run, in its other perturbations of this run. Chained from the first car, on the
/// car-perturbations the base chain predicts, so the two are scored on the same cars; it restarts
/// from the real car ahead where the base chain does (DipComparison::chain_driven_by) and behind a
/// car with no ratio. It asks whether what a car did to a braking
/// in other runs says what it does here: if the cars' own ratios predict the dips no better than
/// the models do, the gap is the runs' variability, not the models' form.
///
/// Sets DipComparison::link_ratio_chain_dip_mps of every position (NaN where a car on the way
/// has no ratio: no other perturbation with a measured leader dip above min_leader_dip_mps).
void addLinkRatioChains(std::vector<PlatoonCheck>& platoons, double min_leader_dip_mps);

}  // namespace acc
