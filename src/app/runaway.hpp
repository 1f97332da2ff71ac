#pragma once
// A run whose velocity has left every scale of its case has blown up, even where its adaptive
// step still shrinks too slowly to reach the collapse test (a stiff particle released at rest with
// the surface ramp kept dt near 1e-7 for thousands of steps at kinetic energy 1e8; docs/REFERENCE_MAP.md,
// "Ramp 0.5 with relax time 0.05 rerun").
#include "config/case_config.hpp"

namespace eulerfsi {

// A speed this many times the case's scale is a blow-up, not a flow: a solution of the
// incompressible equations with a bounded forcing stays within a few of its imposed speeds.
constexpr double kRunawaySpeedFactor = 100.0;

// The case's velocity scale: the largest imposed speed (bulk, walls, a fixed frame) and the
// fastest velocity the run starts from (0 where nothing moves at all).
double case_speed_scale(const CaseConfig& cfg, double initial_speed);

// Whether `speed` has run away from `scale` (never where the scale is 0: nothing to compare with).
inline bool speed_ran_away(double speed, double scale) { return scale > 0.0 && speed > kRunawaySpeedFactor * scale; }

}  // namespace eulerfsi
