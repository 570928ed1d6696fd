#include "mpm/register.h"

#include "mpm/case_spec.h"
#include "mpm/driver.h"

namespace mpm_lig::mpm {
namespace {

//! An explicit MPM run on continuum materials. Serial for now: rank 0 runs it, the other
//! ranks wait (the batch-shaped material interface lets a DEM material spread out later).
class MpmAnalysis final : public Analysis {
 public:
  explicit MpmAnalysis(MpmCase c) : case_(std::move(c)) {}

  void run(const RunContext& context) override {
    int rank = 0;
    MPI_Comm_rank(context.comm, &rank);
    if (rank == 0) {
      if (case_.dimension == 2)
        run_case<2>(case_, context.output_dir);
      else
        run_case<3>(case_, context.output_dir);
    }
    MPI_Barrier(context.comm);
  }

 private:
  MpmCase case_;
};

}  // namespace

std::unique_ptr<Analysis> make_analysis(const CaseNode& root,
                                        const materials::MaterialRegistry& materials) {
  return std::make_unique<MpmAnalysis>(read_case(root, materials));
}

void register_analyses(AnalysisRegistry& registry) {
  registry.add("mpm", [](const CaseNode& root) {
    materials::MaterialRegistry materials;
    materials::register_materials(materials);
    return make_analysis(root, materials);
  });
}

}  // namespace mpm_lig::mpm
