#include "gradients/volume_photon_chain.h"

#include <cmath>

#include "gradients/shift_helpers.h"
#include "manifold/constraints.h"
#include "manifold/local_geometry.h"
#include "pathspace/scatter.h"
#include "scene/bsdf/bsdf.h"
#include "scene/media/free_flight.h"
#include "scene/media/medium_interface.h"
#include "scene/scene.h"
#include "scene/shapes/shape.h"

namespace dp::gradients {

using manifold::Chain;
using manifold::ChainVertex;
using manifold::WalkStatus;

WalkStatus chain_volume_density(const Chain& chain, double& D, ChainFault fault) {
  const int n = chain.n();
  if (fault == ChainFault::direct_distance) {
    D = 1.0 / (chain.v[size_t(n)].p() - chain.v[size_t(n - 1)].p()).squaredNorm();
    return WalkStatus::ok;
  }
  double G = 0.0;
  const WalkStatus st = manifold::generalized_geometry(chain, G);
  if (st != WalkStatus::ok) return st;
  // G carries |cos| at a surface anchor (manifold/constraints.h): D is per solid angle.
  double c0 = 1.0;
  if (chain.v[0].has_surface) c0 = std::abs((chain.v[1].p() - chain.v[0].p()).normalized().dot(chain.v[0].f.ng));
  if (!(c0 > 0.0) || !(G > 0.0)) return WalkStatus::grazing;
  D = G / c0;
  return std::isfinite(D) ? WalkStatus::ok : WalkStatus::singular;
}

bool build_photon_chain(const scene::Scene& scene, const PhotonChain& c, const Vec3d& end, const Vec3d& normal,
                        Chain& out) {
  out = Chain{};
  out.pin = manifold::Pin::position;
  out.end_plane = true;
  ChainVertex a = manifold::make_point(d3(c.anchor.a));
  if (c.anchor.kind == ParentKind::surface) {  // its normal offsets re-traced rays (no self-hit)
    a.f.ng = a.f.n = d3(c.anchor.ng).normalized();
    a.has_surface = true;
  }
  out.v.push_back(a);
  for (const PhotonChainStep& s : c.steps) {
    if (s.shape < 0 || size_t(s.shape) >= scene.shapes().size()) return false;
    ChainVertex v;
    if (!manifold::local_frame(*scene.shapes()[size_t(s.shape)], s.prim, d3(s.p), v.f)) return false;
    v.type = s.refraction ? manifold::Interaction::refraction : manifold::Interaction::reflection;
    v.eta = s.refraction ? double(s.eta) : 1.0;
    v.shape = s.shape;
    v.prim = s.prim;
    out.v.push_back(v);
  }
  out.v.push_back(manifold::make_plane_end(end, normal));
  return true;
}

namespace {

// f(a -> x) and p(x | a) of the chain record's anchor through Dirac vertices at (about)
// `verts` to the medium point x, re-traced in float (the header's formulas without D).
// False: zero (f or p); `occluded` when the re-trace does not follow the vertices or x is
// not reached in photon_medium.
bool eval_chain(const scene::Scene& scene, const PhotonChain& c, const std::vector<Vec3>& verts, const Vec3& x,
                int photon_medium, Rgb& f, double& p, bool& occluded) {
  const PhotonParent& a = c.anchor;
  const float tol = 1e-4f * std::max(1.0f, scene.scene_radius());
  const int cam_medium = scene.camera_medium();
  Vec3 w = (verts[0] - a.a).normalized();
  // A surface anchor's medium is that of the side the base chain left into.
  if (a.kind == ParentKind::surface && (a.ng.dot(w) > 0.0f) != (a.ng.dot(c.steps[0].p - a.a) > 0.0f)) {
    occluded = true;
    return false;
  }
  Rgb rho;
  float p_dir = 0.0f;
  if (!anchor_direction(scene, a, w, rho, p_dir)) return false;
  f = rho;
  p = double(p_dir);
  int medium = a.medium;
  Ray ray;
  ray.o = a.a;
  ray.d = w;
  ray.tmin = scene::Scene::epsilon_at(a.a);
  ray.tmax = kInfinity;
  scene::SurfaceHit hit;
  for (size_t i = 0; i < verts.size(); ++i) {
    // To s_i through index-matched boundaries (each sub-segment passed).
    for (int crossings = 0;; ++crossings) {
      if (!scene.intersect(ray, hit) || crossings > 16) {
        occluded = true;
        return false;
      }
      if (medium >= 0) {
        const scene::HomogeneousMedium& m = scene.media()[size_t(medium)];
        f *= scene::transmittance(m, hit.t);
        p *= double(scene::free_flight_pass_probability(m, hit.t));
      }
      if (!scene::is_index_matched(hit)) break;
      medium = scene::medium_toward(hit, w, medium, cam_medium);
      ray = scene.continue_ray(hit, w);
    }
    if (hit.shape != c.steps[i].shape || !((hit.p - verts[i]).norm() <= tol) || !hit.bsdf) {
      occluded = true;
      return false;
    }
    // The base's Dirac lobe replayed from the light side (importance).
    const Vec3 next = i + 1 < verts.size() ? verts[i + 1] : x;
    const Vec3 wo = (next - hit.p).normalized();
    const Vec3 wi_l = hit.shading.to_local(-w), wo_l = hit.shading.to_local(wo);
    if (!pathspace::consistent_side(hit, -w, wi_l.z()) || !pathspace::consistent_side(hit, wo, wo_l.z())) return false;
    const auto bs = pathspace::sample_dirac_lobe(*hit.bsdf, scene::BsdfContext{hit.uv, scene::TransportMode::importance},
                                                 wi_l, c.steps[i].lobe, c.steps[i].u_lobe);
    if (!bs || !(bs->pdf > 0.0f) || is_black(bs->weight) || (bs->wo - wo_l).norm() > 1e-3f) return false;
    f *= bs->weight * bs->pdf;
    p *= double(bs->pdf);
    medium = scene::medium_toward(hit, wo, medium, cam_medium);
    w = wo;
    ray = scene.continue_ray(hit, w);
  }
  // The last segment: a free flight ending at x in photon_medium.
  const SegmentMedia seg = walk_segment(scene, hit.p, w, (x - hit.p).norm(), medium);
  if (seg.blocked || seg.medium != photon_medium || seg.medium < 0) {
    occluded = true;
    return false;
  }
  const scene::HomogeneousMedium& m = scene.media()[size_t(seg.medium)];
  f *= seg.tr * scene::transmittance(m, seg.last) * m.sigma_s;
  p *= seg.p_pass * double(scene::free_flight_pdf(m, seg.last));
  return p > 0.0 && !is_black(f) && is_finite(f) && std::isfinite(p);
}

}  // namespace

ChainBase chain_base(const scene::Scene& scene, const PhotonChain& chain, int photon_medium, const Vec3& b,
                     ChainFault fault, manifold::WalkStats* stats) {
  ChainBase base;
  if (chain.steps.empty()) return base;
  const Vec3d bd = d3(b);
  base.last = (bd - d3(chain.steps.back().p)).normalized();
  // Re-traced exactly from the anchor (the light walk's side): D(a -> b).
  manifold::Chain built;
  if (!build_photon_chain(scene, chain, bd, base.last, built)) return base;
  base.status = manifold::retrace(scene, built, built.v[1].p(), base.exact);
  if (stats) ++stats->traces;
  if (base.status == WalkStatus::ok) base.status = chain_volume_density(base.exact, base.D, fault);
  if (base.status != WalkStatus::ok) return base;
  std::vector<Vec3> vb(chain.steps.size());
  for (size_t i = 0; i < vb.size(); ++i) vb[i] = chain.steps[i].p;
  bool occluded = false;
  if (!eval_chain(scene, chain, vb, b, photon_medium, base.f, base.p, occluded)) base.status = WalkStatus::invalid_input;
  return base;
}

ChainReconnection reconnect_photon_chain(const scene::Scene& scene, const PhotonChain& chain, const ChainBase& base,
                                         int photon_medium, const Vec3& b_offset, const ChainReconnectSettings& settings,
                                         manifold::WalkStats* stats) {
  ChainReconnection r;
  if (base.status != WalkStatus::ok) {  // numerically lost (a base that cannot be re-traced)
    r.walk = base.status;
    if (stats) stats->record(base.status, 0);
    return r;
  }
  const size_t m = chain.steps.size();
  const Vec3d bo = d3(b_offset);
  // The walk: the end moves in the plane through b' (normal: the base's last segment). The
  // base's end slides along its last ray onto that plane, so the start chain stays exact
  // (no re-trace before the first Newton step).
  Chain start = base.exact;
  const Vec3d b_end = start.v.back().p();
  start.v.back() = manifold::make_plane_end(bo, base.last);
  start.v.back().f.p = b_end + base.last * (bo - b_end).dot(base.last);
  manifold::WalkSettings ws;
  ws.max_iterations = settings.max_iterations;
  ws.accept_distance = settings.accept_distance;
  ws.exact_input = true;
  const manifold::WalkResult w = manifold::walk(scene, start, bo, ws, stats);
  r.walk = w.status;
  if (!w.ok()) return r;
  // D at the walked end, on the plane normal to the offset's own last segment.
  Chain off = w.chain;
  const Vec3d end = off.v.back().p();
  off.v.back() = manifold::make_plane_end(end, (end - off.v[m].p()).normalized());
  double D_off = 0.0;
  const WalkStatus st = chain_volume_density(off, D_off, settings.fault);
  if (st != WalkStatus::ok) {
    r.walk = st;
    return r;
  }
  std::vector<Vec3> vo(m);
  for (size_t i = 0; i < m; ++i) vo[i] = w.chain.v[i + 1].p().cast<float>();
  const Vec3 x_off = end.cast<float>();
  Rgb fo;
  double po = 0.0;
  if (!eval_chain(scene, chain, vo, x_off, photon_medium, fo, po, r.occluded)) return r;
  const float d_ratio = float(D_off / base.D);
  for (int c = 0; c < 3; ++c) r.ratio[c] = base.f[c] > 0.0f ? fo[c] / base.f[c] * d_ratio : 0.0f;
  r.pdf_ratio = (po * D_off) / (base.p * base.D);
  r.w = (x_off - vo.back()).normalized();
  r.b_offset = x_off;
  r.ok = !is_black(r.ratio) && r.pdf_ratio > 0.0 && std::isfinite(r.pdf_ratio) && is_finite(r.ratio);
  return r;
}

ChainReconnection reconnect_photon_chain(const scene::Scene& scene, const PhotonChain& chain, int photon_medium,
                                         const Vec3& b, const Vec3& b_offset, const ChainReconnectSettings& settings,
                                         manifold::WalkStats* stats) {
  const ChainBase base = chain_base(scene, chain, photon_medium, b, settings.fault, stats);
  return reconnect_photon_chain(scene, chain, base, photon_medium, b_offset, settings, stats);
}

}  // namespace dp::gradients
