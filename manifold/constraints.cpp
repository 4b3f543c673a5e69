#include "manifold/constraints.h"

#include <cmath>
#include <limits>

namespace dp::manifold {

namespace {

// |h^ . n| below this is a grazing half vector; |w . ng| below it a grazing ray.
constexpr double kGrazing = 1e-9;
// A 2x2 block with |det| <= kSingular ||D||_F^2 is treated as singular.
constexpr double kSingular = 1e-12;

using Mat23d = Eigen::Matrix<double, 2, 3>;
using Mat32d = Eigen::Matrix<double, 3, 2>;

bool invert2(const Mat2d& m, Mat2d& inv, double& det) {
  det = m.determinant();
  const double scale = m.squaredNorm();
  if (!std::isfinite(det) || !(std::abs(det) > kSingular * scale)) return false;
  inv << m(1, 1), -m(0, 1), -m(1, 0), m(0, 0);
  inv /= det;
  return inv.allFinite();
}

Mat32d tangents(const ChainVertex& v) {
  Mat32d m;
  m.col(0) = v.f.T1;
  m.col(1) = v.f.T2;
  return m;
}

Mat3d projector(const Vec3d& w) { return Mat3d::Identity() - w * w.transpose(); }

}  // namespace

const char* to_string(WalkStatus s) {
  switch (s) {
    case WalkStatus::ok: return "ok";
    case WalkStatus::singular: return "singular";
    case WalkStatus::total_internal_reflection: return "total_internal_reflection";
    case WalkStatus::grazing: return "grazing";
    case WalkStatus::miss: return "miss";
    case WalkStatus::different_object: return "different_object";
    case WalkStatus::index_matched: return "index_matched";
    case WalkStatus::max_iterations: return "max_iterations";
    case WalkStatus::step_too_small: return "step_too_small";
    case WalkStatus::not_reversible: return "not_reversible";
    case WalkStatus::invalid_input: return "invalid_input";
  }
  return "?";
}

WalkStatus half_vector(const Chain& chain, int i, HalfVector& out) {
  const ChainVertex& v = chain.v[size_t(i)];
  if (i == 1 && chain.pin == Pin::direction) {
    out.w_a = -chain.start_dir;
    out.d_a = std::numeric_limits<double>::infinity();
  } else {
    const Vec3d da = chain.v[size_t(i - 1)].p() - v.p();
    out.d_a = da.norm();
    if (!(out.d_a > 0.0)) return WalkStatus::invalid_input;
    out.w_a = da / out.d_a;
  }
  const Vec3d db = chain.v[size_t(i + 1)].p() - v.p();
  out.d_b = db.norm();
  if (!(out.d_b > 0.0)) return WalkStatus::invalid_input;
  out.w_b = db / out.d_b;
  if (!out.w_a.allFinite() || !out.w_b.allFinite()) return WalkStatus::invalid_input;

  const double ca = out.w_a.dot(v.f.ng), cb = out.w_b.dot(v.f.ng);
  if (std::abs(ca) < kGrazing || std::abs(cb) < kGrazing) return WalkStatus::grazing;
  out.eta_a = out.eta_b = 1.0;
  if (v.type == Interaction::reflection) {
    if (ca * cb < 0) return WalkStatus::grazing;  // sides disagree with a reflection
  } else {
    if (ca * cb > 0) return WalkStatus::grazing;
    if (v.eta == 1.0) return WalkStatus::index_matched;
    if (ca > 0) out.eta_b = v.eta;  // arriving from the exterior
    else out.eta_a = v.eta;
  }
  // Generalized half vector, J&M 2012 Eq. 9 (scaled by eta_a).
  const Vec3d h = out.eta_a * out.w_a + out.eta_b * out.w_b;
  out.h_len = h.norm();
  if (!(out.h_len > 1e-12 * (out.eta_a + out.eta_b))) return WalkStatus::singular;
  const double hn = h.dot(v.f.n) / out.h_len;
  if (std::abs(hn) < kGrazing) return WalkStatus::grazing;
  out.sigma = hn > 0 ? 1.0 : -1.0;
  out.h_hat = out.sigma * h / out.h_len;
  return WalkStatus::ok;
}

WalkStatus projected_half_vector(const Chain& chain, int i, Vec2d& out) {
  HalfVector hv;
  const WalkStatus st = half_vector(chain, i, hv);
  if (st != WalkStatus::ok) return st;
  const ChainVertex& v = chain.v[size_t(i)];
  out = Vec2d(hv.h_hat.dot(v.f.s), hv.h_hat.dot(v.f.t));
  return WalkStatus::ok;
}

WalkStatus set_targets_from_current(Chain& chain) {
  for (int i = 1; i < chain.n(); ++i) {
    Vec2d c;
    const WalkStatus st = projected_half_vector(chain, i, c);
    if (st != WalkStatus::ok) return st;
    chain.v[size_t(i)].target = c;
  }
  return WalkStatus::ok;
}

double constraint_residual(const Chain& chain) {
  double worst = 0;
  for (int i = 1; i < chain.n(); ++i) {
    Vec2d c;
    if (projected_half_vector(chain, i, c) != WalkStatus::ok) return std::numeric_limits<double>::infinity();
    worst = std::max(worst, (c - chain.v[size_t(i)].target).cwiseAbs().maxCoeff());
  }
  return worst;
}

WalkStatus derivative_blocks(const Chain& chain, Blocks& out) {
  const int n = chain.n();
  if (n < 2) return WalkStatus::invalid_input;
  out.a.assign(size_t(n + 1), Mat2d::Zero());
  out.b.assign(size_t(n + 1), Mat2d::Zero());
  out.c.assign(size_t(n + 1), Mat2d::Zero());
  for (int i = 1; i < n; ++i) {
    HalfVector hv;
    const WalkStatus st = half_vector(chain, i, hv);
    if (st != WalkStatus::ok) return st;
    const ChainVertex& v = chain.v[size_t(i)];
    Mat23d P;  // projection on the constraint frame
    P.row(0) = v.f.s.transpose();
    P.row(1) = v.f.t.transpose();
    // d h^ / d h = sigma (I - h^ h^T) / |h|;  d w / d x_far = (I - w w^T) / d.
    const Mat3d dH = hv.sigma * projector(hv.h_hat) / hv.h_len;
    const Mat23d PdH = P * dH;
    Mat3d Wa = Mat3d::Zero();
    if (std::isfinite(hv.d_a)) Wa = projector(hv.w_a) / hv.d_a;
    const Mat3d Wb = projector(hv.w_b) / hv.d_b;
    if (!(i == 1 && chain.pin == Pin::direction))
      out.a[size_t(i)] = PdH * (hv.eta_a * Wa) * tangents(chain.v[size_t(i - 1)]);
    out.c[size_t(i)] = PdH * (hv.eta_b * Wb) * tangents(chain.v[size_t(i + 1)]);
    Mat2d b = PdH * (-hv.eta_a * Wa - hv.eta_b * Wb) * tangents(v);
    // Rotation of the constraint frame with the shading normal (dn/du, dn/dv terms).
    b(0, 0) += v.f.ds1.dot(hv.h_hat);
    b(0, 1) += v.f.ds2.dot(hv.h_hat);
    b(1, 0) += v.f.dt1.dot(hv.h_hat);
    b(1, 1) += v.f.dt2.dot(hv.h_hat);
    out.b[size_t(i)] = b;
    if (!out.a[size_t(i)].allFinite() || !b.allFinite() || !out.c[size_t(i)].allFinite())
      return WalkStatus::singular;
  }
  return WalkStatus::ok;
}

namespace {

// Forward block elimination; fills U_i and returns prod det D_i.
WalkStatus eliminate(const Blocks& bl, int n, std::vector<Mat2d>& U, double& det) {
  U.assign(size_t(n + 1), Mat2d::Zero());
  det = 1.0;
  Mat2d D = bl.b[1];
  for (int i = 1; i < n; ++i) {
    if (i > 1) D = bl.b[size_t(i)] - bl.a[size_t(i)] * U[size_t(i - 1)];
    Mat2d Dinv;
    double d;
    if (!invert2(D, Dinv, d)) return WalkStatus::singular;
    det *= d;
    U[size_t(i)] = Dinv * bl.c[size_t(i)];
  }
  if (!std::isfinite(det)) return WalkStatus::singular;
  return WalkStatus::ok;
}

}  // namespace

WalkStatus tangent_map(const Chain& chain, std::vector<Mat2d>& T) {
  Blocks bl;
  WalkStatus st = derivative_blocks(chain, bl);
  if (st != WalkStatus::ok) return st;
  const int n = chain.n();
  std::vector<Mat2d> U;
  double det;
  st = eliminate(bl, n, U, det);
  if (st != WalkStatus::ok) return st;
  T.assign(size_t(n + 1), Mat2d::Zero());
  T[size_t(n)] = Mat2d::Identity();
  for (int i = n - 1; i >= 1; --i) T[size_t(i)] = -U[size_t(i)] * T[size_t(i + 1)];
  for (int i = 1; i < n; ++i)
    if (!T[size_t(i)].allFinite()) return WalkStatus::singular;
  return WalkStatus::ok;
}

WalkStatus constraint_determinant(const Chain& chain, double& det) {
  Blocks bl;
  WalkStatus st = derivative_blocks(chain, bl);
  if (st != WalkStatus::ok) return st;
  std::vector<Mat2d> U;
  return eliminate(bl, chain.n(), U, det);
}

WalkStatus generalized_geometry(const Chain& chain, double& G) {
  std::vector<Mat2d> T;
  const WalkStatus st = tangent_map(chain, T);
  if (st != WalkStatus::ok) return st;
  const double detT = std::abs(T[1].determinant());
  const ChainVertex& x1 = chain.v[1];
  if (chain.pin == Pin::direction) {
    G = detT * std::abs(chain.start_dir.dot(x1.f.ng));
  } else {
    const ChainVertex& x0 = chain.v[0];
    const Vec3d d = x0.p() - x1.p();
    const double d2 = d.squaredNorm();
    const Vec3d w = d / std::sqrt(d2);
    double cos0 = 1.0;
    if (x0.has_surface) cos0 = std::abs(w.dot(x0.f.ng));
    G = detT * cos0 * std::abs(w.dot(x1.f.ng)) / d2;
  }
  return std::isfinite(G) ? WalkStatus::ok : WalkStatus::singular;
}

}  // namespace dp::manifold
