#include "mpm/checkpoint.h"

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "coupling/dem_rve_material.h"
#include "io/checkpoint_file.h"

namespace mpm_lig::mpm {
namespace {

namespace fs = std::filesystem;

std::string material_name(const MpmCase& c, std::size_t m) {
  return "m" + std::to_string(c.material_ids[m]);
}

coupling::DemRveMaterial* as_dem(const std::unique_ptr<materials::Material>& m) {
  return dynamic_cast<coupling::DemRveMaterial*>(m.get());
}

//! Flatten fixed-size Eigen objects (vectors, 3x3 tensors) into one array.
template <class T>
std::vector<double> flatten(const std::vector<T>& values) {
  std::vector<double> out;
  out.reserve(values.size() * T::SizeAtCompileTime);
  for (const T& v : values)
    out.insert(out.end(), v.data(), v.data() + T::SizeAtCompileTime);
  return out;
}

template <class T>
void unflatten(const std::vector<double>& flat, std::vector<T>& values, const std::string& what) {
  if (flat.size() != values.size() * T::SizeAtCompileTime)
    throw std::runtime_error("checkpoint: '" + what + "' does not match the case's points");
  for (std::size_t k = 0; k < values.size(); ++k)
    values[k] = Eigen::Map<const T>(flat.data() + k * T::SizeAtCompileTime);
}

std::string read_latest(const std::string& run_dir) {
  std::ifstream in(run_dir + "/checkpoints/latest");
  std::string name;
  if (!(in >> name))
    throw std::runtime_error("no checkpoint in '" + run_dir + "' (checkpoints/latest is missing)");
  return name;
}

//! Every state variable of material `m`'s points, point by point in particle order.
template <int D>
std::vector<double> material_state(const Solver<D>& solver, std::size_t m) {
  const materials::Material& material = *solver.materials()[m];
  const std::size_t names = material.state_names().size();
  const Particles<D>& p = solver.particles();
  std::vector<double> values;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (p.material[k] != static_cast<int>(m))
      continue;
    for (std::size_t s = 0; s < names; ++s)
      values.push_back(material.state(p.material_point[k], s));
  }
  return values;
}

template <int D>
void restore_material_state(Solver<D>& solver, std::size_t m, const std::vector<double>& values,
                            const std::string& dir) {
  materials::Material& material = *solver.materials()[m];
  const std::size_t names = material.state_names().size();
  const Particles<D>& p = solver.particles();
  std::size_t next = 0;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (p.material[k] != static_cast<int>(m))
      continue;
    material.restore_stress(p.material_point[k], p.stress[k]);
    for (std::size_t s = 0; s < names; ++s) {
      if (next >= values.size())
        throw std::runtime_error("checkpoint '" + dir + "' does not match the case's points");
      material.set_state(p.material_point[k], s, values[next++]);
    }
  }
  if (next != values.size())
    throw std::runtime_error("checkpoint '" + dir + "' does not match the case's points");
}

}  // namespace

template <int D>
std::string checkpoint_obstacle(const Solver<D>& solver) {
  for (const auto& m : solver.materials()) {
    if (!m->checkpointable())
      return "material type '" + m->type() + "' has state variables a checkpoint does not save";
  }
  return "";
}

template <int D>
void write_checkpoint(const MpmCase& c, const Solver<D>& solver, const RecorderState& recorder,
                      const std::string& run_dir, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const std::string root = run_dir + "/checkpoints";
  const std::string name = "step_" + std::to_string(solver.steps());
  const std::string dir = root + "/" + name;
  if (rank == 0) {
    fs::remove_all(dir);
    for (std::size_t m = 0; m < solver.materials().size(); ++m)
      fs::create_directories(dir + "/" + material_name(c, m));
  }
  MPI_Barrier(comm);
  std::unique_ptr<io::CheckpointFile> file;
  if (rank == 0)
    file = std::make_unique<io::CheckpointFile>(dir + "/mpm.h5", io::CheckpointFile::Mode::create);
  for (std::size_t m = 0; m < solver.materials().size(); ++m) {
    coupling::DemRveMaterial* dem = as_dem(solver.materials()[m]);
    if (!dem) {
      if (file)
        file->write(material_name(c, m) + "_state", material_state(solver, m));
      continue;
    }
    const std::vector<double> rows = dem->write_checkpoint(dir + "/" + material_name(c, m));
    if (file) {
      file->write(material_name(c, m) + "_rows", rows);
      file->set(material_name(c, m) + "_updates", static_cast<double>(dem->updates()));
      file->set(material_name(c, m) + "_particle_steps", dem->cost().particle_steps);
    }
  }
  if (file) {
    const Particles<D>& p = solver.particles();
    file->write("position", flatten(p.position));
    file->write("reference", flatten(p.reference));
    file->write("velocity", flatten(p.velocity));
    file->write("deformation", flatten(p.deformation));
    file->write("stress", flatten(p.stress));
    file->write("volume", p.volume);
    std::vector<double> footings;
    for (const auto& f : solver.footings()) {
      footings.push_back(f.settlement());
      footings.push_back(f.load());
      footings.insert(footings.end(), f.reaction().data(), f.reaction().data() + D);
    }
    file->write("footings", footings);
    file->set("time", solver.time());
    file->set("steps", static_cast<double>(solver.steps()));
    file->set("history_rows", static_cast<double>(recorder.history_rows));
    file->set("peak_q", recorder.peak_q);
    file->close();
  }
  MPI_Barrier(comm);
  if (rank == 0) {
    std::string previous;
    if (fs::exists(root + "/latest"))
      previous = read_latest(run_dir);
    {
      std::ofstream out(root + "/latest.tmp");
      out << name << '\n';
      if (!out.flush())
        throw std::runtime_error("cannot write '" + root + "/latest.tmp'");
    }
    fs::rename(root + "/latest.tmp", root + "/latest");
    if (!previous.empty() && previous != name)
      fs::remove_all(root + "/" + previous);
  }
  MPI_Barrier(comm);
}

template <int D>
RecorderState read_checkpoint(const MpmCase& c, Solver<D>& solver, const std::string& run_dir,
                              MPI_Comm comm) {
  const std::string dir = run_dir + "/checkpoints/" + read_latest(run_dir);
  const io::CheckpointFile file(dir + "/mpm.h5", io::CheckpointFile::Mode::read);
  Particles<D>& p = solver.mutable_particles();
  unflatten(file.read("position"), p.position, "position");
  unflatten(file.read("reference"), p.reference, "reference");
  unflatten(file.read("velocity"), p.velocity, "velocity");
  unflatten(file.read("deformation"), p.deformation, "deformation");
  unflatten(file.read("stress"), p.stress, "stress");
  p.volume = file.read("volume");
  if (p.volume.size() != p.size())
    throw std::runtime_error("checkpoint '" + dir + "' does not match the case's points");
  const std::vector<double> footings = file.read("footings");
  auto& rigid = solver.mutable_footings();
  if (footings.size() != rigid.size() * (2 + D))
    throw std::runtime_error("checkpoint '" + dir + "' does not match the case's footings");
  for (std::size_t k = 0; k < rigid.size(); ++k) {
    const double* v = footings.data() + k * (2 + D);
    rigid[k].restore(v[0], v[1], Eigen::Map<const typename RigidFooting<D>::Vec>(v + 2));
  }
  solver.restore_clock(file.get("time"), static_cast<long>(file.get("steps")));
  for (std::size_t m = 0; m < solver.materials().size(); ++m) {
    const auto& material = solver.materials()[m];
    if (coupling::DemRveMaterial* dem = as_dem(material)) {
      const std::string n = material_name(c, m);
      dem->restore_checkpoint(dir + "/" + n, file.read(n + "_rows"),
                              static_cast<long>(file.get(n + "_updates")),
                              file.get(n + "_particle_steps"));
      continue;
    }
    restore_material_state(solver, m, file.read(material_name(c, m) + "_state"), dir);
  }
  MPI_Barrier(comm);
  RecorderState r;
  r.history_rows = static_cast<long>(file.get("history_rows"));
  r.peak_q = file.get("peak_q");
  return r;
}

template void write_checkpoint<2>(const MpmCase&, const Solver<2>&, const RecorderState&,
                                  const std::string&, MPI_Comm);
template void write_checkpoint<3>(const MpmCase&, const Solver<3>&, const RecorderState&,
                                  const std::string&, MPI_Comm);
template RecorderState read_checkpoint<2>(const MpmCase&, Solver<2>&, const std::string&, MPI_Comm);
template RecorderState read_checkpoint<3>(const MpmCase&, Solver<3>&, const std::string&, MPI_Comm);
template std::string checkpoint_obstacle<2>(const Solver<2>&);
template std::string checkpoint_obstacle<3>(const Solver<3>&);

}  // namespace mpm_lig::mpm
