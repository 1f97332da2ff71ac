#include "app/runaway.hpp"

#include <algorithm>
#include <cmath>

namespace eulerfsi {

double case_speed_scale(const CaseConfig& cfg, double initial_speed) {
  const auto& f = cfg.flow;
  double scale = std::fabs(initial_speed);
  scale = std::max(scale, std::fabs(f.bulk_velocity));
  for (double w : f.wall_velocity) scale = std::max(scale, std::fabs(w));
  if (!f.frame_follows_particle) scale = std::max(scale, std::fabs(f.frame_velocity));
  return scale;
}

}  // namespace eulerfsi
