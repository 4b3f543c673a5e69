// Per-sample physics of G-PT in homogeneous participating media (Kettunen et al. 2015 with
// the volumetric path space of Gruson et al. 2018, Sec. 3.1, Eqs. 2-4, and its G-PT
// extension, Sec. 6: copy the distance sampled on the base path). GptIntegrator runs it
// when Scene::caps().has_media; otherwise GptTracer runs unchanged.
//  * Base: one walk sampled as volpath (gpt_media_walk.h).
//  * Shift to each of the 4 neighbours (same sub-pixel offset, as gpt):
//     - x1 a medium vertex at distance t on the primary ray: x1' at t on the offset's
//       primary ray (Jacobian 1 in (raster, t)); fails if the offset ray reaches a surface
//       before t or is in another medium there;
//     - x1 a surface: x1' is the offset ray's own surface; x1 and x1' must be connectable
//       (no half-vector copy in media: glossy / specular first vertices fail);
//     - then x1' reconnects to the base's x2 (a medium vertex, a connectable surface, an
//       emitter or an escape direction) with the factor of gradients/volume_path_shift.h
//       and the transmittance of the reconnected edge (any surface but an index-matched
//       boundary blocks it); x2 onward are shared. NEE at x1' reconnects to the base's
//       light point (direction, for lights at infinity); NEE at x2 and later is the base's
//       with x2's new incoming direction.
//  * Densities for the symmetric MIS (gpt_splat.h, gradients/mis.h): every ratio
//    p_j(T x) |T'| / p_i(x) includes the free-flight densities of the changed edges (p(t)
//    at medium vertices, P(pass) at surfaces, per stretch between boundaries); a
//    technique's density is the direction's solid-angle density times its edge's
//    free-flight density (BSDF / phase sampling), or the light's (NEE, no free flight).
//    Russian roulette follows the base (Kettunen 2015, Sec. 5.3) and is left out of the
//    weights, which stay a partition of unity over the pair's four techniques.
// Directly visible emitters (1 segment) go to the direct layer and are never shifted.
#pragma once

#include <array>
#include <cstdint>
#include <vector>

#include "core/stats.h"
#include "gradients/gradient_buffers.h"
#include "gradients/pair_terms.h"
#include "integrators/gpt/gpt_media_walk.h"
#include "integrators/gpt/gpt_settings.h"

namespace dp::integrators {

// Why a shift in media stopped (counted as gpt.media.fail.<cause>).
enum class MediaShiftFail : uint8_t {
  none,
  not_connectable,          // x1, x1' or x2 glossy/specular (or a Dirac lobe sampled there)
  surface_before_distance,  // the offset's primary ray meets a surface before t (Gruson 2018, Fig. 3)
  other_medium,             // the offset's vertex or edge end lies in another medium
  miss,                     // the offset's primary ray escapes where the base hit a surface
  side_mismatch,            // the offset reaches x2 from the other side of its surface
  occluded,                 // the reconnected edge is blocked
  zero_contribution,        // inconsistent shading side, zero Jacobian
};
constexpr int kMediaShiftFailCount = 8;
const char* to_string(MediaShiftFail f);

struct GptMediaCounters {
  int64_t samples = 0, nan_dropped = 0;
  int64_t shifts = 0, shifts_outside = 0;
  int64_t distance_copies = 0, primary_surfaces = 0;                         // first-vertex shifts that succeeded
  int64_t reconnect_medium = 0, reconnect_surface = 0, reconnect_escape = 0;  // by x2's kind
  int64_t nee_reconnect = 0, nee_fail = 0;  // NEE at x1' reconnected to the base's light sample / not
  std::array<int64_t, kMediaShiftFailCount> fail{};
  GptMediaWalkCounters walk;
  void flush(core::Stats& stats) const;
};

// The offset of one shift: x1' and the prefix ratios at the changed vertices.
//   obc[k] = f_j(T x) |T'| / p_i(x) of the prefix x'_0..x'_k (RGB, base's densities)
//   cr[k]  = p_j(T x) |T'| / p_i(x) of the same prefix (the MIS density ratio)
struct MediaOffset {
  int alive = 0;  // 0: no offset; 2: x1' exists; 3: reconnected at x2 (x2 onward shared)
  bool has_x3 = false;
  MediaVertex x1;
  Rgbd obc[4];
  double cr[4] = {0, 0, 0, 0};
  double J = 1;   // reconnection factor x1' -> x2
  Vec3 d2{0, 0, 1};  // the offset's direction into x2
  bool nee1 = false;
  MediaLightSample light1;  // the NEE sample from x1'
  double J_light1 = 1;
  Rgb f2_light = Rgb::Zero();  // x2's scattering toward its light sample with the new incoming direction
  double spdf2_light = 0;
  Rgb emission2 = Rgb::Zero();
};

class GptMediaTracer {
 public:
  GptMediaTracer(const scene::Scene& scene, const GptSettings& settings, int max_depth);
  // One base sample in pixel (px, py) with its four offsets, splatted as GptTracer does.
  void sample(int px, int py, pathspace::SampleStream& stream, gradients::GradientBuffers& buf,
              GptMediaCounters& counters) const;
  // The shift of `base` by (dx, dy) pixels (public for the tests).
  void shift(const MediaPath& base, int dx, int dy, MediaOffset& out, GptMediaCounters& counters) const;
  // The concrete paths of the pair (base, offset; null: no offset), as gpt's PairTerms.
  void terms(const MediaPath& base, const MediaOffset* offset, std::vector<gradients::PairTerm>& out) const;

 private:
  bool shift_light(const MediaVertex& b1, const MediaVertex& o1, const MediaLightSample& bl, MediaLightSample& ol,
                   double& J) const;
  double light_density(const Vec3& from, const MediaVertex& light) const;
  const scene::Scene& m_scene;
  GptSettings m_settings;
  MediaWalkOptions m_walk;
};

}  // namespace dp::integrators
