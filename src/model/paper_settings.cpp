#include "acc_identification/model/paper_settings.h"

namespace acc
{
AccParameters paperMinimumSetting() { return AccParameters{0.0782, 0.4445, 0.5162, 8.3365}; }

AccParameters paperMaximumSetting() { return AccParameters{0.0131, 0.2692, 1.6881, 7.5699}; }

AccParameters paperFigure2Setting(double tau_e_s) { return AccParameters{0.5, 0.5, tau_e_s, 8.0}; }

std::vector<NamedSetting> namedSettings()
{
  return {
      {"min", "Gunter et al., Table II, minimum following setting", paperMinimumSetting()},
      {"max", "Gunter et al., Table II, maximum following setting", paperMaximumSetting()},
      {"fig2-unstable", "Gunter et al., Fig. 2 left (tau_e = 0.75 s)", paperFigure2Setting(0.75)},
      {"fig2-stable", "Gunter et al., Fig. 2 right (tau_e = 3.2 s)", paperFigure2Setting(3.2)},
  };
}

std::optional<NamedSetting> findNamedSetting(const std::string& name)
{
  for (const NamedSetting& setting : namedSettings())
  {
    if (setting.name == name)
    {
      return setting;
    }
  }
  return std::nullopt;
}

}  // namespace acc
