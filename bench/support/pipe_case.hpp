#pragma once
// The benchmark case: a laminar pipe at Re = 100 with cubic cells, optionally one soft
// particle (d = 0.2, We = 1) at r/R = 0.2828 as in the paper, carried by the paper's model or the
// reference map (with a case file's default surface, use_default_map_surface).
#include "config/case_config.hpp"

namespace eulerfsi::bench {

inline CaseConfig pipe_flow(int nx, int ny, int nz) {
  CaseConfig cfg;
  cfg.source = "<bench>";
  cfg.domain.geometry = Geometry::Pipe;
  cfg.domain.cells = {nx, ny, nz};
  cfg.domain.length = {double(nx) / ny, 1.0, 1.0};
  cfg.flow.Re = 100.0;
  cfg.flow.initial = InitialFlow::Laminar;
  return cfg;
}

// The pipe with `count` bodies of diameter d (in D), spread evenly along x (each at r/R = 0.2828,
// turned by 90 degrees from the one before, so their boxes never meet); one body sits at
// x = Lx / 2, y = 0.2828 R, z = 0.
inline CaseConfig pipe_case_bodies(int nx, int ny, int nz, int count, double d,
                                   SolidModelKind model = SolidModelKind::ReferenceMap) {
  CaseConfig cfg = pipe_flow(nx, ny, nz);
  const double quarter[4][2] = {{1, 0}, {0, 1}, {-1, 0}, {0, -1}};
  const double r = 0.2828 * 0.5;  // r/R = 0.2828 with R = 1/2
  for (int b = 0; b < count; ++b) {
    SolidConfig s;
    s.shape = SolidShape::Sphere;
    s.diameter = d;
    s.center = {(b + 0.5) * cfg.domain.length[0] / count, r * quarter[b % 4][0], r * quarter[b % 4][1]};
    s.We = 1.0;
    s.model = model;
    if (model == SolidModelKind::ReferenceMap) use_default_map_surface(s);
    cfg.solids.push_back(s);
  }
  return cfg;
}

inline CaseConfig pipe_case(int nx, int ny, int nz, bool particle, SolidModelKind model = SolidModelKind::Paper) {
  return pipe_case_bodies(nx, ny, nz, particle ? 1 : 0, 0.2, model);
}

}  // namespace eulerfsi::bench
