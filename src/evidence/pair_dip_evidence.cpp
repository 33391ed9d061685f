#include "acc_identification/evidence/pair_dip_evidence.h"

namespace acc
{
PairDipEvidence pairDipEvidence(const std::vector<CarFollowingRun>& runs, const PerturbationCriteria& criteria,
                                std::size_t replicates, std::uint64_t seed)
{
  PairDipEvidence evidence;
  std::vector<double> leader_dips, follower_dips;
  std::vector<DipShapeObservation> shapes;
  for (std::size_t r = 0; r < runs.size(); ++r)
  {
    const CarFollowingRun& run = runs[r];
    std::vector<Perturbation> perturbations = findPerturbations(run.time_s, run.leader_speed_mps, criteria);
    judgeCutWindows(perturbations, run.time_s, {{"the follower", &run.follower_speed_mps, 2}}, criteria);
    for (const Perturbation& perturbation : perturbations)
    {
      PairDip dip;
      dip.run = run.name;
      dip.run_index = r;
      dip.perturbation = perturbation;
      dip.onset_s = perturbation.onset_s;
      dip.leader_dip_mps = dipDepthMps(run.time_s, run.leader_speed_mps, perturbation, criteria);
      dip.follower_dip_mps = dipDepthMps(run.time_s, run.follower_speed_mps, perturbation, criteria);
      dip.leader_shape = dipShape(run.time_s, run.leader_speed_mps, perturbation, criteria);
      dip.follower_shape = dipShape(run.time_s, run.follower_speed_mps, perturbation, criteria);
      leader_dips.push_back(dip.leader_dip_mps);
      follower_dips.push_back(dip.follower_dip_mps);
      // The shape is scored where the dip ratio is: a leader dip above the ratio's floor.
      if (dip.leader_dip_mps >= kMinLeaderDipMps)
        shapes.push_back({evidence.dips.size(), dip.follower_shape, dip.follower_shape, dip.leader_shape});
      evidence.dips.push_back(dip);
    }
  }
  evidence.ratio = linkDipRatio(follower_dips, leader_dips, replicates, seed);
  evidence.shape = dipShapeTransfer(shapes, replicates, seed);
  return evidence;
}

}  // namespace acc
