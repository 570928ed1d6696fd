#include "coupling/dem_rve_material.h"

#include <filesystem>
#include <stdexcept>

#include "core/mpi_session.h"
#include "rve/consolidation.h"

namespace mpm_lig::coupling {
namespace {

//! Strain of the uniaxial probe that measures a packing's constrained modulus: small enough
//! to stay elastic, large enough to rise above the packing's stress fluctuations.
constexpr double kProbeStrain = 1e-4;
constexpr int kPackingValues = 11;  // stress (9), void ratio, wave modulus

//! Constrained modulus M = Δσ_xx / ε_xx from a uniaxial compression of `rve`. Destroys the
//! state of `rve`: call after its restart file is written.
double probe_wave_modulus(rve::Rve& rve) {
  const double before = rve.stress()(0, 0);
  Mat3 dF = Mat3::Identity();
  dF(0, 0) -= kProbeStrain;
  rve.deform(dF);
  return std::abs(rve.stress()(0, 0) - before) / kProbeStrain;
}

std::vector<double> describe(const Packing& p) {
  std::vector<double> v(p.stress.data(), p.stress.data() + 9);
  v.push_back(p.void_ratio);
  v.push_back(p.wave_modulus);
  return v;
}

Packing packing_from(const double* v, const std::string& restart_file) {
  Packing p;
  p.stress = Eigen::Map<const Mat3>(v);
  p.void_ratio = v[9];
  p.wave_modulus = v[10];
  p.restart_file = restart_file;
  return p;
}

}  // namespace

DemRveMaterial::DemRveMaterial(const CaseNode& node) : path_(node.path()) {
  node.get<std::string>("type");
  spec_ = rve::parse_rve_spec(node.child("rve"));
  packing_count_ = node.get_or<int>("packings", 1);
  if (packing_count_ < 1)
    node.fail("packings", "must be >= 1");
  if (!spec_.restart_file.empty() && packing_count_ != 1)
    node.fail("packings", "must be 1 when rve.restart_file gives the packing");
  ranks_per_rve_ = node.get_or<int>("ranks_per_rve", 1);
  if (ranks_per_rve_ < 1)
    node.fail("ranks_per_rve", "must be >= 1");
}

DemRveMaterial::~DemRveMaterial() = default;

std::string DemRveMaterial::point_label(std::size_t point) const {
  return path_ + " point " + std::to_string(point);
}

void DemRveMaterial::prepare(MPI_Comm comm, const std::string& work_dir) {
  comm_ = comm;
  std::vector<std::string> files(packing_count_);
  for (int k = 0; k < packing_count_; ++k) {
    files[k] =
        spec_.restart_file.empty()
            ? (std::filesystem::path(work_dir) / ("packing_" + std::to_string(k) + ".restart"))
                  .string()
            : spec_.restart_file;
  }
  // The packings are spread over the rank groups like RVEs are.
  RveLayout layout(comm, ranks_per_rve_, static_cast<std::size_t>(packing_count_));
  std::vector<double> owned;
  for (std::size_t k = layout.first(); k < layout.last(); ++k) {
    const std::string label = path_ + " packing " + std::to_string(k);
    std::unique_ptr<rve::Rve> rve;
    if (spec_.restart_file.empty()) {
      rve::RveSpec spec = spec_;
      spec.seed += k;
      rve = rve::Rve::generate(spec, layout.group_comm(), label);
      rve::consolidate(*rve);
      rve->write_restart(files[k]);
    } else {
      rve = rve::Rve::from_restart(spec_, files[k], layout.group_comm(), label);
    }
    Packing p;
    const rve::Observables now = rve->observe();
    p.stress = now.stress;
    p.void_ratio = now.void_ratio;
    p.wave_modulus = probe_wave_modulus(*rve);
    const std::vector<double> v = describe(p);
    owned.insert(owned.end(), v.begin(), v.end());
  }
  const std::vector<double> all = layout.gather(owned, kPackingValues);
  packings_.clear();
  for (int k = 0; k < packing_count_; ++k) {
    packings_.push_back(packing_from(&all[k * kPackingValues], files[k]));
  }
}

double DemRveMaterial::density() const {
  if (packings_.empty())
    throw std::logic_error(path_ + ": density() before prepare()");
  double solid_fraction = 0.0;
  for (const Packing& p : packings_)
    solid_fraction += 1.0 / (1.0 + p.void_ratio);
  return spec_.density * solid_fraction / static_cast<double>(packings_.size());
}

double DemRveMaterial::wave_modulus() const {
  if (packings_.empty())
    throw std::logic_error(path_ + ": wave_modulus() before prepare()");
  double m = 0.0;
  for (const Packing& p : packings_)
    m = std::max(m, p.wave_modulus);
  return m;
}

std::size_t DemRveMaterial::add_points(std::size_t count) {
  if (layout_)
    throw std::logic_error(path_ + ": points added after the first update");
  const std::size_t first = points_;
  points_ += count;
  return first;
}

void DemRveMaterial::set_stress(std::size_t /*point*/, const Mat3& /*sigma*/) {
  throw std::logic_error(path_ +
                         ": a dem_rve point's stress comes from its packing; it cannot be set");
}

Mat3 DemRveMaterial::initial_stress(std::size_t point) const {
  return packings_.at(packing_of(point)).stress;
}

void DemRveMaterial::create_rves() {
  layout_ = std::make_unique<RveLayout>(comm_, ranks_per_rve_, points_);
  stress_.resize(points_);
  substeps_.assign(points_, 0.0);
  for (std::size_t p = 0; p < points_; ++p)
    stress_[p] = initial_stress(p);
  for (std::size_t p = layout_->first(); p < layout_->last(); ++p) {
    rves_.push_back(rve::Rve::from_restart(spec_, packings_[packing_of(p)].restart_file,
                                           layout_->group_comm(), point_label(p)));
  }
}

void DemRveMaterial::update(const std::vector<std::size_t>& points, const std::vector<Mat3>& dF,
                            double /*dt*/, std::vector<Mat3>& stress) {
  if (!layout_)
    create_rves();
  std::vector<long> batch_index(points_, -1);
  for (std::size_t i = 0; i < points.size(); ++i)
    batch_index[points[i]] = static_cast<long>(i);

  std::vector<Mat3> owned_stress;
  std::vector<double> owned_steps;
  for (std::size_t p = layout_->first(); p < layout_->last(); ++p) {
    rve::Rve& rve = *rves_[p - layout_->first()];
    double steps = 0.0;
    if (batch_index[p] >= 0) {
      // One rank's failure must end the whole job: the others are about to wait for it.
      try {
        steps = rve.deform(dF[batch_index[p]]);
        stress_[p] = rve.stress();
        if (!stress_[p].allFinite())
          throw std::runtime_error("stress is not finite (NaN)");
        if (rve.engine().atom_count() != spec_.grains)
          throw std::runtime_error("lost grains");
      } catch (const std::exception& e) {
        abort_job(point_label(p) + ": " + e.what(), kExitEngineFailure);
      }
    }
    owned_stress.push_back(stress_[p]);
    owned_steps.push_back(steps);
  }
  stress_ = layout_->gather(owned_stress);
  substeps_ = layout_->gather(owned_steps, 1);
  for (std::size_t i = 0; i < points.size(); ++i)
    stress[i] = stress_[points[i]];
}

std::vector<std::string> DemRveMaterial::state_names() const {
  return {"dem_substeps", "rve_group"};
}

double DemRveMaterial::state(std::size_t point, std::size_t k) const {
  if (k == 0)
    return point < substeps_.size() ? substeps_[point] : 0.0;
  return layout_ ? static_cast<double>(layout_->owner(point)) : 0.0;
}

double DemRveMaterial::particle_steps() const {
  double total = 0.0;
  for (const auto& rve : rves_)
    total += rve->particle_steps();
  return total;
}

}  // namespace mpm_lig::coupling
