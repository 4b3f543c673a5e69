#include "tests/integrators/bidir_reference.h"

#include <cmath>

#include "core/rng.h"
#include "pathspace/bidir_subpath.h"
#include "scene/shapes/shape.h"

namespace dp::test {

using pathspace::BidirKind;

bool is_dirac(const BidirVertex& v) { return v.kind == BidirKind::surface && v.bsdf && v.bsdf->is_purely_delta(); }
bool at_infinity(const BidirVertex& v) { return v.kind == BidirKind::light && v.emitter->is_infinite(); }

namespace {

bool is_pinhole_or_point(const BidirVertex& v) {
  return v.kind == BidirKind::camera || (v.kind == BidirKind::light && v.is_delta_light());
}

double to_area(double pdf, const BidirVertex& from, const BidirVertex& to) {
  if (at_infinity(to)) return pdf;  // densities of a vertex at infinity are directional
  const Vec3d d = (to.sp.p - from.sp.p).cast<double>();
  const double d2 = d.squaredNorm();
  const double c = is_pinhole_or_point(to) ? 1.0 : std::abs(to.sp.ng.cast<double>().dot(d)) / std::sqrt(d2);
  return pdf * c / d2;
}
// Unit direction a -> b; a vertex at infinity keeps its direction toward the light in ng.
Vec3 dir(const BidirVertex& a, const BidirVertex& b) {
  if (at_infinity(b)) return b.sp.ng;
  if (at_infinity(a)) return -a.sp.ng;
  return (b.sp.p - a.sp.p).normalized();
}
double ref_bsdf_pdf(const BidirVertex& v, const Vec3& from, const Vec3& to, scene::TransportMode mode) {
  return v.bsdf->pdf(scene::BsdfContext{v.sp.uv, mode}, v.sp.shading.to_local(from), v.sp.shading.to_local(to));
}


}  // namespace

Reference reference(const scene::Scene& scene, std::vector<BidirVertex> x, bool power) {
  Reference r;
  const int n = int(x.size());
  r.pl.assign(size_t(n), 0.0);
  r.pc.assign(size_t(n), 0.0);
  const scene::Emitter* e = x[0].emitter;
  const bool point = e->kind() == scene::EmitterKind::point, delta = e->is_delta();
  const bool env = e->kind() == scene::EmitterKind::environment, infinite = e->is_infinite();
  const double pmf = double(scene.emitter_pmf(e));
  // Lights at infinity (pbrt-v3's convention): origin density pmf * direction density,
  // the lit vertex's density uniform on a disk of the scene's radius times its cosine.
  const double disk_r = 0.5 * double(scene.bounds().diagonal());
  for (int i = 0; i < n; ++i) {
    if (i == 0) {
      if (env) r.pl[0] = pmf * double(e->pdf_direct(x[0].sp.p, {}, {}, x[0].sp.ng));
      else r.pl[0] = delta ? pmf : pmf / double(static_cast<const scene::AreaEmitter*>(e)->shape()->area());
    } else if (i == 1 && infinite) {
      r.pl[1] = std::abs(double(x[1].sp.ng.dot(x[0].sp.ng))) / (kPiD * disk_r * disk_r);
    } else if (i == 1) {
      const Vec3 w = dir(x[0], x[1]);
      const double pd = point ? 1.0 / (4.0 * kPiD) : std::max(0.0, double(x[0].sp.ng.dot(w))) / kPiD;
      r.pl[1] = to_area(pd, x[0], x[1]);
    } else r.pl[size_t(i)] = is_dirac(x[size_t(i - 1)]) ? 1.0
        : to_area(ref_bsdf_pdf(x[size_t(i - 1)], dir(x[size_t(i - 1)], x[size_t(i - 2)]), dir(x[size_t(i - 1)], x[size_t(i)]),
                           scene::TransportMode::importance), x[size_t(i - 1)], x[size_t(i)]);
    if (i == n - 1) r.pc[size_t(i)] = 1.0;
    else if (i == n - 2) r.pc[size_t(i)] = to_area(scene.camera().pdf_direction(dir(x[size_t(n - 1)], x[size_t(i)])), x[size_t(n - 1)], x[size_t(i)]);
    else r.pc[size_t(i)] = is_dirac(x[size_t(i + 1)]) ? 1.0
        : to_area(ref_bsdf_pdf(x[size_t(i + 1)], dir(x[size_t(i + 1)], x[size_t(i + 2)]), dir(x[size_t(i + 1)], x[size_t(i)]),
                           scene::TransportMode::radiance), x[size_t(i + 1)], x[size_t(i)]);
  }
  r.valid.assign(size_t(n), false);  // s' = 0 .. n-1 (t' = n - s' >= 1)
  r.weight.assign(size_t(n), 0.0);
  double sum = 0;
  std::vector<double> p(size_t(n), 0.0);
  for (int sp = 0; sp < n; ++sp) {
    r.valid[size_t(sp)] = sp == 0 ? !delta : !is_dirac(x[size_t(sp - 1)]) && !is_dirac(x[size_t(sp)]);
    // t' = 1 splats the light vertex where it projects: impossible at infinity.
    if (sp == n - 1 && at_infinity(x[size_t(sp - 1)])) r.valid[size_t(sp)] = false;
    if (!r.valid[size_t(sp)]) continue;
    double prod = 1.0;
    for (int i = 0; i < n; ++i) prod *= i < sp ? r.pl[size_t(i)] : r.pc[size_t(i)];
    p[size_t(sp)] = power ? prod * prod : prod;
    sum += p[size_t(sp)];
  }
  for (int sp = 0; sp < n; ++sp) r.weight[size_t(sp)] = p[size_t(sp)] / sum;
  r.x = std::move(x);
  return r;
}

void split(const Reference& r, int sp, std::vector<BidirVertex>& light, std::vector<BidirVertex>& camera) {
  const int n = int(r.x.size());
  const bool infinite_light = at_infinity(r.x[0]);
  light.clear();
  camera.clear();
  for (int i = 0; i < sp; ++i) {
    BidirVertex v = r.x[size_t(i)];
    if (i == 0) v.kind = BidirKind::light;
    v.wi = i > 0 ? dir(v, r.x[size_t(i - 1)]) : Vec3::Zero();
    v.pdf_fwd = float(r.pl[size_t(i)]);
    v.pdf_rev = float(r.pc[size_t(i)]);
    v.delta = is_dirac(v);
    light.push_back(v);
  }
  for (int i = n - 1; i >= sp; --i) {
    BidirVertex v = r.x[size_t(i)];
    if (i == 0 && !infinite_light) v.kind = BidirKind::surface;  // s' = 0: the camera walk hit the light
    v.wi = i < n - 1 ? dir(v, r.x[size_t(i + 1)]) : Vec3::Zero();
    v.pdf_fwd = float(r.pc[size_t(i)]);
    v.pdf_rev = float(r.pl[size_t(i)]);
    v.delta = is_dirac(v);
    camera.push_back(v);
  }
}

void for_each_connection(const scene::Scene& scene, int max_depth, int samples, uint64_t seed,
                         const pathspace::MisConfig& config, const ConnectionVisitor& fn) {
  const pathspace::SubpathParams cp{max_depth + 1, 3}, lp{max_depth, 3};
  std::vector<BidirVertex> cam, light, x;
  const auto& c = scene.camera();
  for (int k = 0; k < samples; ++k) {
    core::Rng rng(seed, uint64_t(k));
    const Vec2 raster(rng.uniform() * float(c.width()), rng.uniform() * float(c.height()));
    pathspace::camera_subpath(scene, raster, cp, rng, cam);
    pathspace::light_subpath(scene, lp, rng, light);
    for (int t = 1; t <= int(cam.size()); ++t)
      for (int s = 0; s <= int(light.size()); ++s) {
        if (s + t < 2 || s + t - 1 > max_depth) continue;
        pathspace::Connection con;
        if (!pathspace::connect(scene, light.data(), s, cam.data(), t, config, con)) continue;
        x.assign(light.begin(), light.begin() + s);
        for (int j = t - 1; j >= 0; --j) x.push_back(cam[size_t(j)]);
        fn(k, light, cam, s, t, con, x);
      }
  }
}

}  // namespace dp::test
