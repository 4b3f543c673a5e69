// Finite-difference tools for the bidirectional shifts' tests (test_gbdpt_shift.cpp,
// test_merge_shift.cpp): Richardson-extrapolated central differences and double-precision
// re-traces of specular chains built from bidirectional vertices, independent of
// gradients/bidir_chain.cpp.
#pragma once

#include <optional>
#include <vector>

#include "gradients/bidir_chain.h"
#include "manifold/local_geometry.h"
#include "manifold/walk.h"
#include "pathspace/bidir_vertex.h"
#include "scene/emitters/emitter.h"
#include "scene/shapes/shape.h"
#include "tests/support/jj_bound.h"

namespace dp::test {

// Central difference of f (a 3D point or direction map of 2 parameters) with Richardson
// extrapolation (h, h/2): error O(h^4) instead of O(h^2).
template <class F>
inline Vec3d derivative(F&& f, int axis, double h) {
  auto central = [&](double s) {
    const double a = axis == 0 ? s : 0.0, b = axis == 1 ? s : 0.0;
    return Vec3d((f(a, b) - f(-a, -b)) / (2.0 * s));
  };
  return Vec3d((4.0 * central(h / 2) - central(h)) / 3.0);
}

// Light vertices light[lo .. hi] in camera order (light[hi] first).
inline std::vector<const pathspace::BidirVertex*> camera_order(const std::vector<pathspace::BidirVertex>& light, int lo,
                                                               int hi) {
  std::vector<const pathspace::BidirVertex*> out;
  for (int j = hi; j >= lo; --j) out.push_back(&light[size_t(j)]);
  return out;
}

// The chain v[0] (pinned) .. v[n] in double for finite differences, independent of
// gradients/bidir_chain.cpp: interaction types from the neighbours' sides, glass eta 1.5
// (chain.h: index behind the geometric normal over the one in front; spheres face out).
inline std::optional<manifold::Chain> fd_chain(const scene::Scene& s,
                                              const std::vector<const pathspace::BidirVertex*>& v) {
  manifold::Chain ch;
  for (size_t k = 0; k < v.size(); ++k) {
    const pathspace::BidirVertex& x = *v[k];
    if (x.kind == pathspace::BidirKind::light) {  // an area light's endpoint, pinned
      scene::SurfacePoint sp = x.sp;
      sp.dpdu = sp.shading.s;
      manifold::ChainVertex cv = manifold::make_vertex(sp, manifold::Interaction::reflection);
      const auto* shape = static_cast<const scene::AreaEmitter*>(x.emitter)->shape();
      for (size_t i = 0; i < s.shapes().size(); ++i)
        if (s.shapes()[i].get() == shape) cv.shape = int32_t(i);
      ch.v.push_back(cv);
      continue;
    }
    bool refraction = false;
    if (k > 0 && k + 1 < v.size())
      refraction = x.sp.ng.dot(v[k - 1]->sp.p - x.sp.p) * x.sp.ng.dot(v[k + 1]->sp.p - x.sp.p) < 0.0f;
    const auto cv = manifold::make_vertex(s, pathspace::surface_hit(x), refraction ? manifold::Interaction::refraction
                                                                   : manifold::Interaction::reflection,
                                          refraction ? 1.5 : 1.0);
    if (!cv) return std::nullopt;
    ch.v.push_back(*cv);
  }
  return ch;
}

// Area at the chain's end per unit solid angle at its pinned start, |dA_n / d w_0|, by
// central differences (Richardson) of the double re-trace over a gnomonic chart around
// the direction toward v[1]. 0 if a perturbed re-trace fails.
inline double area_per_solid_angle(const scene::Scene& s, const manifold::Chain& ch) {
  const Vec3d o = ch.v[0].p(), w = (ch.v[1].p() - o).normalized();
  const Frame f = Frame::from_normal(w.cast<float>());
  const Vec3d e0 = f.s.cast<double>(), e1 = f.t.cast<double>();
  bool ok = true;
  auto map = [&](double a, double b) -> Vec3d {
    manifold::Chain out;
    if (manifold::retrace(s, ch, o + (w + a * e0 + b * e1).normalized(), out) != manifold::WalkStatus::ok) {
      ok = false;
      return Vec3d::Zero();
    }
    return out.v.back().p();
  };
  const double h = 1e-4;
  const Vec3d du = derivative(map, 0, h), dv = derivative(map, 1, h);
  return ok ? du.cross(dv).norm() : 0.0;
}

// tests/support/jj_bound.h over vertices x[k0 .. k1] of a path (any order) and their
// positions `back` after a round trip; neighbours outside [k0, k1] enter as segment ends;
// the chain's Dirac vertices multiply the bound by their curvature gain.
inline double bidir_jj_tolerance(const std::vector<const pathspace::BidirVertex*>& x,
                                 const std::vector<const pathspace::BidirVertex*>& back, int k0, int k1) {
  auto d3 = [](const Vec3& v) { return Vec3d(v.cast<double>()); };
  auto normal = [&](int j) { return x[size_t(j)]->on_surface() ? d3(x[size_t(j)]->sp.ng) : Vec3d(Vec3d::Zero()); };
  double sum = 0, gain = 1;
  for (int k = k0; k <= k1; ++k) {
    const pathspace::BidirVertex& v = *x[size_t(k)];
    std::vector<std::pair<Vec3d, Vec3d>> ends;
    if (k > 0) ends.emplace_back(d3(x[size_t(k - 1)]->sp.p), normal(k - 1));
    if (k + 1 < int(x.size())) ends.emplace_back(d3(x[size_t(k + 1)]->sp.p), normal(k + 1));
    sum += jj_vertex_term(d3(back[size_t(k)]->sp.p - v.sp.p).norm(), d3(v.sp.p), normal(k), ends, 1.0);
    if (gradients::chain_interior(v) && k + 1 < int(x.size())) {
      double kappa = 0;
      if (v.sp.dpdu.norm() > 0) kappa = std::max(kappa, double(v.sp.dndu.norm() / v.sp.dpdu.norm()));
      if (v.sp.dpdv.norm() > 0) kappa = std::max(kappa, double(v.sp.dndv.norm() / v.sp.dpdv.norm()));
      gain *= 1 + 2 * kappa * d3(x[size_t(k + 1)]->sp.p - v.sp.p).norm();
    }
  }
  return sum * gain + 1e-12;
}

}  // namespace dp::test
