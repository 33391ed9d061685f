// The campaign's cars as SUMO vTypes, and an OpenACC platoon file laid out for a SUMO replay: the
// chain of cars with a vType, started from their measured gaps and speeds (no SUMO run here; the
// replay itself is test_sumo's).
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "acc_identification/campaign/campaign.h"
#include "acc_identification/campaign/campaign_sumo_export.h"
#include "acc_identification/campaign/campaign_sumo_platoon.h"
#include "campaign_test_data.h"

namespace
{
namespace fs = std::filesystem;

const acc::AccParameters kCarA{0.10, 0.60, 1.2, 5.0};
const acc::AccParameters kCarB{0.08, 0.45, 1.5, 6.0};

struct SyntheticCampaign
{
  acc::CampaignInputs inputs;
  fs::path folder;
  ~SyntheticCampaign() { fs::remove_all(folder); }
};

/// Two runs of CAR_A then CAR_B at setting L (the second in the other order).
void makeCampaign(SyntheticCampaign& campaign)
{
  campaign.folder = fs::temp_directory_path() / ("acc_campaign_sumo_" + std::to_string(::getpid()));
  fs::create_directories(campaign.folder);
  acc_test::writeSyntheticPlatoon((campaign.folder / "a.csv").string(), "L", {{"CAR_A", kCarA}, {"CAR_B", kCarB}}, 7);
  acc_test::writeSyntheticPlatoon((campaign.folder / "b.csv").string(), "L", {{"CAR_B", kCarB}, {"CAR_A", kCarA}}, 8);
  campaign.inputs = acc::loadCampaign({campaign.folder.string()});
}

/// A quick campaign: eight starts per fit, both cores.
acc::CampaignOptions quickOptions()
{
  acc::CampaignOptions options;
  options.group.starts = 8;
  options.threads = 2;
  return options;
}

TEST(CampaignSumo, EveryFittedCarBecomesAVTypeOfItsSetting)
{
  SyntheticCampaign campaign;
  makeCampaign(campaign);
  acc::CampaignOptions options = quickOptions();
  options.platoon_diagnosis = false;
  const acc::CampaignResult result = acc::runCampaign(campaign.inputs, options);
  const std::vector<acc::SumoExport> exports = acc::campaignSumoExports(campaign.inputs, result);
  ASSERT_EQ(exports.size(), 2u);
  std::vector<std::string> ids{exports[0].vtype.id, exports[1].vtype.id};
  std::sort(ids.begin(), ids.end());
  EXPECT_EQ(ids, (std::vector<std::string>{"CAR_A_L", "CAR_B_L"}));
  for (const acc::SumoExport& exported : exports)
  {
    const acc::AccParameters& truth = exported.vtype.id == "CAR_A_L" ? kCarA : kCarB;
    EXPECT_NEAR(exported.vtype.gains.gap_closing_gain_space_per_s2, truth.k1_per_s2, 0.02) << exported.vtype.id;
    EXPECT_NEAR(exported.vtype.tau_s, truth.tau_e_s, 0.1) << exported.vtype.id;
    EXPECT_GT(exported.vtype.decel_mps2, 0.5) << exported.vtype.id;  // the dips' braking, from the data
  }
}

// A diagnosed model with an effect SUMO has no term for: the effects SUMO carries are refitted
// without it and exported as the diagnosed vType (a model of its own, not the diagnosed fit
// stripped of an effect), and both vTypes say what is lost.
TEST(CampaignSumo, ADiagnosedModelIsExportedAsFarAsSumoCarriesIt)
{
  SyntheticCampaign campaign;
  makeCampaign(campaign);
  acc::CampaignOptions options = quickOptions();
  options.effect_selection.force = true;
  options.effect_selection.forced = {{acc::EffectKind::quadratic_closing_response, acc::EffectKind::reaction_delay},
                                     acc::FitObjective::speed};
  const acc::CampaignResult result = acc::runCampaign(campaign.inputs, options);
  const std::vector<acc::SumoExport> exports = acc::campaignSumoExports(campaign.inputs, result);
  ASSERT_EQ(exports.size(), 4u);
  for (const acc::SumoExport& exported : exports)
  {
    std::string caveats;
    for (const std::string& c : exported.caveats)
      caveats += c + "\n";
    EXPECT_NE(caveats.find("cannot carry quadratic_closing_response"), std::string::npos) << exported.vtype.id << caveats;
    const std::string& id = exported.vtype.id;
    const bool diagnosed = id.size() > 10 && id.compare(id.size() - 10, 10, "_diagnosed") == 0;
    if (!diagnosed)
    {
      EXPECT_TRUE(exported.vtype.source_effects.empty()) << id;
      continue;
    }
    EXPECT_EQ(exported.vtype.source_effects, std::vector<acc::EffectKind>{acc::EffectKind::reaction_delay}) << id;
    ASSERT_EQ(exported.vtype.source_effect_values.size(), 1u) << id;
    EXPECT_NE(caveats.find("refitted"), std::string::npos) << id << caveats;
    // The refit is the delay model's own: its parameters are those of a fit with the delay alone
    // (these cars have none, so they stay near the truth).
    const acc::AccParameters& truth = id == "CAR_A_L_diagnosed" ? kCarA : kCarB;
    EXPECT_NEAR(exported.vtype.source_parameters.k2_per_s, truth.k2_per_s, 0.05) << id;
  }
}

TEST(CampaignSumo, APlatoonFileIsLaidOutFromItsMeasuredStarts)
{
  SyntheticCampaign campaign;
  makeCampaign(campaign);
  const std::vector<acc::SumoAccVType> vtypes{acc::exportToSumo("CAR_A_L", kCarA, {}, {}, {}).vtype,
                                              acc::exportToSumo("CAR_B_L", kCarB, {}, {}, {}).vtype};
  const acc::CampaignFile& file = campaign.inputs.files.front();  // a.csv: CAR_A then CAR_B
  const acc::FilePlatoonForSumo platoon = acc::filePlatoonForSumo(file, vtypes);
  ASSERT_EQ(platoon.input.vtypes.size(), 2u);
  EXPECT_EQ(platoon.input.vtypes[0].id, "CAR_A_L");
  EXPECT_EQ(platoon.input.vtypes[1].id, "CAR_B_L");
  EXPECT_EQ(platoon.input.time_s.size(), file.contents.rows());
  EXPECT_EQ(platoon.input.starts[1].gap_m, file.contents.vehicle(2)->gap_to_follower_m.front());
  EXPECT_EQ(platoon.input.starts[1].speed_mps, file.contents.vehicle(3)->speed_mps.front());
  ASSERT_EQ(platoon.input.measured_speed_mps.size(), 2u);
  EXPECT_EQ(platoon.input.measured_speed_mps[0], file.contents.vehicle(2)->speed_mps);
  // Without CAR_B's vType the chain stops before it, and says why.
  const acc::FilePlatoonForSumo shorter = acc::filePlatoonForSumo(file, {vtypes[0]});
  ASSERT_EQ(shorter.input.vtypes.size(), 1u);
  ASSERT_FALSE(shorter.notes.empty());
  EXPECT_NE(shorter.notes.front().find("no vType 'CAR_B_L'"), std::string::npos) << shorter.notes.front();
}

// A mixed-setting run ("SL") replays each car with its own setting's vType when the database's
// listing is given, and without it the chain stops at the first car with the reading's note first.
// Fails when sumo_replay's reading ignores the listings or drops the campaign reader's notes.
TEST(CampaignSumo, AListedMixedRunIsLaidOutWithEachCarsOwnSetting)
{
  SyntheticCampaign campaign;
  campaign.folder = fs::temp_directory_path() / ("acc_campaign_sumo_mixed_" + std::to_string(::getpid()));
  fs::create_directories(campaign.folder);
  const std::string mixed = (campaign.folder / "handling_part12.csv").string();
  const std::string listing = (campaign.folder / "long cars.csv").string();
  acc_test::writeSyntheticPlatoon(mixed, "SL", {{"CAR_A", kCarA}, {"CAR_B", kCarB}}, 9);
  std::ofstream(listing) << "filename,Long timegap setting\nhandling_part12,CAR_B\n";
  const std::vector<acc::SumoAccVType> vtypes{acc::exportToSumo("CAR_A_S", kCarA, {}, {}, {}).vtype,
                                              acc::exportToSumo("CAR_B_L", kCarB, {}, {}, {}).vtype};
  const acc::FilePlatoonForSumo listed = acc::readFilePlatoonForSumo(mixed, {listing}, vtypes, false);
  ASSERT_EQ(listed.input.vtypes.size(), 2u);
  EXPECT_EQ(listed.input.vtypes[0].id, "CAR_A_S");
  EXPECT_EQ(listed.input.vtypes[1].id, "CAR_B_L");

  const acc::FilePlatoonForSumo unlisted = acc::readFilePlatoonForSumo(mixed, {}, vtypes, false);
  EXPECT_TRUE(unlisted.input.vtypes.empty());
  ASSERT_EQ(unlisted.notes.size(), 2u);
  EXPECT_NE(unlisted.notes[0].find("Distance_setting 'SL' is a mixed run"), std::string::npos) << unlisted.notes[0];
  EXPECT_NE(unlisted.notes[1].find("no vType 'CAR_A_SL'"), std::string::npos) << unlisted.notes[1];
  EXPECT_THROW(acc::readFilePlatoonForSumo(mixed, {mixed}, vtypes, false), std::invalid_argument);
}

}  // namespace
