#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <mpi.h>

#include "core/tensor.h"

namespace mpm_lig::dem {

//! A LAMMPS-style periodic box: h = [[lx, xy, xz], [0, ly, yz], [0, 0, lz]].
struct Box {
  Vec3 lo = Vec3::Zero();
  Vec3 hi = Vec3::Zero();
  double xy = 0.0, xz = 0.0, yz = 0.0;

  //! Columns are the box vectors a, b, c (upper triangular).
  Mat3 h() const {
    Mat3 m;
    m << hi.x() - lo.x(), xy, xz,  //
        0.0, hi.y() - lo.y(), yz,  //
        0.0, 0.0, hi.z() - lo.z();
    return m;
  }
  double volume() const { return h().determinant(); }
};

//! One contact between two grains, in the engine's current frame.
struct Contact {
  long id_i = 0, id_j = 0;  //!< grain ids
  Vec3 branch;              //!< from the centre of i to the (periodic image of the) centre of j
  Vec3 force;               //!< force on i from j (normal + tangential)
};

//! Two grains whose centres are closer than the sum of their radii.
struct Overlap {
  long id_i = 0, id_j = 0;  //!< grain ids
  double ratio = 0.0;       //!< overlap / radius of the smaller grain
};

//! Options for one engine instance.
struct EngineOptions {
  std::string label;     //!< who owns the instance, for error reports ("RVE 17")
  std::string log_file;  //!< empty: engine output kept in memory only (for error reports)
};

//! One DEM engine instance (LIGGGHTS or LAMMPS) on a communicator, behind the library API.
//! Every call is collective over the instance's communicator.
class Engine {
 public:
  virtual ~Engine() = default;

  //! "liggghts" or "lammps".
  virtual std::string name() const = 0;
  //! Run one input line.
  virtual void command(const std::string& line) = 0;
  //! Run several input lines (a script with newlines).
  virtual void commands(const std::string& script) = 0;

  virtual Box box() const = 0;
  virtual long atom_count() const = 0;
  //! A global scalar (`compute_vector` for vectors) of a compute defined in the input.
  virtual double compute_scalar(const std::string& compute_id) = 0;
  virtual std::vector<double> compute_vector(const std::string& compute_id, int length) = 0;
  //! Per-atom property gathered on every rank of the instance, ordered by atom id
  //! (`name` as in lammps_gather_atoms: "x", "v", "radius", ...; `count` values per atom).
  virtual std::vector<double> gather_atoms(const std::string& name, int count) = 0;
  //! Set a per-atom property from `values` in gather_atoms' layout (every rank passes all atoms).
  virtual void scatter_atoms(const std::string& name, int count,
                             const std::vector<double>& values) = 0;
  //! Integer per-atom properties ("image": the packed periodic image flags), as gather_atoms.
  virtual std::vector<int> gather_atom_ints(const std::string& name, int count) = 0;
  //! Set an integer per-atom property, as scatter_atoms.
  virtual void scatter_atom_ints(const std::string& name, int count,
                                 const std::vector<int>& values) = 0;
  //! All contacts with their forces (for Σ r⊗f / V and force-chain snapshots), on every rank
  //! of the instance. Forces are evaluated at the current positions and velocities, without
  //! touching the contact history (LIGGGHTS: compute pair/gran/local; LAMMPS: compute
  //! pair/local + property/local, set up by a `run 0 post no` after every run). After a run
  //! under `fix deform` the periodic images still sit in the previous step's cell (LAMMPS: the
  //! branch is the one the force used) and the virial of the last step used mid-step
  //! velocities in its damping terms: after a `run 0` both agree to round-off. Needs a run
  //! since the pair style was defined.
  virtual std::vector<Contact> contacts() = 0;
  //! The overlapping pairs (a pair may appear twice), from the pair style's neighbour list as
  //! the last run left it: no force is evaluated, so it costs a small part of contacts(). The
  //! distance is the minimum image in the current box, as in contacts(). Needs a run since
  //! the pair style was defined.
  virtual std::vector<Overlap> overlaps() = 0;

  //! Add the velocity field `gradient`·(x − `origin`) to every grain (x its position; in 2D the
  //! in-plane rows only) and then take out the packing's net momentum: what `variable … atom`,
  //! `velocity all set … sum yes units box` and `velocity all zero linear` do. LIGGGHTS does
  //! their arithmetic in place, in their order (no command parsed); results are the same bit
  //! for bit.
  virtual void add_velocity_field(const Mat3& gradient, const Vec3& origin, int dimension) = 0;
  //! Run `steps` DEM steps as the continuation of the last run, without the engine's set-up
  //! (`run N pre no post no`: no re-initialisation, neighbour build, atom sort or force
  //! evaluation), the box driven by `deform_fix`, a `fix ID all deform …` line whose ID the
  //! last run with a set-up already held: the fix is replaced in its slot and its start box,
  //! end box and rates set as its set-up would set them. Valid only while nothing since that
  //! run has changed the atoms, the box or the styles (docs/DESIGN.md §3.3). Throws
  //! std::logic_error where the engine cannot (LAMMPS: its contact computes set up after every
  //! run) or the fix is not there.
  virtual void run_continued(const std::string& /*deform_fix*/, int /*steps*/) {
    throw std::logic_error(name() + " cannot continue a run without its set-up");
  }

  //! The last lines the engine printed (kept in memory even when its screen is off).
  virtual std::string recent_output() const = 0;
};

//! Engines that can be named in a case file.
std::vector<std::string> engine_names();

//! Create an instance of engine `name` on `comm`. The engine's module is loaded on first use
//! (both libraries export the same symbols, so each lives in its own dlopen'ed module).
std::unique_ptr<Engine> create_engine(const std::string& name, MPI_Comm comm,
                                      const EngineOptions& options);

}  // namespace mpm_lig::dem
