#include "materials/material.h"

namespace mpm_lig::materials {

void Material::write_checkpoint(CheckpointWriter& out, std::size_t points) {
  const std::size_t names = state_names().size();
  std::vector<double> values;
  values.reserve(points * names);
  for (std::size_t point = 0; point < points; ++point) {
    for (std::size_t k = 0; k < names; ++k)
      values.push_back(state(point, k));
  }
  out.write("state", values);
}

void Material::restore_checkpoint(const CheckpointReader& in, const std::vector<Mat3>& stress) {
  const std::size_t names = state_names().size();
  const std::vector<double> values = in.read("state");
  if (values.size() != stress.size() * names)
    throw std::runtime_error(in.describe() + " holds " + std::to_string(values.size()) +
                             " state values, the case's " + std::to_string(stress.size()) +
                             " points of type '" + type() + "' need " +
                             std::to_string(stress.size() * names));
  for (std::size_t point = 0; point < stress.size(); ++point) {
    restore_stress(point, stress[point]);
    for (std::size_t k = 0; k < names; ++k)
      set_state(point, k, values[point * names + k]);
  }
}

}  // namespace mpm_lig::materials
