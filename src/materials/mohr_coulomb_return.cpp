#include "materials/mohr_coulomb_return.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace mpm_lig::materials {
namespace {

//! One yield plane f = a·σ − k on the ordered pair (i, j), i the larger principal stress,
//! with its flow direction b (gradient of the plastic potential).
struct Plane {
  Vec3 a;
  Vec3 b;
  double k;
};

Plane plane(int i, int j, const MohrCoulombStrength& s) {
  const double sf = std::sin(s.friction);
  const double sd = std::sin(s.dilatancy);
  Plane p{Vec3::Zero(), Vec3::Zero(), 2.0 * s.cohesion * std::cos(s.friction)};
  p.a[i] = 1.0 + sf;
  p.a[j] = -(1.0 - sf);
  p.b[i] = 1.0 + sd;
  p.b[j] = -(1.0 - sd);
  return p;
}

//! Principal elastic stiffness times a vector: λ tr(v) 1 + 2G v.
Vec3 stiffness(const Elasticity& e, const Vec3& v) {
  return e.lame * v.sum() * Vec3::Ones() + 2.0 * e.shear * v;
}

//! Tolerance for "admissible" and for principal ordering, relative to the stress level.
double tolerance(const Vec3& trial, const MohrCoulombStrength& s) {
  return 1e-12 * (trial.cwiseAbs().maxCoeff() + s.cohesion) + 1e-300;
}

Vec3 plane_return(const Vec3& trial, const Plane& p, const Elasticity& e) {
  const Vec3 db = stiffness(e, p.b);
  return trial - ((p.a.dot(trial) - p.k) / p.a.dot(db)) * db;
}

//! Return onto the line where planes p and q meet; false if a multiplier is negative.
bool edge_return(const Vec3& trial, const Plane& p, const Plane& q, const Elasticity& e,
                 Vec3& out) {
  const Vec3 dp = stiffness(e, p.b);
  const Vec3 dq = stiffness(e, q.b);
  Eigen::Matrix2d m;
  m << p.a.dot(dp), p.a.dot(dq), q.a.dot(dp), q.a.dot(dq);
  const Eigen::Vector2d f(p.a.dot(trial) - p.k, q.a.dot(trial) - q.k);
  const Eigen::Vector2d gamma = m.inverse() * f;
  out = trial - gamma[0] * dp - gamma[1] * dq;
  return gamma[0] >= 0.0 && gamma[1] >= 0.0;
}

//! Rankine return of the principal stresses above σ_t (associated flow), active set grown
//! until no other principal stress exceeds σ_t.
Vec3 tension_return(const Vec3& sigma, const Elasticity& e, double cutoff) {
  std::array<bool, 3> active = {false, false, false};
  Vec3 out = sigma;
  for (int pass = 0; pass < 3; ++pass) {
    bool grown = false;
    for (int i = 0; i < 3; ++i) {
      if (!active[i] && out[i] > cutoff) {
        active[i] = true;
        grown = true;
      }
    }
    if (!grown)
      break;
    // Solve D_JJ Δγ_J = σ_J − σ_t on the active set J, then σ = σ − D_:J Δγ_J.
    Mat3 d = Mat3::Identity();
    Vec3 rhs = Vec3::Zero();
    for (int i = 0; i < 3; ++i) {
      if (!active[i])
        continue;
      rhs[i] = sigma[i] - cutoff;
      for (int j = 0; j < 3; ++j)
        d(i, j) = active[j] ? e.lame + (i == j ? 2.0 * e.shear : 0.0) : (i == j ? 1.0 : 0.0);
    }
    const Vec3 gamma = d.partialPivLu().solve(rhs);
    out = sigma - stiffness(e, gamma);
  }
  return out;
}

}  // namespace

double MohrCoulombStrength::yield(const Vec3& s) const {
  const double sf = std::sin(friction);
  return (s[0] - s[2]) + (s[0] + s[2]) * sf - 2.0 * cohesion * std::cos(friction);
}

bool MohrCoulombStrength::admissible(const Vec3& sorted) const {
  return yield(sorted) <= tolerance(sorted, *this) && sorted[0] <= tension_cutoff;
}

double MohrCoulombStrength::apex() const {
  return friction > 0.0 ? cohesion / std::tan(friction) : std::numeric_limits<double>::infinity();
}

Vec3 mohr_coulomb_return(const Vec3& trial, const Elasticity& e, const MohrCoulombStrength& s,
                         ReturnKind* kind) {
  ReturnKind landed = ReturnKind::elastic;
  const double tol = tolerance(trial, s);
  Vec3 out = trial;
  if (s.yield(trial) > tol) {
    const Plane main = plane(0, 2, s);
    out = plane_return(trial, main, e);
    landed = ReturnKind::plane;
    if (out[1] > out[0] + tol || out[2] > out[1] + tol) {
      // Off the face: σ1 = σ2 (planes 1-3 and 2-3) or σ2 = σ3 (planes 1-3 and 1-2).
      const bool upper = out[1] > out[0] + tol;
      const Plane other = upper ? plane(1, 2, s) : plane(0, 1, s);
      const bool positive = edge_return(trial, main, other, e, out);
      const bool ordered = upper ? out[0] + tol >= out[2] : out[0] + tol >= out[1];
      landed = ReturnKind::edge;
      if ((!positive || !ordered) && s.friction > 0.0) {
        out = Vec3::Constant(s.apex());
        landed = ReturnKind::apex;
      }
    }
  }
  if (out.maxCoeff() > s.tension_cutoff) {
    out = tension_return(out, e, s.tension_cutoff);
    landed = ReturnKind::tension;
  }
  if (kind)
    *kind = landed;
  return out;
}

Vec3 plastic_strain(const Vec3& trial, const Vec3& returned, const Elasticity& e) {
  // Inverse of λ 11^T + 2G I: (I − λ/(3K) 11^T) / 2G.
  const Vec3 ds = trial - returned;
  return (ds - (e.lame / (3.0 * e.bulk)) * ds.sum() * Vec3::Ones()) / (2.0 * e.shear);
}

}  // namespace mpm_lig::materials
