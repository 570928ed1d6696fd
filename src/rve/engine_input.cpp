#include "rve/engine_input.h"

#include <cmath>
#include <iomanip>
#include <sstream>

#include "dem/file_name.h"
#include "rve/script.h"

namespace mpm_lig::rve {
namespace {

using Values = std::map<std::string, std::string>;

std::set<std::string> flags_of(const RveSpec& spec) {
  std::set<std::string> flags;
  if (spec.dimension == 2)
    flags.insert("two_d");
  if (spec.contact.rolling_friction)
    flags.insert("rolling");
  if (spec.contact.cohesion_energy_density)
    flags.insert("cohesion");
  return flags;
}

std::string render(const RveSpec& spec, const std::string& name, const Values& values) {
  return render_template(engine_template(spec.engine, name), values, flags_of(spec));
}

//! LAMMPS `rolling sds` needs a rolling spring stiffness [N/m]: 2.25 μ_r² k_n with the Hertz
//! normal stiffness k_n = 2 E* sqrt(R* δ) at a typical overlap δ = 0.5 % of the mean radius.
double lammps_rolling_stiffness(const RveSpec& spec, double mu_r) {
  const double nu = spec.contact.poisson_ratio;
  const double e_star = spec.contact.youngs_modulus / (2.0 * (1.0 - nu * nu));
  const double r_star = 0.5 * spec.radius.mean();
  const double k_n = 2.0 * e_star * std::sqrt(r_star * 0.005 * spec.radius.mean());
  return 2.25 * mu_r * mu_r * k_n;
}

}  // namespace

std::string fmt(double value) {
  std::ostringstream out;
  out << std::setprecision(17) << value;
  return out.str();
}

double neighbour_skin(const RveSpec& spec) {
  return 0.4 * spec.radius.mean();
}

std::string setup_input(const RveSpec& spec, const Packing& packing) {
  const double half_z = spec.dimension == 2 ? spec.radius.max : 0.0;
  const Values values = {{"dimension", std::to_string(spec.dimension)},
                         {"lx", fmt(packing.cell_length)},
                         {"ly", fmt(packing.cell_length)},
                         {"zlo", fmt(spec.dimension == 2 ? -half_z : 0.0)},
                         {"zhi", fmt(spec.dimension == 2 ? half_z : packing.cell_length)},
                         {"skin", fmt(neighbour_skin(spec))}};
  std::ostringstream out;
  out << render(spec, "setup.in", values);
  for (std::size_t i = 0; i < packing.centres.size(); ++i) {
    const Vec3& x = packing.centres[i];
    out << "create_atoms 1 single " << fmt(x.x()) << ' ' << fmt(x.y()) << ' ' << fmt(x.z())
        << " units box\n"
        << "set atom " << i + 1 << " diameter " << fmt(2.0 * packing.radii[i]) << " density "
        << fmt(spec.density) << '\n';
  }
  return out.str();
}

std::string restart_input(const RveSpec& spec, const std::string& restart_file) {
  return render(
      spec, "restart.in",
      {{"restart_file", dem::quoted_file_name(restart_file)}, {"skin", fmt(neighbour_skin(spec))}});
}

std::string material_input(const RveSpec& spec, double friction) {
  const ContactSpec& c = spec.contact;
  Values values = {{"youngs_modulus", fmt(c.youngs_modulus)},
                   {"poisson_ratio", fmt(c.poisson_ratio)},
                   {"restitution", fmt(c.restitution)},
                   {"friction", fmt(friction)},
                   {"rolling_model", ""},
                   {"cohesion_model", ""}};
  if (c.rolling_friction) {
    values["rolling_friction"] = fmt(*c.rolling_friction);
    values["rolling_model"] = spec.engine == "liggghts"
                                  ? " rolling_friction epsd2"
                                  : " rolling sds " +
                                        fmt(lammps_rolling_stiffness(spec, *c.rolling_friction)) +
                                        " 0 " + fmt(*c.rolling_friction);
  }
  if (c.cohesion_energy_density) {
    values["cohesion_energy_density"] = fmt(*c.cohesion_energy_density);
    values["cohesion_model"] = " cohesion sjkr";
  }
  return render(spec, "material.in", values);
}

std::string dynamics_input(const RveSpec& spec, double time_step) {
  return render(spec, "dynamics.in", {{"time_step", fmt(time_step)}});
}

}  // namespace mpm_lig::rve
