#include "dem_scripts.h"

#include <random>
#include <sstream>

namespace mpm_lig::dem::test {

namespace {

std::string box_lines(const std::string& engine, const Box& box, bool periodic) {
  std::ostringstream s;
  s.precision(17);
  const bool tilted = box.xy != 0.0 || box.xz != 0.0 || box.yz != 0.0;
  s << "boundary " << (periodic ? "p p p" : "f f f") << "\n";
  s << "region box " << (tilted ? "prism " : "block ") << box.lo.x() << " " << box.hi.x() << " "
    << box.lo.y() << " " << box.hi.y() << " " << box.lo.z() << " " << box.hi.z();
  if (tilted)
    s << " " << box.xy << " " << box.xz << " " << box.yz;
  s << " units box\n";
  s << "create_box 1 box\n";
  (void)engine;
  return s.str();
}

}  // namespace

std::string setup_script(const std::string& engine, const Box& box, bool periodic,
                         const Material& m) {
  std::ostringstream s;
  s.precision(17);
  if (engine == "liggghts") {
    s << "units si\natom_style granular\natom_modify map array\nnewton off\n"
      << "communicate single vel yes\n"
      << box_lines(engine, box, periodic) << "neighbor 0.001 bin\nneigh_modify delay 0\n"
      << "fix m1 all property/global youngsModulus peratomtype " << m.young << "\n"
      << "fix m2 all property/global poissonsRatio peratomtype " << m.poisson << "\n"
      << "fix m3 all property/global coefficientRestitution peratomtypepair 1 " << m.restitution
      << "\n"
      << "fix m4 all property/global coefficientFriction peratomtypepair 1 " << m.friction << "\n"
      << "pair_style gran model hertz tangential history\npair_coeff * *\n";
  } else {
    s << "units si\natom_style sphere\natom_modify map array\ncomm_modify vel yes\n"
      << box_lines(engine, box, periodic) << "neighbor 0.001 bin\nneigh_modify delay 0\n"
      << "pair_style granular\n"
      << "pair_coeff * * hertz/material " << m.young << " " << m.restitution << " " << m.poisson
      << " tangential mindlin NULL 1.0 " << m.friction << " damping tsuji\n";
  }
  return s.str();
}

std::string grains_script(const std::vector<Grain>& grains, const Material& m) {
  std::ostringstream s;
  s.precision(17);
  for (std::size_t i = 0; i < grains.size(); ++i) {
    const Grain& g = grains[i];
    s << "create_atoms 1 single " << g.x.x() << " " << g.x.y() << " " << g.x.z() << " units box\n"
      << "set atom " << i + 1 << " diameter " << 2.0 * g.radius << " density " << m.density << "\n";
  }
  return s.str();
}

std::string dynamics_script(double timestep, const std::string& pressure_id) {
  std::ostringstream s;
  s.precision(17);
  s << "fix integrate all nve/sphere\ntimestep " << timestep << "\n"
    << "compute " << pressure_id << " all pressure thermo_temp virial\n"
    << "thermo_style custom step atoms c_" << pressure_id << "[1]\nthermo 1000\n";
  return s.str();
}

std::vector<Grain> jittered_packing(int n, double spacing, unsigned seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> jitter(-0.02 * spacing, 0.02 * spacing);
  std::uniform_real_distribution<double> diameter(1.0 * spacing, 1.04 * spacing);
  std::vector<Grain> grains;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) {
        Grain g;
        g.x = spacing * Vec3(i + 0.5, j + 0.5, k + 0.5) +
              Vec3(jitter(random), jitter(random), jitter(random));
        g.radius = 0.5 * diameter(random);
        grains.push_back(g);
      }
  return grains;
}

std::unique_ptr<Engine> periodic_packing(const std::string& engine, const std::string& label,
                                         double tilt) {
  const Material material;
  const int n = 4;
  const double spacing = 0.01;
  Box box;
  box.hi = Vec3::Constant(n * spacing);
  box.xy = tilt * spacing;
  auto instance = create_engine(engine, MPI_COMM_SELF, {label, ""});
  instance->commands(setup_script(engine, box, true, material));
  instance->commands(grains_script(jittered_packing(n, spacing, 7u), material));
  instance->commands(dynamics_script(1e-6, "p"));
  return instance;
}

}  // namespace mpm_lig::dem::test
