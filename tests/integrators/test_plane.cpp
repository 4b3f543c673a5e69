// The primal photon planes `plane` (integrators/plane/): the plane intersection and its
// 1/|det| against a Monte Carlo of the plane's measure, the BVH's pieces against brute force,
// the planes' light against the beams they replace (shadow rays included). Every test also
// runs planted defects (PlaneFault) and requires their rejection. The integrator's renders,
// light pass and counters: test_plane_render.cpp.
#include <boost/math/distributions/normal.hpp>
#include <boost/math/distributions/students_t.hpp>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstdio>
#include <vector>

#include "integrators/plane/plane_bvh.h"
#include "integrators/plane/plane_gather.h"
#include "scene/media/medium_interface.h"
#include "tests/integrators/plane_test_support.h"
#include "tests/support/test_scenes.h"
#include "tests/support/welch.h"

using namespace dp;
using integrators::MediumPlane;
using integrators::PlaneFault;
using test::random_direction;
using test::render_plane;

// Change of variables c = a0 + t0 w0 + t1 w1 - w d (|dc| = |det[w0, w1, d]| dt0 dt1 dw):
//   int_V dc plane_estimate(hit(c)) = int dt0 dt1 dw |det| plane_estimate(t0, t1, w) 1(c in V)
// and |det| plane_estimate = the integrand without the Jacobian (beta = 1, P_s = q = 1).
// Estimator A draws c uniformly in a box V (intersection solved, 1/|det| applied), B draws
// (t0, t1, w) uniformly on the plane x segment ranges; z-test at 1e-3 (Sidak over the
// configurations), each with 2e5 samples a side.
TEST_CASE(
    "plane: the intersection and its 1/|det| equal a Monte Carlo of the "
    "plane's measure",
    "[unit]") {
  scene::HomogeneousMedium med;
  med.sigma_a = Rgb::Constant(0.1f);
  med.sigma_s = Rgb(0.3f, 0.6f, 0.9f);
  med.phase.type = scene::PhaseFunctionDesc::Type::hg;
  med.phase.g = 0.4f;
  constexpr int kConfigs = 6, kN = 200000;
  const double z_crit =
      boost::math::quantile(boost::math::normal(), 1.0 - (1.0 - std::pow(0.999, 1.0 / kConfigs)) / 2.0);
  core::Rng rng(31, 0);
  for (PlaneFault fault : {PlaneFault::none, PlaneFault::no_det}) {
    double worst = 0;
    for (int k = 0; k < kConfigs; ++k) {
      MediumPlane pl;
      Vec3 d;
      double det = 0;
      do {  // |det| in [0.2, 0.7]: the Jacobian differs from 1 (the planted
            // defect shows)
        pl.w0 = random_direction(rng);
        pl.w1 = random_direction(rng);
        d = random_direction(rng);
        det = std::abs(double(pl.w0.dot(pl.w1.cross(d))));
      } while (det < 0.2 || det > 0.7);
      pl.a0 = Vec3(rng.uniform(), rng.uniform(), rng.uniform());
      pl.t0_end = 1.5f;
      pl.t1_end = 1.2f;
      pl.beta = Rgb::Ones();
      const double W = 2.0;
      // V: the box of every c = x - w d with x on the plane, w in [0, W].
      Bounds3 box;
      for (float u : {0.0f, pl.t0_end})
        for (float v : {0.0f, pl.t1_end})
          for (float w : {0.0f, float(W)}) box.expand(Vec3(pl.a0 + u * pl.w0 + v * pl.w1 - w * d));
      const Vec3 ext = box.hi - box.lo;
      const double vol = double(ext.x()) * double(ext.y()) * double(ext.z());
      const double dom = double(pl.t0_end) * double(pl.t1_end) * W;
      double sa = 0, sa2 = 0, sb = 0, sb2 = 0;
      for (int i = 0; i < kN; ++i) {
        const Vec3 c = box.lo + Vec3(rng.uniform() * ext.x(), rng.uniform() * ext.y(), rng.uniform() * ext.z());
        integrators::PlaneHit h;
        double a = 0;
        if (integrators::plane_intersect(pl.a0, pl.w0, pl.w1, c, d, h) && h.t0 >= 0 && h.t0 <= double(pl.t0_end) &&
            h.t1 >= 0 && h.t1 <= double(pl.t1_end) && h.w >= 0 && h.w <= W)
          a = vol * double(integrators::plane_estimate(med, pl, h, d, fault).sum());
        sa += a;
        sa2 += a * a;
        integrators::PlaneHit g;
        g.t0 = double(pl.t0_end) * double(rng.uniform());
        g.t1 = double(pl.t1_end) * double(rng.uniform());
        g.w = W * double(rng.uniform());
        g.inv_det = 1.0;
        const Vec3 x =
            (pl.a0.cast<double>() + g.t0 * pl.w0.cast<double>() + g.t1 * pl.w1.cast<double>() - g.w * d.cast<double>())
                .cast<float>();
        double b = 0;
        if ((x.array() >= box.lo.array()).all() && (x.array() <= box.hi.array()).all())
          b = dom * double(integrators::plane_estimate(med, pl, g, d, PlaneFault::none).sum());
        sb += b;
        sb2 += b * b;
      }
      const double ma = sa / kN, mb = sb / kN;
      const double va = (sa2 / kN - ma * ma) / kN, vb = (sb2 / kN - mb * mb) / kN;
      const double z = (ma - mb) / std::sqrt(va + vb);
      std::printf(
          "[plane jacobian] fault %d config %d |det| %.3f: %.5f vs "
          "%.5f (se %.5f) z %.2f\n",
          int(fault), k, det, ma, mb, std::sqrt(va + vb), z);
      worst = std::max(worst, std::abs(z));
    }
    std::printf("[plane jacobian] fault %d worst |z| %.2f (crit %.2f)\n", int(fault), worst, z_crit);
    if (fault == PlaneFault::none)
      CHECK(worst < z_crit);
    else
      CHECK(worst > z_crit);
  }
}

// Random planes cut into pieces; every segment meets a plane at most once, so over the pieces
// the BVH reports, the intersections accepted by the pieces' half-open ranges must be exactly
// the brute-force set over the whole planes (once each).
TEST_CASE("plane: the BVH's pieces hold each segment-plane intersection exactly once", "[unit]") {
  core::Rng rng(12, 0);
  std::vector<MediumPlane> planes(2000);
  for (size_t i = 0; i < planes.size(); ++i) {
    MediumPlane& p = planes[i];
    p.a0 = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.0f;
    p.w0 = i % 5 == 0 ? Vec3(Vec3::Unit(int(i / 5 % 3))) : random_direction(rng);
    p.w1 = random_direction(rng);
    p.t0_begin = i % 3 == 0 ? 0.1f : 0.0f;
    p.t0_end = 0.2f + 0.8f * rng.uniform();
    p.t1_end = 0.1f + 0.9f * rng.uniform();
    p.index = uint32_t(i);
  }
  integrators::PlaneBvh bvh;
  bvh.build(planes, 0.1f);
  REQUIRE(bvh.pieces() > 4 * planes.size());
  auto in = [](double v, double lo, double hi, double end) { return v >= lo && (v < hi || (!(hi < end) && v <= hi)); };
  int64_t found = 0, mismatches = 0;
  for (int q = 0; q < 300; ++q) {
    const Vec3 o = Vec3(rng.uniform(), rng.uniform(), rng.uniform()) * 2.4f - Vec3::Constant(0.2f);
    Vec3 d = random_direction(rng);
    if (q % 3 == 0) d = Vec3::Unit(q % 9 / 3);
    const float wmax = q % 5 == 0 ? kInfinity : 2.0f * rng.uniform();
    std::vector<int> brute(planes.size(), 0), got(planes.size(), 0);
    for (const auto& p : planes) {
      integrators::PlaneHit h;
      if (integrators::plane_intersect(p.a0, p.w0, p.w1, o, d, h) && h.t0 >= double(p.t0_begin) &&
          h.t0 <= double(p.t0_end) && h.t1 >= 0 && h.t1 <= double(p.t1_end) && h.w >= 0 && h.w <= double(wmax))
        brute[p.index] = 1;
    }
    bvh.query_segment(o, d, wmax, [&](const MediumPlane& p, const integrators::PlaneBvh::Piece& pc) {
      integrators::PlaneHit h;
      if (integrators::plane_intersect(p.a0, p.w0, p.w1, o, d, h) && in(h.t0, pc.u0, pc.u1, p.t0_end) &&
          in(h.t1, pc.v0, pc.v1, p.t1_end) && h.w >= 0 && h.w <= double(wmax))
        ++got[p.index];
    });
    for (size_t i = 0; i < planes.size(); ++i) {
      mismatches += brute[i] != got[i] ? 1 : 0;
      found += brute[i];
    }
  }
  std::printf("[plane bvh] %lld intersections over 300 segments, %lld mismatches\n", (long long)found,
              (long long)mismatches);
  CHECK(found > 1000);
  CHECK(mismatches == 0);
}

// The planes' light (P, plane_gather.h) against the beams they replace (the short beams that
// start at a scattering event, Beam-Beam 3D at r = 1% of the diagonal) on the same light
// passes, along fixed camera segments inside the occluded furnace: a paired t-test over 48
// independent light passes at 1%. The beams are traced (they stop at the core); the planes
// must test a1(t0) -> b. The segments keep r from both spheres, so the beams' 3D blur loses
// nothing at a boundary; what is left is the blur's O(r^2) smoothing.
TEST_CASE(
    "plane: planes carry the light of the beams they replace, shadow "
    "rays included",
    "[stat]") {
  constexpr int kPasses = 48;
  const auto s = test::occluded_furnace(16);
  // Camera segments inside the ball kept >= r away from both spheres (from the entry into the
  // ball shrunk by r to the core grown by r, or to the shrunk ball's exit): every kernel ball
  // lies wholly in the medium, so the beams lose no kernel mass at a boundary.
  const float r = 0.01f * s->bounds().diagonal();
  std::vector<Ray> rays;
  std::vector<float> lens;
  std::vector<int> media;
  core::Rng crng(5, 5);
  auto roots = [](const Ray& ray, double radius, double& t0, double& t1) {
    const double b = double(ray.o.dot(ray.d)), c = double(ray.o.squaredNorm()) - radius * radius;
    const double disc = b * b - c;
    if (disc <= 0) return false;
    t0 = -b - std::sqrt(disc);
    t1 = -b + std::sqrt(disc);
    return true;
  };
  for (int i = 0; i < 4000 && rays.size() < 200; ++i) {
    const Ray ray = s->camera().generate_ray(Vec2(16 * crng.uniform(), 16 * crng.uniform()));
    double a0 = 0, a1 = 0, c0 = 0, c1 = 0;
    if (!roots(ray, 1.0 - double(r), a0, a1)) continue;
    const double end = roots(ray, 0.75 + double(r), c0, c1) ? c0 : a1;
    if (!(end > a0 + 0.05)) continue;
    Ray seg = ray;
    seg.o = ray.at(float(a0));
    rays.push_back(seg);
    lens.push_back(float(end - a0));
    media.push_back(0);  // the ball's medium, the scene's first
  }
  REQUIRE(rays.size() == 200);
  const double t_crit =
      boost::math::quantile(boost::math::complement(boost::math::students_t(double(kPasses - 1)), 0.005));
  for (PlaneFault fault : {PlaneFault::none, PlaneFault::no_occlusion}) {
    integrators::PlaneSettings ps;
    ps.fault = fault;
    const integrators::BeamSettings bs;
    std::vector<double> diff, by_beams;
    int64_t occluded = 0;
    for (int it = 0; it < kPasses; ++it) {
      integrators::PhotonTraceParams tp;
      tp.paths = 8000;
      tp.max_depth = 1000;
      tp.seed = 77;
      tp.iteration = it;
      tp.threads = 2;
      tp.store_photons = false;
      std::vector<integrators::MediumPhoton> none;
      std::vector<integrators::MediumBeam> beams, replaced;
      std::vector<MediumPlane> planes;
      integrators::PhotonTraceCounters pc;
      integrators::BeamTraceCounters bc;
      integrators::PlaneTraceCounters plc;
      REQUIRE(integrators::trace_medium_photons(*s, tp, nullptr, none, pc, nullptr, &beams, &bc, nullptr, &planes, &plc));
      for (const auto& b : beams)
        if (b.after_scatter) replaced.push_back(b);
      integrators::BeamBvh beam_bvh, no_beams;
      beam_bvh.build(replaced, 0.1f);
      integrators::PlaneBvh plane_bvh, no_planes;
      plane_bvh.build(planes, 0.05f);
      const integrators::PlaneGather by_b(*s, ps, bs, beam_bvh, no_planes, r, tp.paths);
      const integrators::PlaneGather by_p(*s, ps, bs, no_beams, plane_bvh, r, tp.paths);
      core::Rng rng(3, uint64_t(it));
      integrators::GatherCounters gc;
      double sb = 0, sp = 0;
      for (size_t k = 0; k < rays.size(); ++k) {
        sb += double(by_b.gather(rays[k], lens[k], media[k], 999, rng, gc).sum());
        sp += double(by_p.gather(rays[k], lens[k], media[k], 999, rng, gc).sum());
      }
      occluded += gc.occluded;
      by_beams.push_back(sb / double(rays.size()));
      diff.push_back((sp - sb) / double(rays.size()));
    }
    const test::Moments m = test::moments(diff), mb = test::moments(by_beams);
    const double t = m.mean / std::sqrt(m.var / double(m.n));
    std::printf(
        "[plane vs replaced beams, fault %d] beams %.5f (se %.5f), "
        "planes - beams %.5f (se %.5f): |t|/crit %.2f; %lld occluded\n",
        int(fault), mb.mean, std::sqrt(mb.var / double(mb.n)), m.mean, std::sqrt(m.var / double(m.n)),
        std::abs(t) / t_crit, (long long)occluded);
    if (fault == PlaneFault::none) {
      CHECK(std::abs(t) < t_crit);
      CHECK(occluded > 0);
    } else {
      CHECK(std::abs(t) > t_crit);
    }
  }
}
