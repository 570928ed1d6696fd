#pragma once

#include <array>
#include <cstddef>

#include "rve/rve.h"

namespace mpm_lig::coupling {

//! One field of rve::Rve::State: its name in a checkpoint, its doubles and where they live.
struct RveStateField {
  const char* name;
  std::size_t width;
  double* (*at)(rve::Rve::State&);
};

//! Every field of rve::Rve::State, in the order both of its copies use: a checkpoint's named
//! arrays (point_checkpoint.cpp) and a moving RVE's broadcast (rve_migration.cpp). A new field
//! of the state is one line here; the static_assert below fails until it is added.
inline constexpr std::array<RveStateField, 5> kRveStateFields{{
    {"rotation", 9, [](rve::Rve::State& s) { return s.rotation.data(); }},
    {"streaming", 9, [](rve::Rve::State& s) { return s.streaming.data(); }},
    {"rve_particle_steps", 1, [](rve::Rve::State& s) { return &s.particle_steps; }},
    {"last_mean_stress", 1, [](rve::Rve::State& s) { return &s.last_mean_stress; }},
    {"rve_strain", 9, [](rve::Rve::State& s) { return s.strain.data(); }},
}};

//! Doubles of a packed rve::Rve::State (the sum of the widths).
constexpr std::size_t rve_state_width() {
  std::size_t width = 0;
  for (const RveStateField& f : kRveStateFields)
    width += f.width;
  return width;
}

static_assert(sizeof(rve::Rve::State) == rve_state_width() * sizeof(double),
              "rve::Rve::State has a field that kRveStateFields does not list");

//! `s` as rve_state_width() doubles at `v`, field by field.
void pack_state(const rve::Rve::State& s, double* v);
//! The state packed at `v`.
rve::Rve::State unpack_state(const double* v);

}  // namespace mpm_lig::coupling
