// The LIGGGHTS 3.8 adapter. The only file that sees LIGGGHTS internals (lammps.h, domain.h,
// ...): the library interface of 3.8 lacks what two fixes below need.
#include <mpi.h>

#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "atom.h"
#include "compute.h"
#include "domain.h"
#include "fix.h"
#include "force.h"
#include "lammps.h"
#include "library.h"
#include "modify.h"
#include "neigh_list.h"
#include "pair.h"
#include "update.h"

#include "dem/library_engine.h"
#include "dem/neighbour_overlaps.h"

namespace mpm_lig::dem::detail {
namespace {

constexpr const char* kContactCompute = "mpm_lig_contacts";

class LiggghtsEngine final : public LibraryEngine {
 public:
  LiggghtsEngine(MPI_Comm comm, const EngineOptions& options, const ModuleOptions& module)
      : LibraryEngine(comm, options) {
    std::vector<std::string> args = engine_args("liggghts");
    std::vector<char*> argv;
    for (std::string& a : args)
      argv.push_back(a.data());
    void* handle = nullptr;
    lammps_open(static_cast<int>(argv.size()), argv.data(), comm, &handle);
    lmp_ = static_cast<LAMMPS_NS::LAMMPS*>(handle);
    adopt(handle, &lmp_->screen);
    if (!module.skip_triclinic_correction)
      correct_triclinic_lamda_box();
  }

  std::string name() const override { return "liggghts"; }

  Box box() const override {
    const LAMMPS_NS::Domain& d = *lmp_->domain;
    Box b;
    b.lo = Vec3(d.boxlo[0], d.boxlo[1], d.boxlo[2]);
    b.hi = Vec3(d.boxhi[0], d.boxhi[1], d.boxhi[2]);
    b.xy = d.xy;
    b.xz = d.xz;
    b.yz = d.yz;
    return b;
  }

  long atom_count() const override { return lammps_get_natoms(handle()); }

  std::vector<Contact> contacts() override;
  std::vector<Overlap> overlaps() override;
  void add_velocity_field(const Mat3& gradient, const Vec3& origin, int dimension) override;
  void run_continued(const std::string& deform_fix, int steps) override;

 private:
  // LIGGGHTS 3.8's Domain constructor leaves prd_lamda and prd_half_lamda at 0 (LAMMPS sets
  // 1 and 0.5, the size of the unit "lamda" box). Triclinic boxes work in lamda coordinates,
  // so with zeros the ghost cutoff and periodic remapping collapse: no ghost atoms, atoms
  // lost, and a hang on 2 ranks, all without an error. Nothing resets these values later, so
  // setting them once per instance, before any command, is enough (tests/dem shows the defect
  // without this and its absence with it). docs/DESIGN.md §3.2.
  void correct_triclinic_lamda_box() {
    for (int i = 0; i < 3; ++i) {
      lmp_->domain->prd_lamda[i] = 1.0;
      lmp_->domain->prd_half_lamda[i] = 0.5;
    }
  }

  void define_contact_compute();

  LAMMPS_NS::LAMMPS* lmp_ = nullptr;
  LAMMPS_NS::Compute* contact_compute_ = nullptr;
};

// compute pair/gran/local refuses to be created after the first run ("Need to define this
// compute before first run") because it can then miss a neighbour-list request; with `id
// force` it only reads the pair style's own list, so defining it later is safe. We lift the
// check by presenting step 0 while the compute is created.
void LiggghtsEngine::define_contact_compute() {
  const LAMMPS_NS::bigint step = lmp_->update->ntimestep;
  lmp_->update->ntimestep = 0;
  command(std::string("compute ") + kContactCompute + " all pair/gran/local id force");
  lmp_->update->ntimestep = step;
  contact_compute_ = lmp_->modify->compute[lmp_->modify->find_compute(kContactCompute)];
}

// Rows of pair/gran/local with `id force`: id_i, id_j, periodic flag, force on i (3). The
// positions it reports are wrapped into the box, so the branch vector comes from the minimum
// image of x_j - x_i instead.
std::vector<Contact> LiggghtsEngine::contacts() {
  if (!contact_compute_)
    define_contact_compute();
  constexpr int kColumns = 6;
  lammps_extract_compute(handle(), const_cast<char*>(kContactCompute), 2, 2);  // evaluate
  const std::vector<double> rows =
      gather_local_array(kContactCompute, contact_compute_->size_local_rows, kColumns);
  const std::vector<Vec3> x = positions_by_id();
  const Mat3 h = box().h();
  std::vector<Contact> result(rows.size() / kColumns);
  for (std::size_t k = 0; k < result.size(); ++k) {
    const double* row = &rows[k * kColumns];
    Contact& c = result[k];
    c.id_i = static_cast<long>(row[0]);
    c.id_j = static_cast<long>(row[1]);
    c.force = Vec3(row[3], row[4], row[5]);
    c.branch = minimum_image(x[c.id_j - 1] - x[c.id_i - 1], h);
  }
  return result;
}

// The arithmetic of the commands LibraryEngine::add_velocity_field issues, in their order: the
// atom-style variable evaluates ((g0·(x−o0) + g1·(y−o1)) + g2·(z−o2)) per grain (its numbers
// are printed with 17 digits, so they parse back to these), `velocity set … sum yes` adds it,
// and `velocity zero linear` subtracts the centre of mass's velocity, Σ m v / Σ m summed grain
// by grain and then over the ranks (Group::mass, Group::vcm).
void LiggghtsEngine::add_velocity_field(const Mat3& gradient, const Vec3& origin, int dimension) {
  LAMMPS_NS::Atom& atom = *lmp_->atom;
  const int n = atom.nlocal;
  double** x = atom.x;
  double** v = atom.v;
  const double* mass = atom.rmass;
  if (!mass)
    throw std::logic_error("liggghts add_velocity_field: grains without per-grain mass");
  const int rows = dimension == 3 ? 3 : 2;
  for (int i = 0; i < n; ++i) {
    double added[3];
    for (int r = 0; r < rows; ++r)
      added[r] = gradient(r, 0) * (x[i][0] - origin[0]) + gradient(r, 1) * (x[i][1] - origin[1]) +
                 gradient(r, 2) * (x[i][2] - origin[2]);
    for (int r = 0; r < rows; ++r)
      v[i][r] += added[r];
  }
  double mine = 0.0, momentum[3] = {0.0, 0.0, 0.0};
  for (int i = 0; i < n; ++i)
    mine += mass[i];
  for (int i = 0; i < n; ++i)
    for (int r = 0; r < 3; ++r)
      momentum[r] += v[i][r] * mass[i];
  double total = 0.0, centre[3];
  MPI_Allreduce(&mine, &total, 1, MPI_DOUBLE, MPI_SUM, comm());
  MPI_Allreduce(momentum, centre, 3, MPI_DOUBLE, MPI_SUM, comm());
  if (total > 0.0)
    for (double& c : centre)
      c /= total;
  for (int i = 0; i < n; ++i)
    for (int r = 0; r < 3; ++r)
      v[i][r] -= centre[r];
}

// `run N pre no` skips LAMMPS::init, so a fix added since the last set-up is in none of the
// engine's per-step lists, and an existing fix deform keeps the start and end boxes its last
// init() computed (docs/DESIGN.md §3.3). A fix given again under its own ID is built anew in
// the same slot of the fix list (Modify::add_fix), which the per-step lists index, and its
// init() reads the run's first and last step: those are set here as the run command will set
// them, and the fix's init() alone is called.
void LiggghtsEngine::run_continued(const std::string& deform_fix, int steps) {
  std::istringstream words(deform_fix);
  std::string keyword, id;
  words >> keyword >> id;
  LAMMPS_NS::Modify& modify = *lmp_->modify;
  const int slot = keyword == "fix" ? modify.find_fix(id.c_str()) : -1;
  if (slot < 0 || std::string(modify.fix[slot]->style) != "deform")
    throw std::logic_error("liggghts run_continued: no fix deform '" + id + "' to continue");
  command(deform_fix);
  LAMMPS_NS::Update& update = *lmp_->update;
  update.firststep = update.beginstep = update.ntimestep;
  update.laststep = update.endstep = update.ntimestep + steps;
  modify.fix[slot]->init();
  update.firststep = update.beginstep = update.laststep = update.endstep = 0;
  command("run " + std::to_string(steps) + " pre no post no");
}

std::vector<Overlap> LiggghtsEngine::overlaps() {
  LAMMPS_NS::NeighList* list = lmp_->force->pair ? lmp_->force->pair->list : nullptr;
  if (!list)
    throw std::runtime_error("liggghts overlaps: no pair neighbour list (no run yet?)");
  const auto element = [&](int ii, int& i, int& count, int*& neighbours) {
    i = list->ilist[ii];
    count = list->numneigh[i];
    neighbours = list->firstneigh[i];
  };
  const LAMMPS_NS::Atom& atom = *lmp_->atom;
  return overlaps_of(near_pair_rows(list->inum, element, atom.x, atom.radius, atom.tag));
}

}  // namespace
}  // namespace mpm_lig::dem::detail

extern "C" __attribute__((visibility("default"))) mpm_lig::dem::detail::ModuleEngine*
mpm_lig_create_engine(MPI_Comm comm, const mpm_lig::dem::EngineOptions* options,
                      const mpm_lig::dem::detail::ModuleOptions* module_options) {
  return new mpm_lig::dem::detail::LiggghtsEngine(comm, *options, *module_options);
}
