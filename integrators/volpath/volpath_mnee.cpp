// Manifold next-event estimation in volpath: the solutions S(x, y), the two MIS weights
// (volpath_mnee.h has the derivation).
#include <algorithm>
#include <cmath>
#include <optional>

#include "integrators/path/path_tracer.h"  // power_heuristic
#include "gradients/shift_helpers.h"  // d3
#include "integrators/volpath/volpath_mnee_chain.h"
#include "integrators/volpath/volpath_tracer.h"
#include "manifold/constraints.h"
#include "manifold/local_geometry.h"
#include "manifold/walk.h"
#include "pathspace/scatter.h"
#include "scene/bsdf/bsdf.h"
#include "scene/media/medium_interface.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

using gradients::d3;
using scene::SurfaceHit;

namespace {

// Vertices closer than this are the same solution (and a BSDF path MNEE's).
float match_tolerance(const scene::Scene& scene) { return 1e-3f * std::max(1.0f, scene.scene_radius()); }

// Two chains with the same refractions at the same places (within tol).
bool same_chain(const MneeConnection& a, const MneeConnection& b, float tol) {
  if (a.m != b.m || a.reflect_mask != b.reflect_mask) return false;
  for (int i = 0; i < a.m; ++i)
    if ((a.verts[size_t(i)] - b.verts[size_t(i)]).norm() > tol) return false;
  return true;
}

}  // namespace

template <typename F>
void VolpathTracer::for_seeds(const Vec3& xp, const Vec3& y, const Bounds3& b, const F& f) const {
  // Directions through the shape at offsets across its bounds, in the plane of x, y and the
  // bounds' centre (the plane of symmetry of a ball: every solution lies in it).
  const int pairs = (std::min(m_settings.mnee_seeds, kMaxMneeSeeds) - 1) / 2;
  if (pairs <= 0) return;
  const Vec3 to_c = b.center() - xp;
  const float half = 0.5f * (b.hi - b.lo).minCoeff();
  Vec3 normal = to_c.cross(y - xp);
  if (!(normal.squaredNorm() > 1e-12f * to_c.squaredNorm() * (y - xp).squaredNorm()))
    normal = Frame::from_normal(to_c.normalized()).s;
  const Vec3 u = normal.cross(to_c).normalized();
  for (int j = 1; j <= pairs; ++j) {
    const float t = float(j) / (float(pairs) + 0.5f) * half;
    f((to_c + t * u).normalized());
    f((to_c - t * u).normalized());
  }
}

template <typename F>
void VolpathTracer::seed_family(const MneeAnchor& x, const Vec3& y, const Vec3& n_y, int m, int shape,
                                const Bounds3& b, const Vec3& first, const F& f, VolpathCounters& c) const {
  if (m_settings.mnee_scan <= 0) {  // the fixed seeds: `first`, then pairs across b
    f(first);
    for_seeds(x.position(), y, b, f);
    return;
  }
  MneeSeeds seeds;
  if (mnee_scan(x, y, n_y, m, shape, b, seeds, c) == 0) {  // nothing bracketed: one walk from `first`
    ++c.mnee_scan_fallbacks;
    f(first);
  }
  for (int i = 0; i < seeds.count; ++i) f(seeds.d[size_t(i)]);
}

MneeSolutions VolpathTracer::mnee_connect(const MneeAnchor& x, const Vec3& y, const Vec3& n_y, int max_chain,
                                          bool refraction_hint, core::Rng& rng, VolpathCounters& c) const {
  MneeSolutions out;
  max_chain = std::min(max_chain, m_settings.mnee_max_chain);
  const Vec3 xp = x.position();
  Vec3 d = y - xp;
  const float dist = d.norm();
  if (max_chain < 1 || !(dist > 0.0f)) return out;
  d /= dist;
  auto add = [&](const MneeConnection& X) {  // distinct: mnee_solve skips the ones in `out`
    if (X.ok && out.count < kMaxMneeSolutions) out.x[size_t(out.count++)] = X;
  };
  // The straight segment x -> y: its refractive boundaries fix m (the straight family);
  // anything else blocks it.
  int m = 0, first = -1;
  bool straight = refraction_hint;
  if (straight) {
    ++c.mnee_attempts;
    SurfaceHit h;
    Ray r = x.surface ? m_scene.spawn_segment(x.hit, y) : mnee_leave(m_scene, x, d);
    if (!x.surface) r.tmax = std::max(0.0f, dist - 2.0f * scene::Scene::epsilon_at(y));
    for (int k = 0; straight && m_scene.intersect(r, h); ++k) {
      if (!scene::is_index_matched(h)) {
        straight = mnee_refracts(h) && ++m <= max_chain;
        if (first < 0) first = h.shape;
      }
      straight = straight && k < kMaxNullCrossings;
      r = m_scene.spawn_segment(h, y);
    }
    straight = straight && m > 0;  // m = 0: unblocked, plain NEE's path
  }

  // The shape families (mnee_shapes), per specular shape S: one reflection off S, seeded at
  // the point of its bounds' sphere whose normal bisects the directions to x and y; two
  // refractions through S (where the straight family does not already seed S), seeded as
  // the straight family (with mnee_scan 0: across S and through its centre).
  for (const int shape : m_shapes) {
    ++c.mnee_shape_attempts;
    const Bounds3 b = m_scene.shapes()[size_t(shape)]->bounds();
    const Vec3 centre = b.center();
    const scene::Bsdf& bsdf = *m_scene.bsdfs()[size_t(m_scene.shapes()[size_t(shape)]->material)];
    if ((bsdf.lobes() & scene::kDeltaReflection) != 0) {
      const float radius = 0.5f * (b.hi - b.lo).minCoeff();
      const Vec3 bis = (xp - centre).normalized() + (y - centre).normalized();
      const Vec3 seed = (centre + radius * bis.normalized() - xp).normalized();
      if (bis.squaredNorm() > 1e-8f && seed.allFinite()) add(mnee_solve(x, y, n_y, 1, 1u, shape, seed, out, rng, c));
    }
    if ((bsdf.lobes() & scene::kDeltaTransmission) != 0 && max_chain >= 2 && !(straight && first == shape && m == 2)) {
      auto through = [&](const Vec3& seed) { add(mnee_solve(x, y, n_y, 2, 0u, shape, seed, out, rng, c)); };
      seed_family(x, y, n_y, 2, shape, b, (centre - xp).normalized(), through, c);
    }
  }
  if (!straight) return out;

  // The straight family: seeds from the scan across the first refractive shape (with
  // mnee_scan 0: the straight direction, then fixed directions across it).
  ++c.mnee_chains;
  auto straight_family = [&](const Vec3& seed) { add(mnee_solve(x, y, n_y, m, 0u, -1, seed, out, rng, c)); };
  seed_family(x, y, n_y, m, -1, m_scene.shapes()[size_t(first)]->bounds(), d, straight_family, c);
  return out;
}

MneeConnection VolpathTracer::mnee_solve(const MneeAnchor& x, const Vec3& y, const Vec3& n_y, int m, uint32_t mask,
                                         int shape, const Vec3& d, const MneeSolutions& found, core::Rng& rng,
                                         VolpathCounters& c) const {
  MneeConnection out;
  auto reflection = [&](int i) { return ((mask >> i) & 1u) != 0; };
  auto lobe = [&](int i) { return reflection(i) ? scene::kDeltaReflection : scene::kDeltaTransmission; };
  const Vec3 xp = x.position();
  SurfaceHit h;
  // The seed: refracted from x along d at the first m boundaries, ending on the plane
  // through y tangent to the light; then the walk moves its end onto y.
  manifold::Chain seed;
  seed.pin = manifold::Pin::position;
  seed.end_plane = true;
  manifold::ChainVertex v0 = manifold::make_point(d3(xp));
  if (x.surface) {  // offsets re-traced rays off the surface
    v0.f.ng = v0.f.n = d3(x.hit.ng).normalized();
    v0.has_surface = true;
  }
  seed.v.push_back(v0);
  Ray r;
  const bool traced = follow_dirac_chain(m_scene, x, d, m, mask, shape, r,
                                         [&](const SurfaceHit& hit, const Vec3& w, const scene::BsdfSample& bs) {
    const bool reflect = reflection(int(seed.v.size()) - 1);  // v_0 is x
    const float eta = reflect ? 1.0f : hit.ng.dot(-w) > 0.0f ? bs.eta : 1.0f / bs.eta;
    const auto type = reflect ? manifold::Interaction::reflection : manifold::Interaction::refraction;
    const auto v = manifold::make_vertex(m_scene, hit, type, double(eta));
    if (!v || (!reflect && eta == 1.0f)) return false;
    seed.v.push_back(*v);
    return true;
  });
  if (!traced) {
    ++c.mnee_seed_failed;
    return out;
  }
  seed.v.push_back(manifold::make_plane_end(d3(y), d3(n_y).normalized()));
  manifold::Chain exact;
  const manifold::WalkStatus seeded = manifold::retrace(m_scene, seed, seed.v[1].p(), exact);
  c.mnee_seeds.record(seeded, 0);
  if (seeded != manifold::WalkStatus::ok) {
    ++c.mnee_seed_failed;
    return out;
  }
  manifold::WalkSettings ws;
  ws.max_iterations = m_settings.mnee_iterations;
  ws.exact_input = true;
  const manifold::WalkResult walked = manifold::walk(m_scene, exact, d3(y), ws, &c.mnee_walks);
  double G = 0.0;
  if (!walked.ok() || manifold::generalized_geometry(walked.chain, G) != manifold::WalkStatus::ok) {
    ++c.mnee_walk_failed;
    return out;
  }
  const manifold::Chain& X = walked.chain;
  // D = d w_0 / dA(y): G without the cosine at a surface anchor.
  double D = G;
  if (x.surface) D /= std::abs((X.v[1].p() - X.v[0].p()).normalized().dot(X.v[0].f.ng));
  if (m_settings.fault == VolpathFault::mnee_planar_geometry)
    D = 1.0 / (X.v[size_t(m + 1)].p() - X.v[size_t(m)].p()).squaredNorm();
  if (!(D > 0.0) || !std::isfinite(D)) {
    ++c.mnee_walk_failed;
    return out;
  }

  // The solved chain re-traced in float: f, the lobes' densities, Tr, the light.
  const float tol = 1e-4f * std::max(1.0f, m_scene.scene_radius());
  for (int i = 0; i < m; ++i) out.verts[size_t(i)] = X.v[size_t(i + 1)].p().cast<float>();
  out.m = m;
  out.reflect_mask = mask;
  // A solution another seed already reached is not evaluated again.
  for (int i = 0; i < found.count; ++i)
    if (same_chain(found.x[size_t(i)], out, match_tolerance(m_scene))) return MneeConnection{};
  const Vec3 w0 = (out.verts[0] - xp).normalized();
  Rgb f;
  double p = 0.0;
  int medium = x.medium;
  if (x.surface) {
    const Vec3 wo = x.hit.shading.to_local(w0);
    if (!pathspace::consistent_side(x.hit, w0, wo.z())) return out;
    float pdf = 0.0f;
    f = x.hit.bsdf->eval_pdf(pathspace::radiance_context(x.hit), x.wi_local, wo, pdf) * abs_cos_theta(wo);
    p = double(pdf);
    medium = scene::medium_toward(x.hit, w0, x.medium, m_camera_medium);
  } else {
    const scene::HenyeyGreenstein phase(m_scene.media()[size_t(x.medium)].phase);
    f = Rgb::Constant(phase.eval(x.d_in, w0));
    p = double(phase.pdf(x.d_in, w0));
  }
  if (is_black(f) || !(p > 0.0)) return out;
  r = mnee_leave(m_scene, x, w0);
  Rgb tr_all = Rgb::Ones(), tr;
  // Light tracing's factors (x.lt): the Dirac lobes' selection probabilities and
  // free flight's along the chain (passing every segment, scattering at a medium x).
  double lobes = 1.0, flights = 1.0;
  double* flight = x.lt ? &flights : nullptr;
  for (int i = 0; i <= m; ++i) {
    const Vec3 target = i < m ? out.verts[size_t(i)] : y;
    const MarchEnd end = march(r, medium, nullptr, rng, c, tr, h, flight, i == 0 && !x.surface);
    const bool there = end == MarchEnd::surface && (h.p - target).norm() <= tol;
    if (!there || (i < m ? h.shape != X.v[size_t(i + 1)].shape : !h.emitter)) {
      ++c.mnee_occluded;
      return out;
    }
    tr_all *= tr;
    if (i == m) break;
    const Vec3 next = i + 1 < m ? out.verts[size_t(i + 1)] : y;
    const Vec3 wo = (next - h.p).normalized();
    const auto bs = mnee_dirac(h, r.d, lobe(i));
    if (!bs || (bs->wo - h.shading.to_local(wo)).norm() > 1e-3f) {
      ++c.mnee_occluded;
      return out;
    }
    f *= bs->weight * bs->pdf;  // f_i |cos_i|
    p *= double(bs->pdf);
    lobes *= double(bs->pdf);
    medium = scene::medium_toward(h, wo, medium, m_camera_medium);
    r = m_scene.continue_ray(h, wo);
  }
  const Rgb Le = h.emitter->eval(h, -r.d);
  // NEE's area density of y from x (of the straight line only for cone-sampled spheres):
  // y may lie behind the light as seen straight from x (set_probe).
  const double p_light =
      double(m_scene.emitter_pmf(h.emitter)) * double(h.emitter->pdf_area_direct(xp, y, n_y.normalized()));
  if (is_black(Le) || is_black(tr_all) || !(p_light > 0.0) || !std::isfinite(p_light)) return out;
  out.value = f * tr_all * Le * float(D / p_light);
  out.p_light = p_light;
  out.p_bsdf = p * D;
  out.D = D;
  if (flight) out.p_trace = light_trace_density(x, *h.emitter, y, n_y, out.verts[size_t(m - 1)], lobes * flights, G);
  out.s1 = X.v[1].p();
  out.ok = is_finite(out.value) && std::isfinite(out.p_bsdf);
  return out;
}

Rgb VolpathTracer::mnee_nee(const MneeAnchor& x, const NeeProbe& probe, const CameraVertex& prev, core::Rng& rng,
                            VolpathCounters& c) const {
  const MneeSolutions S = mnee_connect(x, probe.y, probe.n, m_max_depth - x.depth - 1, probe.try_chain, rng, c);
  const bool no_mis = m_settings.fault == VolpathFault::mnee_without_mis;
  // Light tracing's weight needs the camera's density of x (only where a solution exists).
  const double cam_pdf = x.lt && S.count > 0 ? camera_pdf(prev, x, rng, c) : 0.0;
  Rgb sum = Rgb::Zero();
  for (int i = 0; i < S.count; ++i) {
    const MneeConnection& X = S.x[size_t(i)];
    sum += X.value * float(no_mis ? 1.0 : mnee_mis(X.p_light, X.p_bsdf, trace_over(X, cam_pdf)));
  }
  c.mnee_connections += S.count;
  return sum;
}

bool VolpathTracer::mnee_find(const MneeAnchor& x, const Vec3& y, const Vec3& n_y, const MneeConnection& path,
                              core::Rng& rng, VolpathCounters& c, MneeConnection& match) const {
  VolpathCounters scratch;  // MNEE's own counters count its NEE side only
  const MneeSolutions S = mnee_connect(x, y, n_y, m_max_depth - x.depth - 1, true, rng, scratch);
  c.null_limit += scratch.null_limit;
  const float tol = match_tolerance(m_scene);
  for (int i = 0; i < S.count; ++i)
    if (same_chain(S.x[size_t(i)], path, tol)) {
      match = S.x[size_t(i)];
      return true;
    }
  return false;
}

float VolpathTracer::mnee_bsdf_weight(const ChainTrack& chain, const SurfaceHit& hit, core::Rng& rng,
                                      VolpathCounters& c) const {
  ++c.mnee_bsdf_hits;
  MneeConnection path, X;
  path.m = chain.m;
  path.reflect_mask = chain.reflect_mask;
  path.verts = chain.verts;
  if (!mnee_find(chain.anchor, hit.p, hit.ng, path, rng, c, X)) return 1.0f;
  ++c.mnee_bsdf_matched;
  if (m_settings.fault == VolpathFault::mnee_without_mis) return 1.0f;
  const double cam_pdf = chain.anchor.lt ? camera_pdf(chain.prev, chain.anchor, rng, c) : 0.0;
  return float(mnee_mis(X.p_bsdf, X.p_light, trace_over(X, cam_pdf)));
}

}  // namespace dp::integrators
