// The LAMMPS adapter (library interface; lammps.h only to point the screen at our record).
#include <mpi.h>

#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "lammps.h"
#include "library.h"

#include "dem/library_engine.h"
#include "dem/neighbour_overlaps.h"

namespace mpm_lig::dem::detail {
namespace {

constexpr const char* kContactForces = "mpm_lig_contact_forces";
constexpr const char* kContactIds = "mpm_lig_contact_ids";
//! Relative branch mismatch beyond which two rows cannot describe the same pair.
constexpr double kSamePairTolerance = 0.05;

class LammpsEngine final : public LibraryEngine {
 public:
  LammpsEngine(MPI_Comm comm, const EngineOptions& options) : LibraryEngine(comm, options) {
    std::vector<std::string> args = engine_args("lammps");
    args.push_back("-nocite");
    std::vector<char*> argv;
    for (std::string& a : args)
      argv.push_back(a.data());
    void* handle = lammps_open(static_cast<int>(argv.size()), argv.data(), comm, nullptr);
    adopt(handle, &static_cast<LAMMPS_NS::LAMMPS*>(handle)->screen);
  }

  std::string name() const override { return "lammps"; }

  Box box() const override {
    Box b;
    double lo[3], hi[3];
    int periodic[3], box_change = 0;
    lammps_extract_box(handle(), lo, hi, &b.xy, &b.yz, &b.xz, periodic, &box_change);
    b.lo = Vec3(lo[0], lo[1], lo[2]);
    b.hi = Vec3(hi[0], hi[1], hi[2]);
    return b;
  }

  long atom_count() const override { return std::lround(lammps_get_natoms(handle())); }

  std::vector<Contact> contacts() override;
  std::vector<Overlap> overlaps() override;
  //! `run 0 post no` unless the last run was one (contacts()).
  void set_up_after_run();

 private:
  void define_contact_computes();
  bool computes_defined_ = false;
  long runs_at_setup_ = -1;  //!< runs() right after the contacts' last set-up
};

// pair granular's single() gives the normal force as fx,fy,fz and, as extra values, the
// tangential force on i (p1-p3) and x_i - x_j (p10-p12, the periodic image actually in
// contact). Atom ids come from property/local; both computes visit pairs within the radius
// sum (`cutoff radius`), and contacts() checks that their rows describe the same pairs.
// The computes need a run to set up their neighbour lists: `run 0 post no` does that without
// advancing time or changing the contact history (its force evaluation is a setup pass).
void LammpsEngine::define_contact_computes() {
  command(std::string("compute ") + kContactForces +
          " all pair/local fx fy fz p1 p2 p3 p10 p11 p12 cutoff radius");
  command(std::string("compute ") + kContactIds +
          " all property/local patom1 patom2 cutoff radius");
  command("run 0 post no");
  computes_defined_ = true;
}

void LammpsEngine::set_up_after_run() {
  if (!computes_defined_)
    define_contact_computes();
  else if (runs() != runs_at_setup_)
    command("run 0 post no");
  runs_at_setup_ = runs();
}

std::vector<Contact> LammpsEngine::contacts() {
  // A set-up after every run: the computes' occasional neighbour list is otherwise not rebuilt,
  // and pair granular's single() then meets atom indices beyond the current ghosts ("Not enough
  // atoms for pair granular single function", seen after ~50 MPM updates). Not after a set-up
  // of its own, so that reading the contacts twice (a snapshot after the health check) changes
  // nothing.
  set_up_after_run();
  lammps_extract_compute(handle(), const_cast<char*>(kContactForces), 2, 2);
  lammps_extract_compute(handle(), const_cast<char*>(kContactIds), 2, 2);
  const int local_rows =
      *static_cast<int*>(lammps_extract_compute(handle(), const_cast<char*>(kContactForces), 2, 4));
  const int id_rows =
      *static_cast<int*>(lammps_extract_compute(handle(), const_cast<char*>(kContactIds), 2, 4));
  if (local_rows != id_rows)
    throw std::runtime_error("lammps contacts: pair/local and property/local disagree on pairs");
  const std::vector<double> forces = gather_local_array(kContactForces, local_rows, 9);
  const std::vector<double> ids = gather_local_array(kContactIds, local_rows, 2);
  const std::vector<Vec3> x = positions_by_id();
  const Mat3 h = box().h();
  std::vector<Contact> result;
  for (std::size_t k = 0; k < ids.size() / 2; ++k) {
    const double* f = &forces[9 * k];
    Contact c;
    c.id_i = std::lround(ids[2 * k]);
    c.id_j = std::lround(ids[2 * k + 1]);
    // The branch the force was computed with. Across the cell boundary it is not exactly the
    // minimum image of the current positions: `fix deform` changes the box at the end of a
    // step, after its forces, and the ghost atoms (periodic images) keep the previous step's
    // cell until the next run. The two differ by one step of deformation (1e-5 of the cell
    // here, at most ~1e-3 for very coarse sub-stepping); rows of two different pairs would
    // differ by a grain size, which is what the check below looks for.
    c.branch = -Vec3(f[6], f[7], f[8]);
    const Vec3 expected = minimum_image(x[c.id_j - 1] - x[c.id_i - 1], h);
    if ((expected - c.branch).norm() > kSamePairTolerance * c.branch.norm())
      throw std::runtime_error("lammps contacts: pair/local and property/local rows differ");
    c.force = Vec3(f[0] + f[3], f[1] + f[4], f[2] + f[5]);
    if (c.force.squaredNorm() > 0.0)  // pairs within the radius sum but not (yet) pushing
      result.push_back(c);
  }
  return result;
}

// The same set-up as contacts(): an MPM update's run is followed by one either way, so that
// the results do not depend on which of the two reads the packing.
std::vector<Overlap> LammpsEngine::overlaps() {
  set_up_after_run();
  const int list = lammps_find_pair_neighlist(handle(), "granular", 1, 0, 0);
  if (list < 0)
    throw std::runtime_error("lammps overlaps: no pair neighbour list (no run yet?)");
  const auto element = [&](int ii, int& i, int& count, int*& neighbours) {
    lammps_neighlist_element_neighbors(handle(), list, ii, &i, &count, &neighbours);
  };
  auto* x = static_cast<double**>(lammps_extract_atom(handle(), "x"));
  auto* radius = static_cast<double*>(lammps_extract_atom(handle(), "radius"));
  auto* id = static_cast<LAMMPS_NS::tagint*>(lammps_extract_atom(handle(), "id"));
  return overlaps_of(
      near_pair_rows(lammps_neighlist_num_elements(handle(), list), element, x, radius, id));
}

}  // namespace
}  // namespace mpm_lig::dem::detail

extern "C" __attribute__((visibility("default"))) mpm_lig::dem::detail::ModuleEngine*
mpm_lig_create_engine(MPI_Comm comm, const mpm_lig::dem::EngineOptions* options,
                      const mpm_lig::dem::detail::ModuleOptions* /*module_options*/) {
  return new mpm_lig::dem::detail::LammpsEngine(comm, *options);
}
