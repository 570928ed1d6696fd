#include "mpm/checkpoint.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <stdexcept>

#include "core/build_id.h"
#include "core/mpi_session.h"
#include "io/atomic_file.h"
#include "io/checkpoint_file.h"
#include "io/file_digest.h"
#include "mpm/checkpoint_folder.h"

namespace mpm_lig::mpm {
namespace {

//! The bounded second gradient's relaxed part K and its dissipated energy.
constexpr const char* kRelaxedGradient = "gradient_relaxed";
//! output.damping_work's running sum.
constexpr const char* kDampingWork = "damping_work";

namespace fs = std::filesystem;

std::string material_name(const MpmCase& c, std::size_t m) {
  return "m" + std::to_string(c.material_ids[m]);
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

//! Where a penalty footing's anchors go (docs/footing_contact.md).
std::string footing_anchors_name(std::size_t footing) {
  return "footing" + std::to_string(footing) + "_anchors";
}

//! A penalty footing's anchors as (touching 0/1, position) per point: checkpoints hold finite
//! values only, and a point that does not touch has no anchor (NaN in memory).
template <class Vec>
std::vector<double> flatten_anchors(const std::vector<Vec>& anchors, std::size_t points) {
  std::vector<double> out;
  for (std::size_t k = 0; k < points; ++k) {
    const bool touching = k < anchors.size() && !std::isnan(anchors[k][0]);
    out.push_back(touching ? 1.0 : 0.0);
    for (int d = 0; d < Vec::SizeAtCompileTime; ++d)
      out.push_back(touching ? anchors[k][d] : 0.0);
  }
  return out;
}

template <int D>
std::vector<Eigen::Matrix<double, D, 1>> unflatten_anchors(const std::vector<double>& flat,
                                                           std::size_t points,
                                                           const std::string& what) {
  if (flat.size() != points * (D + 1))
    throw std::runtime_error("checkpoint: '" + what + "' does not match the case's points");
  std::vector<Eigen::Matrix<double, D, 1>> anchors(points);
  for (std::size_t k = 0; k < points; ++k) {
    const double* row = flat.data() + k * (D + 1);
    anchors[k] =
        row[0] != 0.0
            ? Eigen::Matrix<double, D, 1>(Eigen::Map<const Eigen::Matrix<double, D, 1>>(row + 1))
            : Eigen::Matrix<double, D, 1>::Constant(std::nan(""));
  }
  return anchors;
}

template <class T>
void unflatten(const std::vector<double>& flat, std::vector<T>& values, const std::string& what) {
  if (flat.size() != values.size() * T::SizeAtCompileTime)
    throw std::runtime_error("checkpoint: '" + what + "' does not match the case's points");
  for (std::size_t k = 0; k < values.size(); ++k)
    values[k] = Eigen::Map<const T>(flat.data() + k * T::SizeAtCompileTime);
}

//! Material `m`'s part of a checkpoint: its arrays are "m<id>_<name>" in mpm.h5 (written
//! by rank 0), its files go to the folder m<id>/.
class MaterialWriter final : public materials::CheckpointWriter {
 public:
  MaterialWriter(io::CheckpointFile* file, std::string prefix, std::string folder,
                 std::map<std::string, std::string>& digests)
      : file_(file), prefix_(std::move(prefix)), folder_(std::move(folder)), digests_(digests) {}
  std::string folder() const override { return folder_; }
  void write(const std::string& name, const std::vector<double>& values) override {
    if (file_)
      file_->write(prefix_ + name, values);
  }
  void set(const std::string& name, double value) override {
    if (file_)
      file_->set(prefix_ + name, value);
  }
  void record_digest(const std::string& file, const std::string& sha256) override {
    digests_[fs::path(folder_).filename().string() + "/" + file] = sha256;
  }

 private:
  io::CheckpointFile* file_;  // null on ranks other than 0
  std::string prefix_, folder_;
  std::map<std::string, std::string>& digests_;  // checkpoint-relative file -> SHA-256
};

class MaterialReader final : public materials::CheckpointReader {
 public:
  MaterialReader(const io::CheckpointFile& file, std::string prefix, std::string folder)
      : file_(file), prefix_(std::move(prefix)), folder_(std::move(folder)) {}
  std::string folder() const override { return folder_; }
  bool has(const std::string& name) const override { return file_.has(prefix_ + name); }
  std::vector<double> read(const std::string& name) const override {
    return file_.read(prefix_ + name);
  }
  double get(const std::string& name) const override { return file_.get(prefix_ + name); }
  std::string describe() const override {
    return "checkpoint '" + fs::path(folder_).parent_path().string() + "', material " +
           fs::path(folder_).filename().string();
  }

 private:
  const io::CheckpointFile& file_;
  std::string prefix_, folder_;
};

//! The stresses of material `m`'s points, by point index.
template <int D>
std::vector<Mat3> material_stresses(const Particles<D>& p, std::size_t m) {
  std::vector<Mat3> stress;
  for (std::size_t k = 0; k < p.size(); ++k) {
    if (p.material[k] != static_cast<int>(m))
      continue;
    if (p.material_point[k] >= stress.size())
      stress.resize(p.material_point[k] + 1, Mat3::Zero());
    stress[p.material_point[k]] = p.stress[k];
  }
  return stress;
}

template <int D>
void write_state(const MpmCase& c, const Solver<D>& solver, const RecorderState& recorder,
                 io::CheckpointFile& file, const std::string& dir) {
  const Particles<D>& p = solver.particles();
  file.write("position", flatten(p.position));
  file.write("reference", flatten(p.reference));
  file.write("velocity", flatten(p.velocity));
  file.write("deformation", flatten(p.deformation));
  file.write("stress", flatten(p.stress));
  file.write("volume", p.volume);
  if (solver.second_gradient() && solver.second_gradient()->bounded())
    file.write(kRelaxedGradient, solver.second_gradient()->relaxation_state(p.size()));
  if (c.record_damping_work)
    file.write(kDampingWork, std::vector<double>{solver.damping_work()});
  std::vector<double> footings;
  for (const auto& f : solver.footings()) {
    footings.push_back(f.settlement());
    footings.push_back(f.load());
    footings.insert(footings.end(), f.reaction().data(), f.reaction().data() + D);
  }
  file.write("footings", footings);
  for (std::size_t k = 0; k < solver.footings().size(); ++k) {
    const RigidFooting<D>& f = solver.footings()[k];
    if (!f.presses())
      continue;
    file.write(footing_anchors_name(k), flatten_anchors(f.anchors(), p.size()));
  }
  file.set("format", CheckpointFolder::kFormat);
  file.set("time", solver.time());
  file.set("steps", static_cast<double>(solver.steps()));
  file.set("history_rows", static_cast<double>(recorder.history_rows));
  file.set("peak_q", recorder.peak_bearing_pressure);
  file.set("largest_stiffened_cfl", recorder.largest_stiffened_cfl);
  file.close();
  std::ofstream out(dir + "/" + CheckpointFolder::kCase);
  out << c.document.dump(1) << '\n';
  out.close();
  if (!out)
    throw std::runtime_error("cannot write '" + dir + "/" + CheckpointFolder::kCase + "'");
  std::ofstream build(dir + "/" + CheckpointFolder::kBuild);
  build << build_id() << '\n';
  build.close();
  if (!build)
    throw std::runtime_error("cannot write '" + dir + "/" + CheckpointFolder::kBuild + "'");
}

//! Rank 0, once every rank has written its files: checksums, then `latest` (atomically), then
//! the previous checkpoint goes. A kill at any moment leaves one complete checkpoint.
void commit(const std::string& run_dir, const std::string& name,
            const std::map<std::string, std::string>& digests) {
  const std::string root = CheckpointFolder::root(run_dir);
  io::write_manifest(root + "/" + name, CheckpointFolder::kManifest, digests);
  const std::string previous = CheckpointFolder::latest_name_or_empty(run_dir);
  io::replace_file(root + "/latest", name + '\n');
  if (!previous.empty() && previous != name)
    fs::remove_all(root + "/" + previous);
}

//! Run rank 0's part of a checkpoint; a failure ends the job (the other ranks wait for it).
template <class Work>
void on_rank0_or_end_job(int rank, long step, Work&& work) {
  if (rank != 0)
    return;
  try {
    work();
  } catch (const std::exception& e) {
    abort_job("checkpoint at step " + std::to_string(step) +
                  " not written (the previous one is kept): " + e.what(),
              1);
  }
}

}  // namespace

template <int D>
std::string checkpoint_obstacle(const Solver<D>& solver) {
  for (std::size_t k = 0; k < solver.materials().size(); ++k) {
    const materials::Material* m = solver.materials()[k];
    if (!m->checkpointable())
      return "material type '" + m->type() + "' has state variables a checkpoint does not save";
  }
  return "";
}

template <int D>
bool at_exact_checkpoint(const Solver<D>& solver) {
  for (std::size_t k = 0; k < solver.materials().size(); ++k)
    if (!solver.materials()[k]->at_exact_checkpoint())
      return false;
  return true;
}

template <int D>
void write_checkpoint(const MpmCase& c, Solver<D>& solver, const RecorderState& recorder,
                      const std::string& run_dir, MPI_Comm comm) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const long step = solver.steps();
  const std::string name = CheckpointFolder::step_name(step);
  const std::string dir = CheckpointFolder::root(run_dir) + "/" + name;
  std::unique_ptr<io::CheckpointFile> file;
  on_rank0_or_end_job(rank, step, [&] {
    fs::remove_all(dir);
    for (std::size_t m = 0; m < solver.materials().size(); ++m)
      fs::create_directories(dir + "/" + material_name(c, m));
    file = std::make_unique<io::CheckpointFile>(dir + "/" + CheckpointFolder::kState,
                                                io::CheckpointFile::Mode::create);
  });
  MPI_Barrier(comm);
  std::map<std::string, std::string> digests;
  for (std::size_t m = 0; m < solver.materials().size(); ++m) {
    MaterialWriter out(file.get(), material_name(c, m) + "_", dir + "/" + material_name(c, m),
                       digests);
    solver.materials()[m]->write_checkpoint(out, material_stresses(solver.particles(), m).size());
  }
  on_rank0_or_end_job(rank, step, [&] { write_state(c, solver, recorder, *file, dir); });
  MPI_Barrier(comm);
  on_rank0_or_end_job(rank, step, [&] { commit(run_dir, name, digests); });
  MPI_Barrier(comm);
}

template <int D>
RecorderState read_checkpoint(const MpmCase& c, Solver<D>& solver, const std::string& run_dir,
                              MPI_Comm comm) {
  const std::string dir = CheckpointFolder::latest(run_dir);
  const io::CheckpointFile file(dir + "/" + CheckpointFolder::kState,
                                io::CheckpointFile::Mode::read);
  Particles<D>& p = solver.mutable_particles();
  unflatten(file.read("position"), p.position, "position");
  unflatten(file.read("reference"), p.reference, "reference");
  unflatten(file.read("velocity"), p.velocity, "velocity");
  unflatten(file.read("deformation"), p.deformation, "deformation");
  unflatten(file.read("stress"), p.stress, "stress");
  p.volume = file.read("volume");
  if (p.volume.size() != p.size())
    throw std::runtime_error("checkpoint '" + dir + "' does not match the case's points");
  if (SecondGradient<D>* gradient = solver.mutable_second_gradient();
      gradient && gradient->bounded()) {
    if (!file.has(kRelaxedGradient))
      throw std::runtime_error("checkpoint '" + dir +
                               "' has no relaxed gradient: it was not written with "
                               "analysis.internal_length.yield_strain");
    gradient->restore_relaxation(file.read(kRelaxedGradient), p.size());
  }
  if (c.record_damping_work) {
    if (!file.has(kDampingWork))
      throw std::runtime_error("checkpoint '" + dir +
                               "' has no damping work: it was not written with "
                               "output.damping_work");
    const std::vector<double> work = file.read(kDampingWork);
    if (work.size() != 1)
      throw std::runtime_error("checkpoint '" + dir + "': damping_work must hold one value");
    solver.restore_damping_work(work[0]);
  }
  const std::vector<double> footings = file.read("footings");
  auto& rigid = solver.mutable_footings();
  if (footings.size() != rigid.size() * (2 + D))
    throw std::runtime_error("checkpoint '" + dir + "' does not match the case's footings");
  for (std::size_t k = 0; k < rigid.size(); ++k) {
    const double* v = footings.data() + k * (2 + D);
    rigid[k].restore(v[0], v[1], Eigen::Map<const typename RigidFooting<D>::Vec>(v + 2));
    if (!rigid[k].presses())
      continue;
    if (!file.has(footing_anchors_name(k)))
      throw std::runtime_error("checkpoint '" + dir + "' does not match the case's footings");
    rigid[k].restore_anchors(unflatten_anchors<D>(file.read(footing_anchors_name(k)), p.size(),
                                                  footing_anchors_name(k)));
  }
  solver.restore_clock(file.get("time"), static_cast<long>(file.get("steps")));
  for (std::size_t m = 0; m < solver.materials().size(); ++m) {
    const MaterialReader in(file, material_name(c, m) + "_", dir + "/" + material_name(c, m));
    solver.materials()[m]->restore_checkpoint(in, material_stresses(p, m));
  }
  MPI_Barrier(comm);
  RecorderState r;
  r.history_rows = static_cast<long>(file.get("history_rows"));
  r.peak_bearing_pressure = file.get("peak_q");
  // Checkpoints written before it was kept: the largest from the resume on.
  if (file.has_attribute("largest_stiffened_cfl"))
    r.largest_stiffened_cfl = file.get("largest_stiffened_cfl");
  return r;
}

template void write_checkpoint<2>(const MpmCase&, Solver<2>&, const RecorderState&,
                                  const std::string&, MPI_Comm);
template void write_checkpoint<3>(const MpmCase&, Solver<3>&, const RecorderState&,
                                  const std::string&, MPI_Comm);
template RecorderState read_checkpoint<2>(const MpmCase&, Solver<2>&, const std::string&, MPI_Comm);
template RecorderState read_checkpoint<3>(const MpmCase&, Solver<3>&, const std::string&, MPI_Comm);
template std::string checkpoint_obstacle<2>(const Solver<2>&);
template std::string checkpoint_obstacle<3>(const Solver<3>&);
template bool at_exact_checkpoint<2>(const Solver<2>&);
template bool at_exact_checkpoint<3>(const Solver<3>&);

}  // namespace mpm_lig::mpm
