#include "color/glass.h"

#include <cmath>

namespace lantern {

double SellmeierGlass::index(double nm) const {
  const double l2 = nm * nm * 1e-6;
  double n2 = 1.0;
  for (int i = 0; i < 3; ++i) n2 += B[i] * l2 / (l2 - C[i]);
  return std::sqrt(n2);
}

std::optional<SellmeierGlass> named_glass(std::string_view name) {
  // SCHOTT optical glass data sheets: B1, B2, B3, then C1, C2, C3 (um^2).
  struct Entry {
    std::string_view name;
    SellmeierGlass glass;
  };
  static constexpr Entry kGlasses[] = {
      {"glass-BK7", {{1.03961212, 0.231792344, 1.01046945}, {0.00600069867, 0.0200179144, 103.560653}}},
      {"glass-BAF10", {{1.5851495, 0.143559385, 1.08521269}, {0.00926681282, 0.0424489805, 105.613573}}},
      {"glass-FK51A", {{0.971247817, 0.216901417, 0.904651666}, {0.00472301995, 0.0153575612, 168.68133}}},
      {"glass-LASF9", {{2.00029547, 0.298926886, 1.80691843}, {0.0121426017, 0.0538736236, 156.530829}}},
      {"glass-F5", {{1.52481889, 0.187085527, 1.42729015}, {0.011254756, 0.0588995392, 129.141675}}},
      {"glass-F10", {{1.62153902, 0.256287842, 1.64447552}, {0.0122241457, 0.0595736775, 147.468793}}},
      {"glass-F11", {{1.73759695, 0.313747346, 1.89878101}, {0.013188707, 0.0623068142, 155.23629}}},
  };
  for (const Entry& e : kGlasses)
    if (e.name == name) return e.glass;
  return std::nullopt;
}

}  // namespace lantern
