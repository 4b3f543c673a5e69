#include "integrators/gvpm/gvpm_tracer.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "gradients/volume_photon_shift.h"
#include "integrators/beam/beam_gather.h"
#include "integrators/media_photons/volume_kernel.h"
#include "integrators/volpath/volpath_tracer.h"  // kMaxNullCrossings
#include "integrators/vpm/vpm_gather.h"          // sample_truncated_distance, truncated_distance_pdf
#include "scene/media/free_flight.h"
#include "scene/media/medium_interface.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

using gradients::ParentKind;
using gradients::PhotonShiftKind;

void GvpmCounters::flush(core::Stats& stats, const std::string& prefix, const GatherCounterNames& names) const {
  camera.flush(stats, prefix, names);
  stats.add(prefix + ".samples", samples);
  stats.add(prefix + ".nan_dropped", nan_dropped);
  stats.add(prefix + ".direct_paths", direct_paths);
  stats.add(prefix + ".primary_segments", primary_segments);
  stats.add(prefix + ".gather_points", gather_points);
  stats.add(prefix + ".photons_gathered_primary", photons_gathered);
  stats.add(prefix + ".photons_depth_skipped_primary", depth_skipped);
  stats.add(prefix + ".empty_segments_primary", empty_segments);
  stats.add(prefix + ".shift.attempted", shifts);
  stats.add(prefix + ".shift.null", shift_null);
  stats.add(prefix + ".shift.simple", shift_simple);
  stats.add(prefix + ".shift.reflected", shift_reflected);
  stats.add(prefix + ".shift.reconnections", reconnections);
  stats.add(prefix + ".shift.fail.segment_missing", fail_segment_missing);
  stats.add(prefix + ".shift.fail.medium", fail_medium);
  stats.add(prefix + ".shift.fail.distance", fail_distance);
  stats.add(prefix + ".shift.fail.occluded", fail_occluded);
  stats.add(prefix + ".shift.fail.zero_contribution", fail_zero);
  for (int k = 0; k < gradients::kParentKindCount; ++k) {
    const auto kind = ParentKind(k);
    if (kind == ParentKind::medium || kind == ParentKind::surface || kind == ParentKind::light) continue;
    stats.add(prefix + ".shift.fail.parent_" + gradients::to_string(kind), fail_parent[size_t(k)]);
  }
  stats.add(prefix + ".shift.chain_reconnections", chain_reconnections);
  stats.add(prefix + ".shift.fail.chain_occluded", fail_chain_occluded);
  walks.flush(stats, prefix + ".shift.manifold");
  stats.add(prefix + ".shift.plane_rotations", plane_rotations);
  stats.add(prefix + ".shift.fail.plane_degenerate", fail_plane_degenerate);
  stats.add(prefix + ".shift.fail.plane_segment", fail_plane_segment);
  stats.add(prefix + ".pairs.shifted", pairs_shifted);
  stats.add(prefix + ".pairs.fallback", pairs_fallback);
  stats.add(prefix + ".pairs.outside_image", outside_image);
}

namespace {

// vpm's gather for every camera segment except the primary ray's (those have the full
// path-length budget max_depth - 1 and are gathered and shifted by GvpmTracer); on the
// primary ray's segments only `primary` (gplane: the unshifted beam part), if any.
class LaterSegments final : public MediumGather {
 public:
  LaterSegments(const MediumGather* inner, const MediumGather* primary, int primary_budget)
      : m_inner(inner), m_primary_gather(primary), m_primary(primary_budget) {}
  Rgb gather(const Ray& ray, float seg_len, int medium, int max_photon_depth, core::Rng& rng,
             GatherCounters& counters) const override {
    const MediumGather* g = max_photon_depth == m_primary ? m_primary_gather : m_inner;
    if (!g) return Rgb::Zero();
    return g->gather(ray, seg_len, medium, max_photon_depth, rng, counters);
  }

 private:
  const MediumGather* m_inner;
  const MediumGather* m_primary_gather;
  int m_primary;
};

}  // namespace

GvpmTracer::GvpmTracer(const scene::Scene& scene, const GvpmSettings& settings, int max_depth, float radius,
                       const GvpmLightData& data)
    : m_scene(scene),
      m_settings(settings),
      m_max_depth(max_depth),
      m_photons(data.photons),
      m_parents(data.parents),
      m_chains(data.chains),
      m_radius(radius),
      m_beam(settings.gather != GvpmGather::points),
      m_beams(settings.gather == GvpmGather::beams ? data.beams : nullptr),
      m_scale(data.light_paths > 0 ? uniform_kernel(3, double(radius)) /
                                         (double(data.light_paths) * (m_beam ? 1 : settings.distance_samples))
                                   : 0.0),
      m_later(data.later),
      m_primary_unshifted(data.primary_unshifted),
      m_planes(settings.gather == GvpmGather::planes ? data.planes : nullptr),
      m_paths(data.light_paths),
      m_camera(scene, settings.rr_depth, max_depth) {}

void GvpmTracer::primary_segments(const Ray& primary, std::vector<GvpmSegment>& out) const {
  // As MediaCameraTracer walks the primary ray: segments in media until the first surface
  // that is not an index-matched boundary.
  out.clear();
  const int cam_medium = m_scene.camera_medium();
  int medium = cam_medium, nulls = 0;
  Ray ray = primary;
  Rgb beta = Rgb::Ones();
  scene::SurfaceHit hit;
  bool from_surface = false;
  for (;;) {
    const bool found = from_surface ? m_scene.trace_from(hit, ray.d, hit) : m_scene.intersect(ray, hit);
    if (medium >= 0) {
      const float seg = found ? hit.t : kInfinity;
      out.push_back({ray, seg, medium, beta});
      beta *= scene::transmittance(m_scene.media()[size_t(medium)], seg);
      if (is_black(beta)) return;
    }
    if (!found || !scene::is_index_matched(hit) || ++nulls > VolpathTracer::kMaxNullCrossings) return;
    medium = scene::medium_toward(hit, ray.d, medium, cam_medium);
    ray = m_scene.continue_ray(hit, ray.d);
    from_surface = true;
  }
}

float GvpmTracer::distance_pdf(const scene::HomogeneousMedium& m, float len, float t, bool truncated) const {
  // vpm_gather.cpp's mixture over the channels whose truncated exponential is a density.
  const Rgb st = m.sigma_t();
  float p = 0.0f;
  int n = 0;
  for (int c = 0; c < 3; ++c) {
    if (!(st[c] > 0.0f || std::isfinite(len))) continue;
    ++n;
    p += truncated ? truncated_distance_pdf(st[c], len, t) : st[c] * std::exp(-st[c] * t);
  }
  return n > 0 ? p / float(n) : 0.0f;
}

void GvpmTracer::gather(const GvpmSegment& seg, int k, core::Rng& rng, GvpmScratch& sc, GvpmCounters& counters) const {
  const int budget = m_max_depth - 1;
  const bool beams = m_settings.gather == GvpmGather::beams, planes = m_settings.gather == GvpmGather::planes;
  const bool no_data = planes  ? (!m_planes || m_planes->empty())
                       : beams ? (!m_beams || m_beams->empty())
                               : (!m_photons || m_photons->empty());
  if (budget < 1 || no_data || !(seg.len > 0.0f)) return;
  if (planes) return gather_planes(seg, k, sc, counters);  // checks the medium itself
  const scene::HomogeneousMedium& med = m_scene.media()[size_t(seg.medium)];
  if (is_black(med.sigma_s)) {  // nothing scatters toward the camera here
    ++counters.empty_segments;
    return;
  }
  if (beams) return gather_beams(seg, k, med, rng, sc, counters);
  if (m_beam) return gather_beam(seg, k, med, rng, sc, counters);
  const Rgb st = med.sigma_t();
  int channels[3], n_ch = 0;
  for (int c = 0; c < 3; ++c)
    if (st[c] > 0.0f || std::isfinite(seg.len)) channels[n_ch++] = c;
  if (n_ch == 0) {
    ++counters.empty_segments;
    return;
  }
  const scene::HenyeyGreenstein phase(med.phase);
  const Vec3 to_camera = -seg.ray.d;
  const int m = m_settings.distance_samples;
  for (int j = 0; j < m; ++j) {  // as VpmGather::gather
    const int c = channels[std::min(int(rng.uniform() * float(n_ch)), n_ch - 1)];
    const float u = (float(j) + rng.uniform()) / float(m);
    const float t = std::min(sample_truncated_distance(st[c], seg.len, u), seg.len);
    const float p = distance_pdf(med, seg.len, t, true);
    if (!(p > 0.0f) || !std::isfinite(t)) continue;
    GvpmGatherPoint gp;
    gp.segment = k;
    gp.t = t;
    gp.pdf = p;
    gp.d = seg.ray.at(t);
    gp.first = uint32_t(sc.terms.size());
    ++counters.gather_points;
    // Camera side of Eq. 5: beta_k Tr(t) / p(t), with K3 / (N M).
    const Rgb cam = seg.beta * scene::transmittance(med, t) * float(m_scale / double(p));
    m_photons->query_point(gp.d, m_radius, [&](const MediumPhoton& ph, float) {
      if (ph.medium != seg.medium) return;
      if (ph.depth > budget) {
        ++counters.depth_skipped;
        return;
      }
      const Rgb v = cam * phase.eval(ph.w, to_camera) * ph.beta;  // rho_p at the merged vertex (Eq. 3)
      if (is_black(v)) return;
      ++counters.photons_gathered;
      sc.terms.push_back({&ph, v});
    });
    gp.count = uint32_t(sc.terms.size()) - gp.first;
    if (gp.count > 0) sc.points.push_back(gp);
  }
}

void GvpmTracer::gather_beam(const GvpmSegment& seg, int k, const scene::HomogeneousMedium& med, core::Rng& rng,
                             GvpmScratch& sc, GvpmCounters& counters) const {
  // Point-Beam 3D (Sec. 5.1): every photon within r of the segment, its gather point d
  // drawn uniformly on its chord (p(t) = 1 / |chord|), then shifted as G-VPM's (the
  // distance copied, the mixed photon shift keeps |d'b'| <= r).
  const int budget = m_max_depth - 1;
  const scene::HenyeyGreenstein phase(med.phase);
  const float r = m_radius;
  m_photons->query_beam(seg.ray.o - r * seg.ray.d, seg.ray.d, seg.len + 2.0f * r, r,
                        [&](const MediumPhoton& ph, float tq, float d2) {
                          if (ph.medium != seg.medium) return;
                          if (ph.depth > budget) {
                            ++counters.depth_skipped;
                            return;
                          }
                          float lo = 0, hi = 0;
                          if (!point_beam_chord(tq - r, d2, r, seg.len, lo, hi)) return;
                          chord_term(seg, k, med, phase, ph, lo, hi, rng, sc, counters);
                        });
}

void GvpmTracer::chord_term(const GvpmSegment& seg, int k, const scene::HomogeneousMedium& med,
                            const scene::HenyeyGreenstein& phase, const MediumPhoton& ph, float lo, float hi,
                            core::Rng& rng, GvpmScratch& sc, GvpmCounters& counters) const {
  const float t = std::min(lo + rng.uniform() * (hi - lo), std::nextafter(hi, lo));
  GvpmGatherPoint gp;
  gp.segment = k;
  gp.t = t;
  gp.pdf = m_settings.fault == GvpmFault::chord_as_diameter ? 0.5f / m_radius : 1.0f / (hi - lo);
  gp.d = seg.ray.at(t);
  gp.first = uint32_t(sc.terms.size());
  gp.count = 1;
  ++counters.gather_points;
  const Rgb v = seg.beta * scene::transmittance(med, t) * float(m_scale / double(gp.pdf)) *
                phase.eval(ph.w, -seg.ray.d) * ph.beta;
  if (is_black(v) || !(gp.pdf > 0.0f) || !std::isfinite(gp.pdf)) return;
  ++counters.photons_gathered;
  sc.terms.push_back({&ph, v});
  sc.points.push_back(gp);
}

void GvpmTracer::gather_beams(const GvpmSegment& seg, int k, const scene::HomogeneousMedium& med, core::Rng& rng,
                              GvpmScratch& sc, GvpmCounters& counters) const {
  // Beam-Beam 3D (Sec. 5.2, Fig. 6c): per beam piece within r of the segment one photon b
  // uniform on the piece's chord (beam_gather.h), then its gather point uniform on the
  // camera chord around b (p(t) = 1 / |chord|, as gbre); shifted as gbre's.
  const int budget = m_max_depth - 1;
  const float r = m_radius;
  const float s = m_beams->clip(seg.ray.o, seg.ray.d, seg.len, r);  // no beam lies beyond
  if (!(s > 0.0f)) return;
  const scene::HenyeyGreenstein phase(med.phase);
  const bool chord_pdf = m_settings.fault != GvpmFault::beam_chord_ignored;
  m_beams->query_segment(seg.ray.o, seg.ray.d, s, r, [&](const MediumBeam& beam, float v0, float v1) {
    if (beam.medium != seg.medium) return;
    if (beam.depth > budget) {
      ++counters.depth_skipped;
      return;
    }
    double blo = 0, bhi = 0;
    if (!beam_tube_interval(beam.a, beam.w, double(v0), double(v1), seg.ray.o, seg.ray.d, double(s), double(r), blo, bhi))
      return;
    const double chord_b = bhi - blo;
    const float v = float(blo + double(rng.uniform()) * chord_b);
    const Vec3 b = beam.a + v * beam.w;
    float lo = 0, hi = 0;
    if (!point_beam_chord(seg.ray.o, seg.ray.d, seg.len, b, r, lo, hi)) return;  // b(v) farther than r
    const Rgb weight = beam.beta * beam_point_weight(med, v) * med.sigma_s * float(chord_pdf ? chord_b : 1.0);
    // The photon drawn on the beam, kept at a stable address for its term.
    sc.beam_photons.push_back(MediumPhoton{b, beam.w, weight, beam.depth, beam.medium, beam.index});
    chord_term(seg, k, med, phase, sc.beam_photons.back(), lo, hi, rng, sc, counters);
  });
}

namespace {
// gbeam: the chord of the line through x along w within r of the camera segment
// (beam_tube_interval over the whole line); 0 if it misses (R's light factor).
double line_chord(const Vec3& x, const Vec3& w, const GvpmSegment& seg, float r) {
  double lo = 0, hi = 0;
  if (!beam_tube_interval(x, w, -1e30, 1e30, seg.ray.o, seg.ray.d, double(seg.len), double(r), lo, hi)) return 0.0;
  return hi - lo;
}
}  // namespace

void GvpmTracer::sample(int px, int py, core::Rng& rng, GvpmScratch& sc, gradients::GradientBuffers& buf,
                        GvpmCounters& counters) const {
  ++counters.samples;
  const auto& cam = m_scene.camera();
  const Vec2 raster(float(px) + rng.uniform(), float(py) + rng.uniform());
  const Ray primary = cam.generate_ray(raster);
  sc.splats.clear();
  sc.splats.pair_primal = true;
  sc.terms.clear();
  sc.points.clear();
  sc.beam_photons.clear();
  sc.plane_terms.clear();
  sc.chain_bases.clear();
  // The unshifted part: vpm's camera path without the primary ray's gathers.
  const LaterSegments later(m_later, m_primary_unshifted, m_max_depth - 1);
  const Rgb direct = m_camera.radiance(primary, m_later ? &later : nullptr, rng, counters.camera);
  if (!is_black(direct) || !is_finite(direct)) {
    sc.splats.add(px, py, 1, direct.cast<double>());
    ++counters.direct_paths;
  }
  if (m_later) {  // a scene with media
    primary_segments(primary, sc.base);
    for (size_t k = 0; k < sc.base.size(); ++k) {
      ++counters.primary_segments;
      gather(sc.base[k], int(k), rng, sc, counters);
    }
    if (!sc.terms.empty() || !sc.plane_terms.empty())
      for (int nb = 0; nb < 4; ++nb) offsets(nb, px, py, raster, sc, buf.width(), buf.height(), counters);
  }
  if (!sc.splats.flush(buf, px, py)) ++counters.nan_dropped;  // the whole sample is dropped, never splatted
}

void GvpmTracer::offsets(int nb, int px, int py, const Vec2& raster, GvpmScratch& sc, int w, int h,
                         GvpmCounters& counters) const {
  const int qx = px + kPairDx[nb], qy = py + kPairDy[nb];
  if (qx < 0 || qy < 0 || qx >= w || qy >= h) {  // no pair: the base pixel keeps its own estimate
    counters.outside_image += int64_t(sc.terms.size() + sc.plane_terms.size());
    for (const GvpmTerm& t : sc.terms) sc.splats.unpaired(px, py, t.value.cast<double>(), 1.0);
    for (const GvpmPlaneTerm& t : sc.plane_terms) sc.splats.unpaired(px, py, t.value.cast<double>(), 1.0);
    return;
  }
  // Sec. 4.1: the primary ray through the same sub-pixel position of pixel j.
  primary_segments(m_scene.camera().generate_ray(raster + Vec2(float(kPairDx[nb]), float(kPairDy[nb]))), sc.offset);
  if (m_planes) return plane_offsets(nb, px, py, sc, counters);
  const bool truncated = m_settings.fault != GvpmFault::untruncated_offset_pdf;
  const bool weight_one = m_settings.fault == GvpmFault::mis_weight_one;
  for (const GvpmGatherPoint& gp : sc.points) {
    const GvpmSegment& base = sc.base[size_t(gp.segment)];
    const scene::HomogeneousMedium& med = m_scene.media()[size_t(base.medium)];
    const scene::HenyeyGreenstein phase(med.phase);
    // The gather point's copy t' = t (Jacobian 1), valid only inside the offset segment.
    const GvpmSegment* off = nullptr;
    int64_t* fail = nullptr;
    if (size_t(gp.segment) >= sc.offset.size()) fail = &counters.fail_segment_missing;
    else if (sc.offset[size_t(gp.segment)].medium != base.medium) fail = &counters.fail_medium;
    else if (!(gp.t < sc.offset[size_t(gp.segment)].len)) fail = &counters.fail_distance;
    else off = &sc.offset[size_t(gp.segment)];
    float p_off = 0.0f;
    if (off && !m_beam) {
      p_off = distance_pdf(med, off->len, gp.t, truncated);  // Eq. 14 on the offset segment
      if (!(p_off > 0.0f)) {
        fail = &counters.fail_distance;
        off = nullptr;
      }
    }
    const Vec3 d_off = off ? off->ray.at(gp.t) : gp.d;
    Rgb cam_off = Rgb::Zero();
    if (off) cam_off = off->beta * scene::transmittance(med, gp.t) * float(m_scale / double(gp.pdf));
    const double r_cam = off ? double(p_off) / double(gp.pdf) : 0.0;
    // R's camera factor p'(t) / p(t) for the offset photon b' (gbre: 1 / |chord of b'| on
    // the offset segment; 0 -- a failed shift -- if t is not on it).
    auto camera_ratio = [&](const Vec3& b_off) -> double {
      if (!m_beam) return r_cam;
      float lo = 0, hi = 0;
      if (!point_beam_chord(off->ray.o, off->ray.d, off->len, b_off, m_radius, lo, hi) || gp.t < lo || gp.t > hi)
        return 0.0;
      return 1.0 / (double(hi - lo) * double(gp.pdf));
    };
    for (uint32_t i = gp.first; i < gp.first + gp.count; ++i) {
      const GvpmTerm& term = sc.terms[i];
      const Rgbd base_v = term.value.cast<double>();
      ++counters.shifts;
      Rgbd off_v = Rgbd::Zero();
      double R = 0.0;
      bool ok = false;
      if (!off) {
        ++*fail;
      } else {
        const MediumPhoton& ph = *term.photon;
        Vec3 b_off;
        const PhotonShiftKind kind = m_settings.mixed
                                         ? gradients::mixed_photon_shift_t(ph.p, gp.d, d_off, m_radius, b_off)
                                         : (b_off = gradients::simple_photon_shift(ph.p, gp.d, d_off), PhotonShiftKind::simple);
        // gbeam: R's light factor C(b, w_b) / C(b', w_b') (gvpm_tracer.h).
        const double c_base = m_beams ? line_chord(ph.p, ph.w, base, m_radius) : 1.0;
        auto light_ratio = [&](const Vec3& x, const Vec3& dir) -> double {
          if (!m_beams) return 1.0;
          const double c_off = line_chord(x, dir, *off, m_radius);
          return c_off > 0.0 ? c_base / c_off : 0.0;
        };
        if (kind == PhotonShiftKind::null) {  // the same photon in both kernels: no reconnection
          ++counters.shift_null;
          const Rgb v = cam_off * phase.eval(ph.w, -off->ray.d) * ph.beta;
          off_v = v.cast<double>();
          R = camera_ratio(ph.p) * light_ratio(ph.p, ph.w);
          ok = !is_black(v) && R > 0.0;
          if (!(R > 0.0)) ++counters.fail_distance;
          else if (!ok) ++counters.fail_zero;
        } else {
          ++(kind == PhotonShiftKind::simple ? counters.shift_simple : counters.shift_reflected);
          const gradients::PhotonParent& parent = (*m_parents)[ph.index];
          const bool walk = parent.kind == ParentKind::specular && parent.chain >= 0 && m_chains && m_settings.manifold;
          if (!walk && parent.kind != ParentKind::medium && parent.kind != ParentKind::surface &&
              parent.kind != ParentKind::light) {
            ++counters.fail_parent[size_t(parent.kind)];
          } else {
            bool blocked = false;
            gradients::PhotonReconnection rec;
            if (walk) {
              // Sec. 6: the walk may stop once its end lies in the offset kernel (around d').
              gradients::ChainReconnectSettings cs;
              cs.max_iterations = m_settings.manifold_iterations;
              cs.fault = m_settings.chain_fault;
              if (m_settings.manifold_relaxed) cs.accept_distance = std::max(0.0, double(m_radius) - double((b_off - d_off).norm()));
              const gradients::PhotonChain& chain = (*m_chains)[size_t(parent.chain)];
              // The base side once per photon and camera sample (its four neighbours share it).
              auto [it, fresh] = sc.chain_bases.try_emplace(&ph);
              if (fresh) it->second = gradients::chain_base(m_scene, chain, ph.medium, ph.p, cs.fault, &counters.walks);
              const gradients::ChainReconnection cr =
                  gradients::reconnect_photon_chain(m_scene, chain, it->second, ph.medium, b_off, cs, &counters.walks);
              rec = cr;
              if (cr.ok) {
                b_off = cr.b_offset;
                ++counters.chain_reconnections;
              }
              if (cr.occluded) ++counters.fail_chain_occluded;
              blocked = cr.walk != manifold::WalkStatus::ok || cr.occluded;
            } else {
              rec = gradients::reconnect_photon_edge(m_scene, parent, ph.medium, ph.p, b_off, blocked,
                                                     m_settings.reconnect_fault);
            }
            if (!rec.ok) {
              ++(blocked ? counters.fail_occluded : counters.fail_zero);
            } else {
              const Rgb v = cam_off * phase.eval(rec.w, -off->ray.d) * ph.beta * rec.ratio;
              off_v = v.cast<double>();
              // Eq. 19: p(Tz) p(Ty) / (p(z) p(y)), |T'| = 1
              R = camera_ratio(b_off) * rec.pdf_ratio * light_ratio(b_off, rec.w);
              ok = !is_black(v) && R > 0.0;
              if (ok) ++counters.reconnections;
              else ++(R > 0.0 ? counters.fail_zero : counters.fail_distance);
            }
          }
        }
      }
      // Eq. 19 (balance heuristic, one strategy per pixel): w = 1 / (1 + R).
      const bool paired = sc.splats.mis_pair(nb, px, py, base_v, 1.0, ok, off_v, 1.0, R, 1.0, weight_one);
      ++(paired ? counters.pairs_shifted : counters.pairs_fallback);
    }
  }
}

}  // namespace dp::integrators
