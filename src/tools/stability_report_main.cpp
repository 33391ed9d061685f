// stability_report: the string-stability analysis of ACC parameter sets (paper Section II-B).
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "acc_identification/model/acc_model.h"
#include "acc_identification/command_line.h"
#include "acc_identification/model/paper_settings.h"
#include "acc_identification/model/string_stability.h"


namespace
{
const char* kUsage =
    "usage: stability_report [--setting NAME]... [--k1 K1 --k2 K2 --tau-e TAU --eta ETA]\n"
    "  Prints lambda2, the verdict, the amplified band and the peak gain of each parameter set.\n"
    "  Without arguments: Table II's minimum and maximum settings (Gunter et al.).\n"
    "  Named settings: min, max, fig2-unstable, fig2-stable.\n";

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
  acc::CommandLine cli({"setting", "k1", "k2", "tau-e", "eta"}, {"help"});
  if (!cli.parse(argc, argv) || cli.has("help"))
  {
    std::cerr << (cli.error().empty() ? "" : "error: " + cli.error() + "\n") << kUsage;
    return cli.has("help") ? 0 : 2;
  }
  std::vector<acc::NamedSetting> settings;
  for (const std::string& name : cli.values("setting"))
  {
    const auto found = acc::findNamedSetting(name);
    if (!found)
    {
      std::cerr << "error: unknown setting '" << name << "'\n" << kUsage;
      return 2;
    }
    settings.push_back(*found);
  }
  if (cli.has("k1") || cli.has("k2") || cli.has("tau-e") || cli.has("eta"))
  {
    const auto k1 = cli.number("k1"), k2 = cli.number("k2"), tau = cli.number("tau-e"), eta = cli.number("eta");
    if (!k1 || !k2 || !tau)
    {
      std::cerr << "error: " << (cli.error().empty() ? "--k1, --k2 and --tau-e go together" : cli.error()) << "\n";
      return 2;
    }
    settings.push_back({"custom", "command line", {*k1, *k2, *tau, eta.value_or(0.0)}});
  }
  if (settings.empty())
  {
    settings = {*acc::findNamedSetting("min"), *acc::findNamedSetting("max")};
  }
  std::printf("String stability (Gunter et al., Sec. II-B): stable when lambda2 < 0, i.e. |Gamma(jw)| <= 1 for all w\n");
  std::printf("%-14s %7s %7s %7s %7s %10s  %-9s %13s %10s %12s\n", "setting", "k1", "k2", "tau_e", "eta",
              "lambda2", "verdict", "band<[rad/s]", "peak[dB]", "at[rad/s]");
  for (const auto& setting : settings)
  {
    printRow(setting.name, setting.parameters);
  }
  return 0;
}
