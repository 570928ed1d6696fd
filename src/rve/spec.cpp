#include "rve/spec.h"

#include <cmath>
#include <filesystem>
#include <sstream>

#include "core/tensor.h"
#include "dem/file_name.h"
#include "dem/restart_check.h"

namespace mpm_lig::rve {
namespace {

std::string number(double v) {
  std::ostringstream out;
  out << v;
  return out.str();
}

RadiusSpec parse_radius(const CaseNode& node) {
  RadiusSpec r;
  if (node.has("distribution")) {
    const CaseNode d = node.child("distribution");
    r.radii = d.get<std::vector<double>>("radii");
    r.cumulative = d.get<std::vector<double>>("cumulative_fraction");
    if (r.radii.size() < 2)
      d.fail("radii", "needs at least two radii");
    if (r.cumulative.size() != r.radii.size())
      d.fail("cumulative_fraction",
             "needs one value per radius (" + std::to_string(r.radii.size()) + ")");
    for (std::size_t i = 0; i < r.radii.size(); ++i) {
      if (!(r.radii[i] > 0.0))
        d.fail("radii", "radius " + std::to_string(i) + " must be > 0");
      if (i > 0 && !(r.radii[i] > r.radii[i - 1]))
        d.fail("radii", "must increase strictly");
      if (i > 0 && !(r.cumulative[i] >= r.cumulative[i - 1]))
        d.fail("cumulative_fraction", "must not decrease");
    }
    if (r.cumulative.front() != 0.0 || r.cumulative.back() != 1.0)
      d.fail("cumulative_fraction", "must start at 0 and end at 1");
    r.min = r.radii.front();
    r.max = r.radii.back();
    return r;
  }
  r.min = node.positive("min");
  r.max = node.positive("max");
  if (r.max < r.min)
    node.fail("max", "must be >= radius.min (" + number(r.min) + "), got " + number(r.max));
  return r;
}

ContactSpec parse_contact(const CaseNode& node) {
  ContactSpec c;
  c.youngs_modulus = node.positive("youngs_modulus");
  if (node.has("poisson_ratio") == node.has("stiffness_ratio"))
    node.fail("give exactly one of poisson_ratio and stiffness_ratio");
  if (node.has("poisson_ratio")) {
    c.poisson_ratio = node.in_range("poisson_ratio", 0.0, 0.5);
  } else {
    // Hertz–Mindlin: k_t / k_n = 2 (1 - ν) / (2 - ν).
    const double ratio = node.positive("stiffness_ratio");
    c.poisson_ratio = (2.0 - 2.0 * ratio) / (2.0 - ratio);
    if (!(ratio < 1.0) || !(c.poisson_ratio <= 0.5))
      node.fail("stiffness_ratio",
                "Hertz–Mindlin needs k_t/k_n in [2/3, 1) (Poisson ratio 0 ... "
                "0.5), got " +
                    number(ratio));
  }
  if (node.has("friction") == node.has("friction_deg"))
    node.fail("give exactly one of friction (coefficient) and friction_deg (angle)");
  // (deg * π) / 180 rather than deg * kDegree: the two round differently for some angles (23°),
  // and every documented DEM run was made with this rounding.
  c.friction = node.has("friction")
                   ? node.non_negative("friction")
                   : std::tan(node.in_range("friction_deg", 0.0, 89.0) * kPi / 180);
  if (node.has("restitution") == node.has("damping_ratio"))
    node.fail("give exactly one of restitution and damping_ratio");
  if (node.has("restitution")) {
    c.restitution = node.in_range("restitution", 0.01, 1.0);
  } else {
    const double zeta = node.in_range("damping_ratio", 0.0, 0.99);
    c.restitution = std::exp(-kPi * zeta / std::sqrt(1.0 - zeta * zeta));
  }
  if (node.has("rolling_friction"))
    c.rolling_friction = node.non_negative("rolling_friction");
  if (node.has("cohesion_energy_density"))
    c.cohesion_energy_density = node.non_negative("cohesion_energy_density");
  return c;
}

PreparationSpec parse_preparation(const CaseNode& node, int dimension) {
  PreparationSpec p;
  p.confining_pressure = node.positive("confining_pressure");
  if (node.has("target_void_ratio"))
    p.target_void_ratio = node.positive("target_void_ratio");
  if (node.has("consolidation_friction_deg")) {
    if (!p.target_void_ratio)
      node.fail("consolidation_friction_deg", "needs preparation.target_void_ratio");
    p.consolidation_friction =
        std::tan(node.in_range("consolidation_friction_deg", 0.0, 89.0) * kPi / 180);
  }
  p.tolerance = node.in_range_or("tolerance", 1e-4, 0.02, 0.005);
  p.void_ratio_tolerance = node.in_range_or("void_ratio_tolerance", 1e-4, 0.1, 0.005);
  const double dense = dimension == 2 ? 0.8 : 0.6;
  p.initial_solid_fraction =
      node.in_range_or("initial_solid_fraction", 0.05, dimension == 2 ? 0.5 : 0.35, 0.6 * dense);
  p.max_strain_rate = node.positive_or("max_strain_rate", 0.0);
  p.max_steps = node.get_or<long>("max_steps", 5'000'000);
  if (p.max_steps < 1000)
    node.fail("max_steps", "must be >= 1000");
  return p;
}

//! The DEM step `node` gives, as `time_step` [s] or `time_step_fraction` of the Rayleigh step
//! (the caller has checked that exactly one is there), at most the Rayleigh step.
double given_time_step(const CaseNode& node, double rayleigh_time_step) {
  const double step = node.has("time_step")
                          ? node.positive("time_step")
                          : node.in_range("time_step_fraction", 1e-3, 1.0) * rayleigh_time_step;
  if (step > rayleigh_time_step)
    node.fail("time_step", "exceeds the Rayleigh time step " + number(rayleigh_time_step) +
                               " s of the smallest grain");
  return step;
}

//! The preparation's own DEM step if the case gives one, else the RVE's.
double preparation_time_step(const CaseNode& node, const RveSpec& s) {
  if (node.has("time_step") && node.has("time_step_fraction"))
    node.fail("give at most one of time_step [s] and time_step_fraction (of the Rayleigh step)");
  if (!node.has("time_step") && !node.has("time_step_fraction"))
    return s.time_step;
  return given_time_step(node, s.rayleigh_time_step);
}

SubstepSpec parse_substeps(const CaseNode& node) {
  SubstepSpec s;
  if (node.has("fixed") == node.has("inertial_number"))
    node.fail("give exactly one of fixed and inertial_number");
  if (node.has("fixed")) {
    s.fixed = node.get<int>("fixed");
    if (s.fixed < 1)
      node.fail("fixed", "must be >= 1");
    return s;
  }
  s.inertial_number = node.in_range("inertial_number", 1e-7, 0.1);
  s.min = node.get_or<int>("min", 10);
  s.max = node.get_or<int>("max", 100000);
  if (s.min < 1)
    node.fail("min", "must be >= 1");
  if (s.max < s.min)
    node.fail("max", "must be >= substeps.min (" + std::to_string(s.min) + ")");
  s.pressure_floor = node.in_range_or("pressure_floor", 1.0, 1e9, 1e3);
  if (node.has("sheared")) {
    const CaseNode sheared = node.child("sheared");
    s.sheared_after = sheared.in_range("shear_strain", 1e-4, 100.0);
    s.sheared_inertial_number = sheared.in_range("inertial_number", 1e-7, 0.1);
  }
  return s;
}

//! LIGGGHTS refuses Young's moduli outside this range in SI units ("youngsModulus >= 5e6
//! required for SI units"); LAMMPS has no such limit.
constexpr double kLiggghtsMinYoungsModulus = 5e6;
constexpr double kLiggghtsMaxYoungsModulus = 1e9;

void check_engine_limits(const CaseNode& contact, const RveSpec& s) {
  const double e = s.contact.youngs_modulus;
  if (s.engine == "liggghts" && (e < kLiggghtsMinYoungsModulus || e > kLiggghtsMaxYoungsModulus))
    contact.fail("youngs_modulus", "engine \"liggghts\" takes " +
                                       number(kLiggghtsMinYoungsModulus) + " ... " +
                                       number(kLiggghtsMaxYoungsModulus) + " Pa, got " + number(e) +
                                       " (engine \"lammps\" has no such limit)");
}

//! The engine opens its log file itself: its folder must exist before the run.
void check_log_folder(const CaseNode& node, const std::string& log_file) {
  const std::filesystem::path folder = std::filesystem::path(log_file).parent_path();
  std::error_code error;
  if (!folder.empty() && !std::filesystem::is_directory(folder, error))
    node.fail("log_file", "folder '" + folder.string() + "' does not exist");
  if (std::filesystem::is_directory(log_file, error))
    node.fail("log_file", "'" + log_file + "' is a folder");
}

}  // namespace

double RadiusSpec::mean() const {
  if (radii.empty())
    return 0.5 * (min + max);
  double m = 0.0;
  for (std::size_t i = 1; i < radii.size(); ++i)
    m += 0.5 * (radii[i] + radii[i - 1]) * (cumulative[i] - cumulative[i - 1]);
  return m;
}

double instance_memory_bytes(const RveSpec& spec) {
  const double per_grain = spec.engine == "lammps" ? 1.95e6 / 400 : 1.1e6 / 400;
  return per_grain * static_cast<double>(spec.grains);
}

double rayleigh_time_step(const RveSpec& spec) {
  const double nu = spec.contact.poisson_ratio;
  const double shear_modulus = spec.contact.youngs_modulus / (2.0 * (1.0 + nu));
  return kPi * spec.radius.min * std::sqrt(spec.density / shear_modulus) / (0.1631 * nu + 0.8766);
}

RveSpec parse_rve_spec(const CaseNode& node) {
  RveSpec s;
  s.path = node.path();
  s.engine = node.choice_or("engine", {"liggghts", "lammps"}, "liggghts");
  s.dimension = node.get_or<int>("dimension", 3);
  if (s.dimension != 2 && s.dimension != 3)
    node.fail("dimension", "must be 2 (discs) or 3 (spheres), got " + std::to_string(s.dimension));
  // File names are relative to the case file's folder (the case runs from any directory).
  if (node.has("log_file")) {
    s.log_file = node.file_path("log_file");
    check_log_folder(node, s.log_file);
  }
  // Default by measurement (README, method notes): with streaming velocities the quasi-static
  // strength converges as the strain rate goes down; with remapped positions it does not.
  const std::string affine = node.choice_or(
      "affine_motion", {"streaming_velocity", "remap_positions"}, "streaming_velocity");
  s.stream_velocity = affine == "streaming_velocity";
  s.setup_every = node.get_or<int>("setup_every", 1);
  // A checkpoint, asked for or on a stop signal, waits for the end of a period: at most
  // setup_every - 1 steps, which must stay within a batch system's warning before the end.
  if (s.setup_every < 1 || s.setup_every > 1000)
    node.fail("setup_every",
              "must be between 1 (the engine's set-up before every update) and "
              "1000, got " +
                  std::to_string(s.setup_every));
  if (s.setup_every > 1 && s.engine != "liggghts")
    node.fail("setup_every",
              "runs without the engine's set-up need engine \"liggghts\" (LAMMPS sets up its "
              "contact computes after every run)");
  s.cell_angle = node.in_range_or("cell_angle_deg", -90.0, 90.0, 0.0) * kDegree;
  s.max_kinetic_ratio = node.positive_or("max_kinetic_ratio", 1.0);
  // Measured: sheared 60- and 400-disc packings, before and after liquefaction, carry 3 to 32
  // times the flow energy ½ Σ m (2 r |L|)²; a blow-up carries orders of magnitude more.
  s.max_flow_ratio = node.positive_or("max_flow_ratio", 1000.0);

  s.contact = parse_contact(node.child("contact"));
  check_engine_limits(node.child("contact"), s);
  if (s.contact.cohesion_energy_density && s.engine != "liggghts")
    node.child("contact").fail("cohesion_energy_density",
                               "cohesion (sjkr) is available with engine \"liggghts\" only");
  s.substeps = node.has("substeps") ? parse_substeps(node.child("substeps"))
                                    : SubstepSpec{0, 1e-3, 10, 100000};

  // A restart file carries the packing; grain data and preparation are then not read.
  if (node.has("restart_file") == node.has("preparation"))
    node.fail("give exactly one of preparation (prepare a fresh packing) and restart_file");
  if (node.has("restart_file")) {
    s.restart_file = node.file_path("restart_file");
    if (!std::filesystem::is_regular_file(s.restart_file))
      node.fail("restart_file", "no such file '" + s.restart_file + "'");
    const std::string unusable = dem::unusable_file_name(s.restart_file);
    if (!unusable.empty())
      node.fail("restart_file", "'" + s.restart_file + "': " + unusable);
  }
  s.grains = node.get<long>("grains");
  if (s.grains < kMinGrains)
    node.fail("grains",
              "must be >= " + std::to_string(kMinGrains) + ", got " + std::to_string(s.grains));
  if (!s.restart_file.empty()) {
    const std::string problem = dem::restart_file_problem(s.restart_file, s.engine, s.grains);
    if (!problem.empty())
      node.fail("restart_file", "'" + s.restart_file + "': " + problem);
  }
  s.radius = parse_radius(node.child("radius"));
  s.density = node.positive("density");
  const long seed = node.get_or<long>("seed", 1);
  if (seed < 0)
    node.fail("seed", "must be >= 0");
  s.seed = static_cast<std::uint64_t>(seed);
  if (s.restart_file.empty()) {
    s.preparation = parse_preparation(node.child("preparation"), s.dimension);
    if (s.preparation.consolidation_friction &&
        *s.preparation.consolidation_friction < s.contact.friction)
      node.child("preparation")
          .fail("consolidation_friction_deg",
                "must be at least the contact friction (a lower one packs denser, which the "
                "staged lowering towards target_void_ratio does already)");
  }
  if (s.dimension == 2)
    s.thickness = node.positive_or("thickness", 2.0 * s.radius.mean());

  s.rayleigh_time_step = rayleigh_time_step(s);
  if (node.has("time_step") == node.has("time_step_fraction"))
    node.fail("give exactly one of time_step [s] and time_step_fraction (of the Rayleigh step)");
  s.time_step = given_time_step(node, s.rayleigh_time_step);
  s.preparation.time_step =
      s.restart_file.empty() ? preparation_time_step(node.child("preparation"), s) : s.time_step;
  return s;
}

}  // namespace mpm_lig::rve
