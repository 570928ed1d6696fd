#pragma once

#include <iomanip>
#include <sstream>
#include <string>

#include "core/tensor.h"

namespace mpm_lig::dem {

//! The engine commands that add the velocity field `gradient`·(x − `origin`) to every grain (in
//! 2D the in-plane rows) and then take out the net momentum, with variables named
//! `prefix`_x, _y, _z. Numbers are written with 17 digits: they parse back to the same doubles.
inline std::string velocity_field_commands(const Mat3& gradient, const Vec3& origin, int dimension,
                                           const std::string& prefix) {
  constexpr const char* kAxes = "xyz";
  std::ostringstream script;
  script << std::setprecision(17);
  for (int i = 0; i < 3; ++i) {
    script << "variable " << prefix << '_' << kAxes[i] << " atom ";
    for (int j = 0; j < 3; ++j)
      script << (j ? "+" : "") << "(" << gradient(i, j) << ")*(" << kAxes[j] << "-(" << origin[j]
             << "))";
    script << '\n';
  }
  script << "velocity all set v_" << prefix << "_x v_" << prefix << "_y "
         << (dimension == 3 ? "v_" + prefix + "_z" : std::string("NULL"))
         << " sum yes units box\nvelocity all zero linear\n";
  return script.str();
}

}  // namespace mpm_lig::dem
