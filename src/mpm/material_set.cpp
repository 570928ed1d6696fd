#include "mpm/material_set.h"

#include <stdexcept>

namespace mpm_lig::mpm {

void MaterialSet::add(std::unique_ptr<materials::Material> material) {
  if (prepared_)
    throw std::logic_error("MaterialSet::add after prepare()");
  materials_.push_back(std::move(material));
}

void MaterialSet::prepare(const std::vector<int>& case_ids, MPI_Comm comm,
                          const std::string& work_dir, const TestHooks& hooks) {
  if (prepared_)
    throw std::logic_error("MaterialSet::prepare called twice");
  materials::MaterialContext context;
  context.comm = comm;
  context.hooks = hooks;
  for (std::size_t m = 0; m < materials_.size(); ++m) {
    context.work_dir = work_dir + "/m" + std::to_string(case_ids.at(m));
    materials_[m]->prepare(context);
  }
  prepared_ = true;
}

materials::Statistics MaterialSet::statistics() const {
  materials::Statistics statistics;
  statistics.add(zero_statistics_);
  for (const auto& material : materials_)
    statistics.add(material->report());
  return statistics;
}

}  // namespace mpm_lig::mpm
