// Incremental manifold walk (Manzi 2014, Sec. 3.4) with a fixed decision: the
// near-singular geometry term of a concave corner cancels against the walk's Jacobian.
// CGAL vertex normals of a mesh without normals (mesh_normals.h).
#include <catch2/catch.hpp>

#include <cmath>
#include <iomanip>

#include "manifold/incremental.h"
#include "manifold/mesh_normals.h"
#include "tests/manifold/manifold_fixtures.h"

using namespace dp;
using namespace dp::test_mf;

namespace {

double geometry(const ChainVertex& a, const ChainVertex& b) {
  const Vec3d d = b.p() - a.p();
  const double d2 = d.squaredNorm();
  const Vec3d w = d / std::sqrt(d2);
  return std::abs(w.dot(a.f.ng)) * std::abs(w.dot(b.f.ng)) / d2;
}

}  // namespace

TEST_CASE("incremental walk: G(y~0 <-> y~1) times the Jacobian stays finite near a corner", "[unit]") {
  Builder b;
  const int floor = b.quad({0, -2, 0}, {3, -2, 0}, {3, 2, 0}, {0, 2, 0}, std::nullopt);
  const int wall = b.quad({0, -2, 0}, {0, 2, 0}, {0, 2, 3}, {0, -2, 3}, std::nullopt);
  auto s = b.commit();
  auto vert = [&](int shape, const Vec3d& p) {
    ChainVertex v;
    v.shape = shape;
    v.prim = 0;
    REQUIRE(local_frame(*s->shapes()[size_t(shape)], 0, p, v.f));
    REQUIRE(v.f.p.isApprox(p));
    if (!(v.f.p.isApprox(p))) v.prim = 1;
    return v;
  };
  const double eps = 1e-3;  // base y_1 sits eps above the corner line
  std::vector<ChainVertex> base = {vert(floor, Vec3d(0.3, 0.1, 0)), vert(wall, Vec3d(0, 0.1, eps)),
                                   make_point(Vec3d(2.0, 0.5, 1.5))};
  const double G_base = geometry(base[0], base[1]);
  auto always = [](int, const ChainVertex&, const ChainVertex&) { return true; };
  double prev_mw = 0, recon_max = 0, recon_min = 1e300, recon_at_eps = 0;
  for (const double delta : {1e-2, 1e-3, 3e-4, 1e-4}) {
    const ChainVertex moved = vert(floor, Vec3d(delta, 0.1, 0));
    const IncrementalResult r = incremental_walk(*s, base, moved, always, WalkSettings{});
    INFO("delta " << delta << " status " << to_string(r.status));
    REQUIRE(r.ok());
    REQUIRE(r.reconnect == 2);
    const double recon = geometry(moved, base[1]) / G_base;              // plain reconnection at y_1
    const double mw = geometry(r.offset[0], r.offset[1]) * r.jacobian / G_base;  // INCMW
    recon_max = std::max(recon_max, recon);
    if (delta == eps) recon_at_eps = recon;
    recon_min = std::min(recon_min, recon);
    INFO("reconnection ratio " << recon << ", manifold ratio " << mw << " (per-step product "
                               << r.per_step_product << ", exact " << r.jacobian << ")");
    // Self-similar limit: the walked configuration scales with delta, so the product
    // converges as delta -> 0 with corrections O(delta / |y_2 - y_1|).
    if (prev_mw > 0) CHECK(std::abs(mw - prev_mw) <= 0.05 * prev_mw);
    if (delta < 1e-2) prev_mw = mw;
  }
  // Reconnection: G(delta) = eps delta / (delta^2 + eps^2)^2 for this corner, so at
  // delta = eps the ratio is 1 / (4 eps^2 G_base) = 6.75e6.
  const double peak = 1.0 / (4 * eps * eps) / G_base;
  CHECK(std::abs(recon_at_eps - peak) <= 1e-9 * peak);
  INFO("reconnection ratio range [" << recon_min << ", " << recon_max << "], closed-form peak " << peak
                                    << ", manifold ratio limit " << prev_mw);
  // The manifold-walk ratio stays orders of magnitude below it.
  CHECK(prev_mw * 1e3 < recon_max);
}

// Incremental walks with 1, 2 and 3 declared vertices (floor -> side wall x = 0 -> back
// wall y = 2 -> side wall x = 3 of a box, then a point y_k where the offset reconnects):
// the exact Jacobian |d y~_{1..k-1} / d y_{1..k-1}| (block tridiagonal R solved by block
// LU, with the c_i - c~_i coupling that Manzi's per-step product drops) against the
// determinant of central differences of the walked positions: move base y_i by +-h along
// its T1, T2 (re-projected onto its quad), walk again from the same y~_0, and difference
// every y~_j in the offset's tangent frame.
// Detects: a wrong block, sign or coupling term in the Jacobian, and (2, 3 steps) the
// per-step product used as the Jacobian, which this geometry puts 2.7e-4 (2 steps) and
// 10 % (3 steps) off.
// Tolerance, per entry of the difference matrix (computed below for each geometry):
//  * truncation h^2 |y'''| / 6, with third derivatives of the walked positions of order
//    1 / L^2 for the shortest segment L of the chain (the map is built from ray directions
//    whose n-th derivatives scale as L^-n; the quads are flat, so no curvature scale);
//  * convergence over h: each walk stops within tolerance * S of its target (S = the
//    largest |position|, the walk's scale); a later step inherits the earlier error with a
//    gain up to max(1, max |J_ij|), so each of the 2 walks per entry is off by at most
//    steps * gain * tolerance * S, and their difference over 2h by that over h;
//  * double round-off of positions, 2^-52 S over h (negligible at h = 1e-4).
// The determinant's first-order relative error is tr(J^-1 dJ) <= sum_ij |J^-1_ji| e_entry.
TEST_CASE("incremental walk: multi-step Jacobian matches central differences of the walked positions", "[unit]") {
  Builder b;
  const int floor = b.quad({0, -2, 0}, {3, -2, 0}, {3, 2, 0}, {0, 2, 0}, std::nullopt);
  const int left = b.quad({0, -2, 0}, {0, 2, 0}, {0, 2, 3}, {0, -2, 3}, std::nullopt);
  const int back = b.quad({0, 2, 0}, {3, 2, 0}, {3, 2, 3}, {0, 2, 3}, std::nullopt);
  const int right = b.quad({3, 2, 0}, {3, -2, 0}, {3, -2, 3}, {3, 2, 3}, std::nullopt);
  auto s = b.commit();
  auto vert = [&](int shape, const Vec3d& p) {
    ChainVertex v;
    v.shape = shape;
    v.prim = 0;
    if (!local_frame(*s->shapes()[size_t(shape)], 0, p, v.f) || !v.f.p.isApprox(p)) {
      v.prim = 1;
      REQUIRE(local_frame(*s->shapes()[size_t(shape)], 1, p, v.f));
    }
    REQUIRE(v.f.p.isApprox(p, 1e-12));
    return v;
  };
  const ChainVertex y0 = vert(floor, Vec3d(0.6, 0.4, 0)), y1 = vert(left, Vec3d(0, 0.8, 0.7)),
                    y2 = vert(back, Vec3d(1.0, 2, 1.2)), y3 = vert(right, Vec3d(3, 1.0, 1.6));
  const std::vector<std::vector<ChainVertex>> bases = {
      {y0, y1, make_point(Vec3d(2.0, 0.5, 1.5))},
      {y0, y1, y2, make_point(Vec3d(2.0, 0.5, 1.5))},
      {y0, y1, y2, y3, make_point(Vec3d(1.5, -0.5, 2.0))}};
  const ChainVertex start = vert(floor, Vec3d(0.45, 0.5, 0));
  auto always = [](int, const ChainVertex&, const ChainVertex&) { return true; };
  WalkSettings ws;
  ws.tolerance = 1e-13;
  ws.max_iterations = 40;
  const double h = 1e-4;
  auto tc = [](const ChainVertex& v, const Vec3d& d) { return Vec2d(d.dot(v.f.T1), d.dot(v.f.T2)); };
  for (const std::vector<ChainVertex>& base : bases) {
    const int k = int(base.size()) - 1, n = 2 * (k - 1);  // reconnection index, unknowns
    const IncrementalResult r = incremental_walk(*s, base, start, always, ws);
    INFO(k - 1 << " declared vertices: status " << to_string(r.status));
    REQUIRE(r.ok());
    REQUIRE(r.reconnect == k);
    Eigen::MatrixXd J(n, n);
    for (int i = 1; i < k; ++i)
      for (int t = 0; t < 2; ++t) {
        const Vec3d dir = t == 0 ? base[size_t(i)].f.T1 : base[size_t(i)].f.T2;
        std::vector<Vec3d> walked[2];
        for (int sgn = 0; sgn < 2; ++sgn) {
          std::vector<ChainVertex> moved = base;
          moved[size_t(i)] = vert(base[size_t(i)].shape, base[size_t(i)].p() + (sgn == 0 ? h : -h) * dir);
          const IncrementalResult m = incremental_walk(*s, moved, start, always, ws);
          REQUIRE(m.ok());
          REQUIRE(m.reconnect == k);
          for (int j = 0; j < k; ++j) walked[sgn].push_back(m.offset[size_t(j)].p());
        }
        for (int j = 1; j < k; ++j) {
          const Vec2d d = tc(r.offset[size_t(j)], walked[0][size_t(j)] - walked[1][size_t(j)]) / (2 * h);
          J(2 * (j - 1), 2 * (i - 1) + t) = d.x();
          J(2 * (j - 1) + 1, 2 * (i - 1) + t) = d.y();
        }
      }
    double seg_min = 1e300, scale = 0;
    for (const std::vector<ChainVertex>* c : {&base, &r.offset})
      for (size_t j = 0; j < c->size(); ++j) {
        scale = std::max(scale, (*c)[j].p().norm());
        if (j > 0) seg_min = std::min(seg_min, ((*c)[j].p() - (*c)[j - 1].p()).norm());
      }
    const double gain = std::max(1.0, J.cwiseAbs().maxCoeff());
    const double e_entry = h * h / (6 * seg_min * seg_min) + (k - 1) * gain * ws.tolerance * scale / h +
                           std::ldexp(1.0, -52) * scale / h;
    const double tol = J.inverse().cwiseAbs().sum() * e_entry;
    const double fd = std::abs(J.determinant());
    INFO(std::setprecision(12) << "exact " << r.jacobian << ", finite differences " << fd << ", per-step product "
                               << r.per_step_product << "; relative error " << std::abs(r.jacobian - fd) / fd
                               << ", allowed " << tol << " (entry error " << e_entry << ")");
    CHECK(std::abs(r.jacobian - fd) <= tol * fd);
    // With coupling (2+ steps) the per-step product must be measurably wrong here, or
    // this geometry could not tell the exact Jacobian from it.
    if (k > 2) CHECK(std::abs(r.per_step_product - fd) > 10 * tol * fd);
  }
}

TEST_CASE("CGAL vertex normals of a tessellated sphere approximate the radial normal", "[unit]") {
  const int nu = 48, nv = 24;
  const double R = 1.3;
  auto make = [&]() {
    auto m = std::make_unique<scene::TriangleMesh>();
    for (int j = 0; j <= nv; ++j)
      for (int i = 0; i <= nu; ++i) {  // seam column duplicated (welded by the estimator)
        // Poles and the seam repeat bit-identical positions (to exercise the welding).
        const double th = kPiD * j / nv, ph = 2 * kPiD * (i % nu) / nu;
        const double sr = (j == 0 || j == nv) ? 0.0 : R * std::sin(th);
        const double z = j == 0 ? R : (j == nv ? -R : R * std::cos(th));
        m->positions.push_back(Vec3(float(sr * std::cos(ph)), float(sr * std::sin(ph)), float(z)));
      }
    for (int j = 0; j < nv; ++j)
      for (int i = 0; i < nu; ++i) {
        const uint32_t a = uint32_t(j * (nu + 1) + i), bb = a + 1, c = a + uint32_t(nu + 1), d = c + 1;
        if (j > 0) m->triangles.push_back({a, c, bb});
        if (j < nv - 1) m->triangles.push_back({bb, c, d});
      }
    return m;
  };
  const double h = kPiD / nv;  // edge angle
  for (NormalMethod method : {NormalMethod::angle_weighted, NormalMethod::jet_fit}) {
    auto m = make();
    m->finalize();
    REQUIRE(m->normals.empty());
    scene::BsdfPtr mirror = scene::make_mirror(scene::constant_texture(Rgb::Ones()));
    CHECK(needs_vertex_normals(*m, mirror.get()));
    NormalEstimation opts;
    opts.method = method;
    const size_t welded = estimate_vertex_normals(*m, opts);
    CHECK(welded == size_t((nv - 1) * nu + 2));
    double worst = 0;
    for (size_t k = 0; k < m->positions.size(); ++k) {
      // Jet fits need neighbourhoods around the point; the k nearest of a pole are a
      // one-sided arc of its ring, so poles are checked for the mesh-based method only.
      if (method == NormalMethod::jet_fit && std::abs(double(m->positions[k].z())) > 0.9 * R) continue;
      const Vec3d radial = m->positions[k].cast<double>().normalized();
      worst = std::max(worst, std::acos(std::min(1.0, radial.dot(m->normals[k].cast<double>()))));
    }
    INFO("method " << int(method) << " worst angle " << worst << " rad, h^2 = " << h * h);
    // Second-order accurate estimators: the error is O(h^2) (float storage adds ~1e-7).
    CHECK(worst < h * h);
    // Interpolated normals now carry curvature: |dn/ds| ~ 1/R on the sphere mesh.
    LocalFrame f;
    const size_t tri = m->triangles.size() / 2 + 3;
    const auto& t = m->triangles[tri];
    const Vec3d centroid = (m->positions[t[0]] + m->positions[t[1]] + m->positions[t[2]]).cast<double>() / 3.0;
    REQUIRE(local_frame(*m, int(tri), centroid, f));
    const double curv = 0.5 * (f.dn1.dot(f.T1) + f.dn2.dot(f.T2));
    INFO("mean normal curvature " << curv << " vs " << 1 / R);
    CHECK(std::abs(curv - 1 / R) < 0.1 / R);
  }
}
