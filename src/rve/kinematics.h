#pragma once

#include "core/tensor.h"

namespace mpm_lig::rve {

//! Result of mapping a physical deformation increment onto the engine's box (docs/DESIGN.md §2.2).
struct BoxStep {
  Mat3 target;    //!< new upper-triangular box matrix R_new (columns a, b, c)
  Mat3 rotation;  //!< Q_inc: the rotation that stays outside the box (Q <- Q Q_inc)
};

//! Split ΔF'·h (ΔF' in the RVE frame) into Q_inc·R_new with R_new upper triangular and a
//! positive diagonal, so that the engine's box can follow the stretch while the rotation is
//! kept outside.
BoxStep box_step(const Mat3& dF_rve, const Mat3& h);

//! The same periodic lattice with tilts reduced to |xy| <= lx/2, |xz| <= lx/2, |yz| <= ly/2
//! (a change of cell basis by integer combinations of the box vectors: no deformation).
Mat3 reduce_tilts(const Mat3& h);

}  // namespace mpm_lig::rve
