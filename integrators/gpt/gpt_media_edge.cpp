#include "integrators/gpt/gpt_media_edge.h"

#include "pathspace/bidir_media.h"  // kMaxEdgeCrossings
#include "scene/media/free_flight.h"
#include "scene/media/medium_interface.h"

namespace dp::integrators {

namespace {

// One sub-segment of length `len` in `medium`: Tr and the free-flight factor.
void gpt_media_stretch(const scene::Scene& scene, int medium, float len, bool at_medium_vertex, MediaEdge& e) {
  if (medium < 0) return;
  const scene::HomogeneousMedium& m = scene.media()[size_t(medium)];
  e.tr *= scene::transmittance(m, len);
  e.ff *= double(at_medium_vertex ? scene::free_flight_pdf(m, len) : scene::free_flight_pass_probability(m, len));
}

}  // namespace

MediaEdge trace_media_edge(const scene::Scene& scene, const EdgeStart& start, const Vec3& d, float len, int medium,
                           bool to_medium_vertex) {
  MediaEdge e;
  const Vec3 origin = start.surface ? start.surface->p : start.p;
  const bool finite = len < kInfinity;
  const Vec3 target = origin + (finite ? len : 0.0f) * d;
  // Hits within the epsilon of a surface target are the target itself.
  const float guard = finite && !to_medium_vertex ? 2.0f * scene::Scene::epsilon_at(target) : 0.0f;
  scene::SurfaceHit h, crossing;
  const scene::SurfaceHit* from = start.surface;
  Vec3 seg_o = origin;
  for (;;) {
    float remaining = finite ? (target - seg_o).dot(d) : kInfinity;
    bool found;
    if (from) {
      found = scene.trace_from(*from, d, h);
    } else {
      Ray r;
      r.o = seg_o;
      r.d = d;
      r.tmin = 0.0f;
      found = scene.intersect(r, h);
    }
    if (found && finite && !(h.t < remaining - guard)) found = false;
    if (!found) {
      gpt_media_stretch(scene, medium, finite ? std::max(remaining, 0.0f) : kInfinity, to_medium_vertex, e);
      e.end_medium = medium;
      return e;
    }
    if (!scene::is_index_matched(h) || ++e.crossings > pathspace::kMaxEdgeCrossings) {
      e.blocked = true;
      return e;
    }
    gpt_media_stretch(scene, medium, h.t, false, e);
    medium = scene::medium_toward(h, d, medium, scene.camera_medium());
    seg_o = h.p;
    // trace_from may write its result into its argument: keep the crossing in a copy.
    crossing = h;
    from = &crossing;
  }
}

MediaEdge trace_primary(const scene::Scene& scene, const Ray& ray, float t, scene::SurfaceHit& hit) {
  MediaEdge e;
  int medium = scene.camera_medium();
  const bool to_medium = t >= 0.0f;
  scene::SurfaceHit crossing;
  bool from_surface = false;
  Vec3 seg_o = ray.o;
  for (;;) {
    const bool found = from_surface ? scene.trace_from(crossing, ray.d, hit) : scene.intersect(ray, hit);
    const float travelled = (seg_o - ray.o).norm();
    if (to_medium && !(found && travelled + hit.t < t)) {  // the vertex lies in this stretch
      if (medium < 0) {
        e.blocked = true;
        return e;
      }
      gpt_media_stretch(scene, medium, std::max(t - travelled, 0.0f), true, e);
      e.end_medium = medium;
      return e;
    }
    if (!found) {  // a surface end that escaped
      e.blocked = true;
      return e;
    }
    if (!scene::is_index_matched(hit)) {
      if (to_medium) {
        e.blocked = true;  // a surface before the copied distance (Gruson 2018, Fig. 3)
        return e;
      }
      gpt_media_stretch(scene, medium, hit.t, false, e);
      e.end_medium = medium;
      return e;
    }
    if (++e.crossings > pathspace::kMaxEdgeCrossings) {
      e.blocked = true;
      return e;
    }
    gpt_media_stretch(scene, medium, hit.t, false, e);
    medium = scene::medium_toward(hit, ray.d, medium, scene.camera_medium());
    seg_o = hit.p;
    crossing = hit;
    from_surface = true;
  }
}

}  // namespace dp::integrators
