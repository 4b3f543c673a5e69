#include "integrators/media_photons/photon_tracer.h"

#include <algorithm>
#include <cmath>
#include <iterator>

#include "core/rng.h"
#include "core/thread_pool.h"
#include "integrators/volpath/volpath_tracer.h"  // kMaxNullCrossings
#include "pathspace/bidir_subpath.h"
#include "scene/emitters/emitter.h"
#include "scene/media/free_flight.h"
#include "scene/media/grid_tracking.h"
#include "scene/media/medium_interface.h"
#include "scene/media/phase_function.h"

namespace dp::integrators {

PhotonTraceCounters& PhotonTraceCounters::operator+=(const PhotonTraceCounters& o) {
  paths += o.paths;
  stored += o.stored;
  surface_events += o.surface_events;
  null_crossings += o.null_crossings;
  rr_terminated += o.rr_terminated;
  null_limit += o.null_limit;
  nan_dropped += o.nan_dropped;
  grid_flights += o.grid_flights;
  return *this;
}

void PhotonTraceCounters::flush(core::Stats& stats, const std::string& prefix) const {
  stats.add(prefix + ".photon_paths", paths);
  stats.add(prefix + ".photons_stored", stored);
  stats.add(prefix + ".photon_surface_events", surface_events);
  stats.add(prefix + ".photon_null_crossings", null_crossings);
  stats.add(prefix + ".photon_rr_terminated", rr_terminated);
  stats.add(prefix + ".fail.photon_null_limit", null_limit);
  stats.add(prefix + ".photon_nan_dropped", nan_dropped);
  if (grid_flights > 0) stats.add(prefix + ".photon_grid_flights", grid_flights);
}

void grown_bounds_clip(const scene::Scene& scene, const Vec3& o, const Vec3& d, float& t0, float& t1) {
  const Bounds3& b = scene.bounds();
  t0 = 0.0f;
  t1 = kInfinity;
  if (!b.valid()) {
    t0 = 1.0f;
    t1 = 0.0f;
    return;
  }
  const float grow = std::max(b.diagonal(), 1.0f);
  for (int a = 0; a < 3; ++a) {
    const float lo = b.lo[a] - grow, hi = b.hi[a] + grow;
    if (d[a] == 0.0f) {
      if (o[a] < lo || o[a] > hi) t0 = kInfinity;
      continue;
    }
    const float ta = (lo - o[a]) / d[a], tb = (hi - o[a]) / d[a];
    t0 = std::max(t0, std::min(ta, tb));
    t1 = std::min(t1, std::max(ta, tb));
  }
}

namespace {

constexpr int64_t kChunk = 4096;  // light paths per work item (and random stream)

using gradients::ParentKind;
using gradients::PhotonParent;

// The light endpoint as emit_light_ray drew it from `rng` (a copy taken before the draw).
PhotonParent light_parent(const scene::Scene& scene, core::Rng rng, std::vector<pathspace::BidirVertex>& scratch) {
  PhotonParent parent;
  pathspace::SubpathParams one;
  one.max_vertices = 1;
  pathspace::light_subpath(scene, one, rng, scratch);
  if (scratch.empty()) return parent;
  const pathspace::BidirVertex& y0 = scratch[0];
  parent.a = y0.sp.p;
  parent.ng = y0.sp.ng;
  parent.uv = y0.sp.uv;
  parent.emitter = y0.emitter;
  parent.kind = y0.emitter && !y0.emitter->is_infinite() ? ParentKind::light : ParentKind::light_infinite;
  return parent;
}

// The short beam of the segment the free flight just sampled (photon_tracer.h): from the
// ray's origin over `length` (the flight's end), with the throughput before its weight.
void tracer_record_beam(const scene::Scene& scene, const scene::HomogeneousMedium& med, const Ray& ray, float length,
                        const Rgb& beta, int s, int medium, bool after_scatter, std::vector<MediumBeam>& beams,
                        BeamTraceCounters& bc) {
  if (is_black(med.sigma_s) || is_black(beta)) return;  // nothing scatters out of it
  if (!is_finite(beta) || !ray.o.allFinite() || !ray.d.allFinite() || std::isnan(length)) {
    ++bc.dropped;
    return;
  }
  if (!(length > 0.0f)) return;  // an empty segment
  float t0 = 0.0f, t1 = 0.0f;
  grown_bounds_clip(scene, ray.o, ray.d, t0, t1);
  const float begin = std::max(t0, 0.0f), end = std::min(t1, length);
  if (begin > 0.0f || end < length) ++bc.clipped;
  if (!(end > begin) || !std::isfinite(end)) return;  // wholly outside the grown bounds
  beams.push_back(MediumBeam{ray.o, ray.d, end, begin, beta, int16_t(s), int16_t(medium), uint32_t(beams.size()),
                             after_scatter});
  ++bc.stored;
}

// The specular chain of the photons after a Dirac vertex at `hit` (volume_photon_chain.h):
// a new chain anchored at a reconnectable `parent`, or `parent`'s chain one vertex longer;
// -1 (no walk possible) for a BSDF that is not purely specular, an anchor at infinity or a
// chain longer than kMaxPhotonChain. `din`: the arriving ray's direction.
int32_t extend_chain(const PhotonParent& parent, const scene::SurfaceHit& hit, const scene::BsdfSample& bs,
                     float u_lobe, const Vec3& din, const Vec3& wo, std::vector<gradients::PhotonChain>& chains) {
  if (!hit.bsdf->is_purely_delta() || hit.shape < 0) return -1;
  const bool anchor =
      parent.kind == ParentKind::medium || parent.kind == ParentKind::surface || parent.kind == ParentKind::light;
  const bool extend = parent.kind == ParentKind::specular && parent.chain >= 0 &&
                      chains[size_t(parent.chain)].steps.size() < size_t(gradients::kMaxPhotonChain);
  if (!anchor && !extend) return -1;
  gradients::PhotonChainStep st;
  st.p = hit.p;
  st.shape = hit.shape;
  st.prim = hit.prim;
  st.lobe = bs.lobe;
  st.u_lobe = u_lobe;
  // Refraction: the arriving and leaving directions on opposite sides; eta as
  // manifold/chain.h's (interior over exterior): bs.eta is eta_o / eta_i.
  st.refraction = hit.ng.dot(-din) * hit.ng.dot(wo) < 0.0f;
  st.eta = !st.refraction ? 1.0f : hit.ng.dot(-din) > 0.0f ? bs.eta : 1.0f / bs.eta;
  if (st.refraction && st.eta == 1.0f) return -1;  // index-matched: no half vector
  // A longer chain is a new record (beams recorded inside the chain keep the shorter one).
  const int32_t idx = int32_t(chains.size());
  if (anchor) chains.push_back(gradients::PhotonChain{parent, {}});
  else chains.push_back(chains[size_t(parent.chain)]);
  chains[size_t(idx)].steps.push_back(st);
  return idx;
}

void trace_one(const scene::Scene& scene, const PhotonTraceParams& params, core::Rng& rng,
               std::vector<MediumPhoton>& out, PhotonTraceCounters& c, std::vector<PhotonParent>* parents,
               std::vector<pathspace::BidirVertex>& scratch, std::vector<MediumBeam>* beams, BeamTraceCounters& bc,
               std::vector<PhotonParent>* beam_parents, std::vector<MediumPlane>* planes, PlaneTraceCounters& plc,
               core::Rng& plane_rng, std::vector<gradients::PhotonChain>* chains) {
  ++c.paths;
  Ray ray;
  Rgb beta;
  PhotonParent parent;
  if (parents) parent = light_parent(scene, rng, scratch);
  if (!pathspace::emit_light_ray(scene, rng, ray, beta)) return;
  const float beta0 = max_component(beta);
  const int cam_medium = scene.camera_medium();
  const int max_store = params.max_depth - 1;  // a gather needs at least one camera segment
  scene::SurfaceHit hit;
  bool found = scene.intersect(ray, hit);
  // The medium the light sits in: the near side of the first surface if it is a boundary.
  int medium = found ? scene::medium_toward(hit, -ray.d, cam_medium, cam_medium) : cam_medium;
  int nulls = 0;
  parent.medium = medium;
  // Russian roulette after the bounce that makes segment s (relative to the emitted power).
  float q_last = 1.0f;         // the last roulette's survival probability (a plane's q)
  bool after_scatter = false;  // the ray starts at a medium scattering event
  auto survive = [&](int segment) {
    q_last = 1.0f;
    if (segment <= params.rr_depth) return true;
    const float q = std::min(0.95f, max_component(beta) / beta0);
    q_last = q;
    if (!(rng.uniform() < q)) {
      ++c.rr_terminated;
      return false;
    }
    beta /= q;
    return true;
  };
  for (int s = 1; s <= max_store;) {
    if (medium >= 0) {
      const scene::HomogeneousMedium& med = scene.media()[size_t(medium)];
      scene::FreeFlightSample ff;
      if (med.heterogeneous()) {  // delta tracking: weight albedo at a scatter, 1 on a pass (grid_tracking.h)
        ++c.grid_flights;
        ff = scene::sample_free_flight_grid(med, ray.o, ray.d, found ? hit.t : kInfinity, rng);
      } else {
        const float u_channel = rng.uniform(), u_distance = rng.uniform();
        ff = scene::sample_free_flight(med, found ? hit.t : kInfinity, u_channel, u_distance);
      }
      if (beams) {
        const size_t before = beams->size();
        tracer_record_beam(scene, med, ray, ff.t, beta, s, medium, after_scatter, *beams, bc);
        if (beam_parents && beams->size() > before) beam_parents->push_back(parent);
      }
      const Vec3 seg_o = ray.o, seg_d = ray.d;  // the segment and its throughput (a plane's a0, w0, beta)
      const float seg_end = found ? hit.t : kInfinity;
      const Rgb beta_a = beta;
      // A grid medium's plane: from every segment (its own probability, photon_plane.h).
      if (planes && med.heterogeneous() && s < max_store)
        record_plane_grid(med, seg_o, seg_d, seg_end, beta_a, s + 1, medium, plane_rng, *planes, plc);
      beta *= ff.weight;  // Tr sigma_s / p(t) at a scatter, Tr / P(pass) otherwise (free_flight.h)
      if (is_black(beta)) return;
      if (ff.scattered) {
        const Vec3 p = ray.at(ff.t);
        if (!is_finite(beta) || !p.allFinite()) {
          ++c.nan_dropped;
          return;
        }
        if (params.store_photons) {
          out.push_back(MediumPhoton{p, ray.d, beta, int16_t(s), int16_t(medium), uint32_t(out.size())});
          ++c.stored;
        }
        if (parents) {
          parents->push_back(parent);
          parent = PhotonParent{};
          parent.kind = ParentKind::medium;
          parent.a = p;
          parent.w = ray.d;
          parent.medium = medium;
        }
        if (s == max_store) return;
        ray.o = p;
        ray.d = scene::HenyeyGreenstein(med.phase).sample(ray.d, rng.uniform2());  // weight rho_p / pdf = 1
        ray.tmin = 0.0f;
        ray.tmax = kInfinity;
        if (!survive(++s)) return;
        if (planes && !med.heterogeneous()) {
          const float u_plane_channel = plane_rng.uniform(), u_plane = plane_rng.uniform();
          record_plane(scene, med, seg_o, seg_d, seg_end, ray.d, beta_a, q_last, s, medium, u_plane_channel, u_plane,
                       *planes, plc);
        }
        after_scatter = true;
        found = scene.intersect(ray, hit);
        continue;
      }
    }
    if (!found) return;
    if (scene::is_index_matched(hit)) {  // not a vertex: switch media, keep direction and depth
      ++c.null_crossings;
      if (++nulls > VolpathTracer::kMaxNullCrossings) {
        ++c.null_limit;
        return;
      }
      medium = scene::medium_toward(hit, ray.d, medium, cam_medium);
      after_scatter = false;
      ray = scene.continue_ray(hit, ray.d);  // the one continuation rule (scene/scene.h)
      found = scene.trace_from(hit, ray.d, hit);
      continue;
    }
    if (!hit.bsdf) return;
    const Vec3 wi_local = hit.shading.to_local(-ray.d);
    if (!(hit.ng.dot(-ray.d) * wi_local.z() > 0.0f)) return;  // sidedness, as volpath
    ++c.surface_events;
    const scene::BsdfContext ctx{hit.uv, scene::TransportMode::importance};
    const float u_lobe = rng.uniform();
    const Vec2 u = rng.uniform2();
    const auto bs = hit.bsdf->sample(ctx, wi_local, u_lobe, u);
    if (!bs || is_black(bs->weight)) return;
    const Vec3 wo = hit.shading.to_world(bs->wo);
    if (!(hit.ng.dot(wo) * bs->wo.z() > 0.0f)) return;
    beta *= bs->weight;
    if (parents) {
      const int32_t chain = chains && bs->is_delta() ? extend_chain(parent, hit, *bs, u_lobe, ray.d, wo, *chains) : -1;
      parent = PhotonParent{};
      parent.kind = bs->is_delta() ? ParentKind::specular : ParentKind::surface;
      parent.chain = chain;
      parent.a = hit.p;
      parent.w = -ray.d;
      parent.ng = hit.ng;
      parent.shading = hit.shading;
      parent.uv = hit.uv;
      parent.bsdf = hit.bsdf;
    }
    medium = scene::medium_toward(hit, wo, medium, cam_medium);
    if (parents) parent.medium = medium;
    if (parent.chain >= 0) (*chains)[size_t(parent.chain)].steps.back().medium_out = medium;
    if (!survive(++s)) return;
    after_scatter = false;
    ray = scene.continue_ray(hit, wo);
    found = scene.trace_from(hit, wo, hit);
  }
}

}  // namespace

bool trace_medium_photons(const scene::Scene& scene, const PhotonTraceParams& params, const std::atomic<bool>* stop,
                          std::vector<MediumPhoton>& out, PhotonTraceCounters& counters,
                          std::vector<PhotonParent>* parents, std::vector<MediumBeam>* beams,
                          BeamTraceCounters* beam_counters, std::vector<PhotonParent>* beam_parents,
                          std::vector<MediumPlane>* planes, PlaneTraceCounters* plane_counters,
                          std::vector<gradients::PhotonChain>* chains) {
  if (!parents || !beams) beam_parents = nullptr;
  if (!parents) chains = nullptr;
  const int64_t chunks = (params.paths + kChunk - 1) / kChunk;
  std::vector<std::vector<MediumPhoton>> parts(static_cast<size_t>(chunks));
  std::vector<std::vector<PhotonParent>> parent_parts(parents ? static_cast<size_t>(chunks) : 0);
  std::vector<std::vector<MediumBeam>> beam_parts(beams ? static_cast<size_t>(chunks) : 0);
  std::vector<std::vector<PhotonParent>> beam_parent_parts(beam_parents ? static_cast<size_t>(chunks) : 0);
  std::vector<BeamTraceCounters> beam_chunk_counters(static_cast<size_t>(chunks));
  std::vector<std::vector<MediumPlane>> plane_parts(planes ? static_cast<size_t>(chunks) : 0);
  std::vector<PlaneTraceCounters> plane_chunk_counters(static_cast<size_t>(chunks));
  std::vector<std::vector<gradients::PhotonChain>> chain_parts(chains ? static_cast<size_t>(chunks) : 0);
  std::vector<PhotonTraceCounters> chunk_counters(static_cast<size_t>(chunks));
  std::vector<char> done(size_t(chunks), 0);
  core::parallel_for(
      chunks, params.threads,
      [&](int64_t k, int) {
        core::Rng rng(params.seed, (uint64_t(params.iteration) << 32) | 0x40000000ull | uint64_t(k));
        const int64_t n = std::min(kChunk, params.paths - k * kChunk);
        std::vector<pathspace::BidirVertex> scratch;
        std::vector<PhotonParent>* pp = parents ? &parent_parts[size_t(k)] : nullptr;
        std::vector<MediumBeam>* bp = beams ? &beam_parts[size_t(k)] : nullptr;
        std::vector<PhotonParent>* bpp = beam_parents ? &beam_parent_parts[size_t(k)] : nullptr;
        std::vector<MediumPlane>* plp = planes ? &plane_parts[size_t(k)] : nullptr;
        std::vector<gradients::PhotonChain>* cp = chains ? &chain_parts[size_t(k)] : nullptr;
        // The planes' distances D come from their own stream: the light paths are unchanged.
        core::Rng plane_rng(params.seed, (uint64_t(params.iteration) << 32) | 0x50000000ull | uint64_t(k));
        for (int64_t i = 0; i < n; ++i)
          trace_one(scene, params, rng, parts[size_t(k)], chunk_counters[size_t(k)], pp, scratch, bp,
                    beam_chunk_counters[size_t(k)], bpp, plp, plane_chunk_counters[size_t(k)], plane_rng, cp);
        done[size_t(k)] = 1;
      },
      stop);
  if (std::find(done.begin(), done.end(), 0) != done.end()) return false;
  size_t total = 0;
  for (const auto& p : parts) total += p.size();
  out.clear();
  out.reserve(total);
  if (parents) {
    parents->clear();
    parents->reserve(total);
  }
  if (beams) {
    size_t beam_total = 0;
    for (const auto& p : beam_parts) beam_total += p.size();
    beams->clear();
    beams->reserve(beam_total);
    if (beam_parents) {
      beam_parents->clear();
      beam_parents->reserve(beam_total);
    }
  }
  if (planes) planes->clear();
  if (chains) chains->clear();
  for (size_t k = 0; k < parts.size(); ++k) {
    const uint32_t offset = uint32_t(out.size());
    for (MediumPhoton& ph : parts[k]) ph.index += offset;  // chunk-local -> global
    out.insert(out.end(), parts[k].begin(), parts[k].end());
    if (chains) {  // chunk-local chain indices -> global
      const int32_t chain_offset = int32_t(chains->size());
      for (PhotonParent& pp : parent_parts[k])
        if (pp.chain >= 0) pp.chain += chain_offset;
      if (beam_parents)
        for (PhotonParent& pp : beam_parent_parts[k])
          if (pp.chain >= 0) pp.chain += chain_offset;
      chains->insert(chains->end(), std::make_move_iterator(chain_parts[k].begin()),
                     std::make_move_iterator(chain_parts[k].end()));
    }
    if (parents) parents->insert(parents->end(), parent_parts[k].begin(), parent_parts[k].end());
    if (beams) {
      const uint32_t beam_offset = uint32_t(beams->size());
      for (MediumBeam& b : beam_parts[k]) b.index += beam_offset;
      beams->insert(beams->end(), beam_parts[k].begin(), beam_parts[k].end());
      if (beam_parents) beam_parents->insert(beam_parents->end(), beam_parent_parts[k].begin(), beam_parent_parts[k].end());
      if (beam_counters) *beam_counters += beam_chunk_counters[k];
    }
    if (planes) {
      const uint32_t plane_offset = uint32_t(planes->size());
      for (MediumPlane& pl : plane_parts[k]) pl.index += plane_offset;
      planes->insert(planes->end(), plane_parts[k].begin(), plane_parts[k].end());
      if (plane_counters) *plane_counters += plane_chunk_counters[k];
    }
    counters += chunk_counters[k];
  }
  return true;
}

}  // namespace dp::integrators
