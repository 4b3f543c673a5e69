#include "pathspace/bidir_connect.h"

#include "pathspace/bidir_light.h"
#include "pathspace/bidir_media.h"

namespace dp::pathspace {

namespace {

// f(wi, w) |cos w| at a surface vertex (its own subpath's mode), or Le cos for a light
// endpoint; 0 if either direction violates sidedness (geometric vs shading normal).
// At a medium vertex: the phase function (no cosine; sigma_s is in beta).
Rgb scatter(const scene::Scene& scene, const BidirVertex& v, const Vec3& w, scene::TransportMode mode, bool cosine) {
  if (v.kind == BidirKind::light) return light_emit_cos(v, w);
  if (v.kind == BidirKind::medium) return Rgb::Constant(phase_value(scene, v, v.wi, w));
  if (!v.bsdf) return Rgb::Zero();
  const Vec3 wi = v.sp.shading.to_local(v.wi), wo = v.sp.shading.to_local(w);
  if (!(v.sp.ng.dot(v.wi) * wi.z() > 0.0f) || !(v.sp.ng.dot(w) * wo.z() > 0.0f)) return Rgb::Zero();
  return v.bsdf->eval(scene::BsdfContext{v.sp.uv, mode}, wi, wo) * (cosine ? std::abs(wo.z()) : 1.0f);
}

bool blocked(const scene::Scene& scene, const BidirVertex& a, const BidirVertex& b) {
  if (a.infinite()) return scene.occluded(scene.spawn_ray(b.sp, a.sp.ng));
  if (a.on_surface()) return scene.occluded(scene.spawn_segment(a.sp, b.sp.p));
  if (b.on_surface()) return scene.occluded(scene.spawn_segment(b.sp, a.sp.p));
  return scene.occluded(a.sp.p, b.sp.p);
}

}  // namespace

bool connect(const scene::Scene& scene, const BidirVertex* light, int s, const BidirVertex* camera, int t,
             const MisConfig& config, Connection& out, bool test_visibility, const ReversePdfs* reverse,
             GridTracking* grid) {
  out = Connection{};
  const BidirVertex& z = camera[t - 1];
  if (s == 0) {
    if (t < 2 || !z.emitter) return false;
    if (z.infinite()) out.value = z.beta * light_emit_cos(z, -z.sp.ng);  // the camera walk escaped
    else if (z.kind == BidirKind::surface) out.value = z.beta * z.emitter->eval(z.sp, z.wi);
    else return false;
  } else {
    const BidirVertex& y = light[s - 1];
    if (!y.connectable() || !z.connectable() || z.kind == BidirKind::light) return false;
    // A point light seen by a pinhole: no image.
    if (t == 1 && y.kind == BidirKind::light && !y.on_surface()) return false;
    // y -> z; a light at infinity lies along its direction at no distance factor.
    const Vec3 d = z.sp.p - y.sp.p;
    const float dist2 = y.infinite() ? 1.0f : d.squaredNorm();
    if (!(dist2 > 0.0f)) return false;
    const Vec3 w = y.infinite() ? Vec3(-y.sp.ng) : Vec3(d / std::sqrt(dist2));
    const bool cosine = config.fault != BidirFault::connection_without_cosine;
    const Rgb fy = scatter(scene, y, w, scene::TransportMode::importance, cosine);
    if (is_black(fy)) return false;
    if (t == 1) {
      const auto raster = scene.camera().raster_of(y.sp.p);
      if (!raster) return false;
      out.raster = *raster;
      out.value = y.beta * fy * (scene.camera().pdf_direction(-w) / dist2);
    } else {
      const Rgb fz = scatter(scene, z, -w, scene::TransportMode::radiance, cosine);
      out.value = y.beta * fy * fz * z.beta / dist2;
    }
  }
  if (is_black(out.value)) return false;
  // With media the connection is traced through index-matched boundaries: its
  // transmittance, and the free-flight factors of its reverse densities (bidir_media.h).
  const bool media = s > 0 && scene.caps().has_media;
  EdgeMedia edge;
  if (media) {
    out.tested = true;
    edge = trace_edge(scene, z, light[s - 1], grid);
    out.occluded = edge.blocked;
    if (config.fault != BidirFault::connection_without_transmittance) out.value *= edge.tr;
    if (out.occluded || is_black(out.value)) return false;
  } else if (s > 0 && test_visibility) {
    out.tested = true;
    out.occluded = blocked(scene, light[s - 1], z);
    if (out.occluded) return false;
  }
  if (config.unweighted) out.weight = 1.0f;
  else if (reverse) out.weight = mis_weight(light, s, camera, t, config, *reverse);
  else if (media)
    out.weight = mis_weight(light, s, camera, t, config, connection_reverse_pdfs(scene, light, s, camera, t, config, &edge));
  else out.weight = mis_weight(scene, light, s, camera, t, config);
  return out.weight > 0.0f;
}

}  // namespace dp::pathspace
