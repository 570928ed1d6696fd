#pragma once

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "core/case_node.h"
#include "rve/rve.h"
#include "rve/spec.h"

namespace mpm_lig::test {

//! The packing the RVE tests share: 100 discs of radius 3-7 mm, glass-like Hertz contacts,
//! prepared at 100 kPa, 50 fixed substeps per increment. Each test changes only the keys it is
//! about (engine, dimension, grains, seed, preparation).
inline nlohmann::json small_rve_json() {
  return {{"dimension", 2},
          {"grains", 100},
          {"radius", {{"min", 0.003}, {"max", 0.007}}},
          {"density", 2650},
          {"seed", 3},
          {"contact",
           {{"youngs_modulus", 7e8},
            {"poisson_ratio", 0.3},
            {"friction", 0.5},
            {"damping_ratio", 0.1}}},
          {"time_step_fraction", 0.15},
          {"preparation", {{"confining_pressure", 1e5}}},
          {"substeps", {{"fixed", 50}}}};
}

//! `rve` read as the case reader reads a case's "rve" node.
inline rve::RveSpec parse_rve(const nlohmann::json& rve) {
  const auto doc = CaseDocument::parse(nlohmann::json{{"rve", rve}}.dump());
  return rve::parse_rve_spec(doc.root().child("rve"));
}

//! Rve::observe_health (overlaps from the neighbour list, no force evaluation) against
//! Rve::observe (the engine's contacts): the same stress and motion measures, the same largest
//! overlap, and the overlapping pairs are the contacts. Right after a run under `fix deform`,
//! LIGGGHTS decides contact with periodic images still in the previous step's cell while both
//! observations measure in the current one: a pair may then overlap by less than one step's
//! cell change without being a contact yet (`lag`), which also moves its grains in or out of the
//! kinetic energy.
inline void expect_health_matches_full(rve::Rve& r, double lag) {
  // Health first: LAMMPS's contacts() follows a run with a set-up (`run 0`), as overlaps() does.
  const rve::Observables health = r.observe_health(), full = r.observe();
  EXPECT_EQ(health.stress, full.stress);
  EXPECT_EQ(health.void_ratio, full.void_ratio);
  EXPECT_EQ(health.grains, full.grains);
  EXPECT_EQ(health.max_speed_ratio, full.max_speed_ratio);
  EXPECT_EQ(health.flow_energy, full.flow_energy);
  ASSERT_GT(full.max_overlap_ratio, 10 * lag);
  EXPECT_NEAR(health.max_overlap_ratio, full.max_overlap_ratio, 1e-9 * full.max_overlap_ratio);
  EXPECT_NEAR(health.kinetic_energy, full.kinetic_energy,
              (lag > 0 ? 1e-3 : 1e-12) * full.kinetic_energy);
  auto unordered = [](long i, long j) { return std::make_pair(std::min(i, j), std::max(i, j)); };
  std::map<std::pair<long, long>, double> overlapping;
  for (const dem::Overlap& o : r.engine().overlaps())
    overlapping[unordered(o.id_i, o.id_j)] = o.ratio;
  const std::vector<double> radius = r.engine().gather_atoms("radius", 1);
  std::size_t touching = 0;
  for (const dem::Contact& c : r.engine().contacts()) {
    const double ri = radius[c.id_i - 1], rj = radius[c.id_j - 1];
    if (ri + rj - c.branch.norm() <= 0.0)
      continue;  // touching in the previous step's cell only
    ++touching;
    EXPECT_EQ(overlapping.count(unordered(c.id_i, c.id_j)), 1u) << c.id_i << "-" << c.id_j;
  }
  EXPECT_GT(touching, static_cast<std::size_t>(full.grains / 2));
  EXPECT_LE(overlapping.size(), touching + (lag > 0 ? overlapping.size() / 50 : 0));
  // Pairs beyond the contacts: only ones that barely overlap.
  std::size_t barely = 0;
  for (const auto& [pair, ratio] : overlapping)
    barely += ratio < lag ? 1 : 0;
  EXPECT_GE(barely, overlapping.size() - touching);
}

}  // namespace mpm_lig::test
