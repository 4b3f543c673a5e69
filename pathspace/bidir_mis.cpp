#include "pathspace/bidir_mis.h"

#include <cmath>

#include "pathspace/bidir_light.h"
#include "pathspace/bidir_media.h"

namespace dp::pathspace {

namespace {

// Dirac-derived densities are stored as 0 and cancel between strategies (bidir_vertex.h).
double remap(float pdf) { return pdf != 0.0f ? double(pdf) : 1.0; }

}  // namespace

ReversePdfs connection_reverse_pdfs(const scene::Scene& scene, const BidirVertex* light, int s,
                                    const BidirVertex* camera, int t, bool cos, const EdgeMedia* edge,
                                    bool free_flight) {
  ReversePdfs r;
  const BidirVertex& z = camera[t - 1];
  // Free-flight factors of the edges z_{t-1} z_{t-2} and y_{s-1} y_{s-2} toward the
  // predecessors (1 without media).
  const float z_back = free_flight ? z.ff_rev : 1.0f;
  if (s == 0) {
    // z_{t-1} acts as the light vertex: its density is light selection x area sampling,
    // z_{t-2}'s is the emission direction density.
    r.z[0] = light_pdf_pos(scene, z);
    if (t >= 2) r.z[1] = light_pdf_next(scene, z, camera[t - 2]) * z_back;
    return r;
  }
  const BidirVertex& y = light[s - 1];
  const float y_back = free_flight ? y.ff_rev : 1.0f;
  // The connection's factors: ending at z (light walk) and at y (camera walk).
  EdgeMedia traced;
  if (!edge && scene.caps().has_media) {
    traced = trace_edge(scene, z, y);
    edge = &traced;
  }
  const float to_z = edge && free_flight ? edge->to_a : 1.0f, to_y = edge && free_flight ? edge->to_b : 1.0f;
  const Vec3 yz = y.infinite() ? Vec3(-y.sp.ng) : Vec3((z.sp.p - y.sp.p).normalized());
  // z_{t-1} generated from y_{s-1} (light walk direction).
  r.z[0] = to_z * (s == 1 ? light_pdf_next(scene, y, z)
                          : solid_angle_to_area(scatter_pdf(scene, y, y.wi, yz, scene::TransportMode::importance), y,
                                                z, cos));
  // z_{t-2} generated from z_{t-1}, arriving from y_{s-1}.
  if (t >= 2)
    r.z[1] = z_back * solid_angle_to_area(scatter_pdf(scene, z, -yz, z.wi, scene::TransportMode::importance), z,
                                          camera[t - 2], cos);
  // y_{s-1} generated from z_{t-1} (camera walk direction).
  const float pdf_zy = t == 1 ? scene.camera().pdf_direction(-yz)
                              : scatter_pdf(scene, z, z.wi, -yz, scene::TransportMode::radiance);
  r.y[0] = to_y * solid_angle_to_area(pdf_zy, z, y, cos);
  // y_{s-2} generated from y_{s-1}, arriving from z_{t-1}.
  if (s >= 2)
    r.y[1] = y_back * solid_angle_to_area(scatter_pdf(scene, y, yz, y.wi, scene::TransportMode::radiance), y,
                                          light[s - 2], cos);
  return r;
}

ReversePdfs connection_reverse_pdfs(const scene::Scene& scene, const BidirVertex* light, int s,
                                    const BidirVertex* camera, int t, const MisConfig& config,
                                    const EdgeMedia* edge) {
  return connection_reverse_pdfs(scene, light, s, camera, t, config.fault != BidirFault::reverse_pdf_without_cosine,
                                 edge, config.fault != BidirFault::reverse_pdf_without_free_flight);
}

float mis_weight(const scene::Scene& scene, const BidirVertex* light, int s, const BidirVertex* camera, int t,
                 const MisConfig& config) {
  return mis_weight(light, s, camera, t, config, connection_reverse_pdfs(scene, light, s, camera, t, config));
}

float mis_weight(const BidirVertex* light, int s, const BidirVertex* camera, int t, const MisConfig& config,
                 const ReversePdfs& reverse) {
  const float* z_rev = reverse.z;
  const float* y_rev = reverse.y;
  const bool power = config.heuristic == MisHeuristic::power;
  auto h = [power](double r) { return power ? r * r : r; };
  double sum = 0.0;
  // Toward the camera: strategy (s + t - i, i) for i = t-1 .. 1 connects z_i (now a light
  // vertex) to z_{i-1}; impossible if either scattered through a Dirac lobe. The
  // connection endpoint z_{t-1} itself is a connection vertex here, never "delta".
  double r = 1.0;
  for (int i = t - 1; i > 0; --i) {
    const float rev = i == t - 1 ? z_rev[0] : i == t - 2 ? z_rev[1] : camera[i].pdf_rev;
    r *= h(remap(rev) / remap(camera[i].pdf_fwd));
    const bool delta_i = i == t - 1 ? false : camera[i].delta;
    if (delta_i || camera[i - 1].delta) continue;
    if (i == 1 && config.fault == BidirFault::mis_without_light_tracing) continue;
    // Light tracing (t = 1) from a light at infinity: nothing to project to the pinhole.
    if (i == 1 && camera[1].infinite() && config.fault != BidirFault::light_tracing_at_infinity) continue;
    sum += r;
  }
  // Toward the light: strategy (i, s + t - i) for i = s-1 .. 0 connects y_{i-1} to y_i
  // (now a camera vertex); i = 0 means the camera walk hits the light: impossible for a
  // delta-position light.
  r = 1.0;
  for (int i = s - 1; i >= 0; --i) {
    const float rev = i == s - 1 ? y_rev[0] : i == s - 2 ? y_rev[1] : light[i].pdf_rev;
    r *= h(remap(rev) / remap(light[i].pdf_fwd));
    const bool delta_i = i == s - 1 ? false : light[i].delta;
    const bool delta_prev = i > 0 ? light[i - 1].delta : light[0].is_delta_light();
    if (delta_i || delta_prev) continue;
    sum += r;
  }
  const double w = 1.0 / (1.0 + sum);
  return std::isfinite(w) ? float(w) : 0.0f;
}

}  // namespace dp::pathspace
