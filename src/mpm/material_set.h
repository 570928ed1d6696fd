#pragma once

#include <cstddef>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <mpi.h>

#include "core/test_hooks.h"
#include "materials/material.h"

namespace mpm_lig::mpm {

//! The live materials of a case, in case order (Body::material indexes it).
//!
//! Their life has three stages, in this order: created by read_case (case nodes validated,
//! nothing allocated), prepared once by prepare() (collective: a DEM material makes its
//! packings), then owned by the Solver that steps them. Constness is deep: a const set hands
//! out const materials only, so a collective or mutating call needs a mutable owner.
class MaterialSet {
 public:
  MaterialSet() = default;

  //! Append a material created from its case node (before prepare()).
  void add(std::unique_ptr<materials::Material> material);

  std::size_t size() const { return materials_.size(); }
  const materials::Material* operator[](std::size_t m) const { return materials_[m].get(); }
  materials::Material* operator[](std::size_t m) { return materials_[m].get(); }

  //! Collective over `comm`: every material's prepare(), material m in `work_dir`/m<id>
  //! (id = case_ids[m], the case file's). Once only, and before a Solver is built from the
  //! set (it reads densities and wave moduli).
  void prepare(const std::vector<int>& case_ids, MPI_Comm comm, const std::string& work_dir,
               const TestHooks& hooks = {});
  bool prepared() const { return prepared_; }

  //! Statistics every run reports, at their zero values (MaterialRegistry::statistics()).
  void set_zero_statistics(materials::Report zero) { zero_statistics_ = std::move(zero); }
  //! The zero statistics and every material's report(), merged (this rank's; for summary.json).
  materials::Statistics statistics() const;

 private:
  std::vector<std::unique_ptr<materials::Material>> materials_;
  bool prepared_ = false;
  materials::Report zero_statistics_;
};

}  // namespace mpm_lig::mpm
