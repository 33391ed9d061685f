// stability_report: the string-stability analysis of ACC parameter sets (paper Section II-B).
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "acc_identification/model/acc_model.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/model/string_stability.h"
#include "acc_identification/tools/number_checks.h"


namespace
{
void printRow(const std::string& name, const acc::AccParameters& p)
{
  const auto report = acc::analyzeStringStability(p);
  std::printf("%-14s %7.4f %7.4f %7.4f %7.3f %10.4g  %-9s %13.4f %10.3f %12.4f%s\n", name.c_str(),
              p.k1_per_s2, p.k2_per_s, p.tau_e_s, p.eta_m, report.lambda2,
              report.string_stable ? "stable" : "UNSTABLE", report.amplified_band_upper_rad_s,
              report.peak_gain_db, report.peak_frequency_rad_s,
              acc::satisfiesRationalDrivingConstraints(p) ? "" : "  (violates rational driving constraints)");
}
}  // namespace

int main(int argc, char** argv)
{
  CLI::App app{"Prints lambda2, the verdict, the amplified band and the peak gain of each parameter set. "
               "Without arguments: Table II's minimum and maximum settings (Gunter et al.)."};
  std::vector<std::string> names;
  double k1 = 0.0, k2 = 0.0, tau_e = 0.0, eta = 0.0;
  std::vector<std::string> setting_names;
  for (const auto& setting : acc::namedSettings())
    setting_names.push_back(setting.name);
  app.add_option("--setting", names, "a named setting, repeatable")->check(CLI::IsMember(setting_names));
  // The model's domain (kLargestModelGainOrTimeGap), every value finite.
  auto* k1_option = app.add_option("--k1", k1, "custom parameter set: k1 [1/s^2]")->check(acc::modelGainOrTimeGap());
  auto* k2_option = app.add_option("--k2", k2, "k2 [1/s]")->check(acc::modelGainOrTimeGap());
  auto* tau_option = app.add_option("--tau-e", tau_e, "tau_e [s]")->check(acc::modelGainOrTimeGap());
  app.add_option("--eta", eta, "eta [m] of the custom set (plays no part in string stability)")
      ->check(acc::finiteNumber("METRES"))
      ->capture_default_str()
      ->needs(k1_option);
  k1_option->needs(k2_option)->needs(tau_option);
  k2_option->needs(k1_option);
  tau_option->needs(k1_option);
  CLI11_PARSE(app, argc, argv);

  std::vector<acc::NamedSetting> settings;
  for (const std::string& name : names)
    settings.push_back(*acc::findNamedSetting(name));
  if (k1_option->count() > 0)
    settings.push_back({"custom", "command line", {k1, k2, tau_e, eta}});
  if (settings.empty())
  {
    settings = {*acc::findNamedSetting("min"), *acc::findNamedSetting("max")};
  }
  std::printf("String stability (Gunter et al., Sec. II-B): stable when |Gamma(jw)| <= 1 for all w, i.e. lambda2 < 0, "
              "or lambda2 = 0 on the boundary or with k1 = 0 (no gap feedback: |Gamma| = k2 / |jw + k2|)\n");
  std::printf("%-14s %7s %7s %7s %7s %10s  %-9s %13s %10s %12s\n", "setting", "k1", "k2", "tau_e", "eta",
              "lambda2", "verdict", "band<[rad/s]", "peak[dB]", "at[rad/s]");
  for (const auto& setting : settings)
  {
    printRow(setting.name, setting.parameters);
  }
  return 0;
}
