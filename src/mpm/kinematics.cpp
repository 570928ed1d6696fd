#include "mpm/kinematics.h"

#include <stdexcept>

#include "mpm/nonlocal_deformation.h"
#include "mpm/volumetric_smoothing.h"

namespace mpm_lig::mpm {

template <int D>
void KinematicsOperator<D>::pull_back(const KinematicsContext<D>&, std::vector<Tensor>&) const {
  throw std::logic_error("the kinematics operator " + name() +
                         " has no work-conjugate for an energy's forces");
}

template class KinematicsOperator<2>;
template class KinematicsOperator<3>;

template <int D>
std::vector<std::unique_ptr<KinematicsOperator<D>>> kinematics_operators(const MpmCase& c) {
  // A new operator: its case key in read_analysis (case_reader.cpp) and one line here.
  std::vector<std::unique_ptr<KinematicsOperator<D>>> operators;
  // The non-local average first: the F-bar then corrects the volume change of the averaged
  // increments, cell by cell, as it does the local ones.
  if (c.internal_length > 0.0 && c.internal_length_method == "nonlocal")
    operators.push_back(
        std::make_unique<NonlocalDeformation<D>>(c.internal_length, c.nonlocal_weight));
  if (c.volumetric_smoothing)
    operators.push_back(std::make_unique<VolumetricSmoothing<D>>());
  return operators;
}

template std::vector<std::unique_ptr<KinematicsOperator<2>>> kinematics_operators<2>(
    const MpmCase&);
template std::vector<std::unique_ptr<KinematicsOperator<3>>> kinematics_operators<3>(
    const MpmCase&);

}  // namespace mpm_lig::mpm
