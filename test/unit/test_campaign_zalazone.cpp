// The campaign on the shipped JRC OpenACC ZalaZone dynamic-platform runs (CC BY 4.0, see
// data/openacc/README.md): grouping of the real files and one group's verdict, checked by hand
// with `calibrate --follower TOYOTA_RAV4 dynamic_part5/6/12/14.csv` (unstable, p 0.001).
#include <string>

#include <gtest/gtest.h>

#include "acc_identification/campaign/campaign.h"
#include "acc_identification/campaign/group_identification.h"

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
