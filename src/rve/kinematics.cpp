#include "rve/kinematics.h"

#include <cmath>

namespace mpm_lig::rve {

BoxStep box_step(const Mat3& dF_rve, const Mat3& h) {
  const Mat3 m = dF_rve * h;
  Eigen::HouseholderQR<Mat3> qr(m);
  Mat3 q = qr.householderQ();
  Mat3 r = qr.matrixQR().triangularView<Eigen::Upper>();
  // Make the diagonal positive: M = (Q D)(D R) with D = diag(±1).
  for (int i = 0; i < 3; ++i) {
    if (r(i, i) < 0.0) {
      r.row(i) *= -1.0;
      q.col(i) *= -1.0;
    }
  }
  return {r, q};
}

Mat3 reduce_tilts(const Mat3& h) {
  Mat3 out = h;
  // c -= k b, then c -= k a, then b -= k a: each keeps the matrix upper triangular.
  const double kb = std::round(out(1, 2) / out(1, 1));
  out.col(2) -= kb * out.col(1);
  const double kca = std::round(out(0, 2) / out(0, 0));
  out.col(2) -= kca * out.col(0);
  const double kba = std::round(out(0, 1) / out(0, 0));
  out.col(1) -= kba * out.col(0);
  return out;
}

}  // namespace mpm_lig::rve
