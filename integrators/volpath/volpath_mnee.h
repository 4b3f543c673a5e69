// Manifold next-event estimation for volpath (Hanika, Droske and Fascione 2015, "Manifold
// next event estimation"), combined with volpath's BSDF/phase sampling by multiple
// importance sampling, so that light seen only through refractive surfaces -- a caustic on
// a floor, a volumetric caustic in fog behind a glass ball -- is found by light sampling
// and not only by the rare paths that refract onto a small light.
//
// The strategy. At a non-specular vertex x (a medium vertex or a surface vertex with a
// non-Dirac BSDF) NEE samples a light point y with area density p_L(y) (emitter pmf times
// the solid-angle density of Emitter::sample_direct from x, times |cos_y| / |y - x|^2).
// If the straight segment x -> y is blocked only by refractive boundaries (smooth
// dielectrics: purely Dirac BSDFs with a transmission lobe; index-matched boundaries are
// passed), their count m (1 <= m <= mnee_max_chain and the depth budget) fixes the chain
// x, s_1 .. s_m, y. The seed refracts the ray x -> y at the first m boundaries it meets
// and ends on the plane through y tangent to the light; manifold::walk (Jakob & Marschner
// 2012, Sec. 5) then moves its end onto y, keeping x pinned and every s_i a refraction.
// Seeds (volpath_mnee_scan.cpp): a scan of mnee_scan directions across the first
// refracting shape, in the plane of x, y and the shape's centre (a ball lens has up to
// three solutions inside its caustic, all in that plane), each carried through the chain to
// the light's plane; every sign change of its miss there seeds a walk, and so does a
// near-zero minimum (two solutions closer than the scan, at a caustic fold). With
// mnee_scan 0: the straight direction and mnee_seeds - 1 fixed directions across the
// shape. With mnee_shapes, each purely specular shape S (at most four) adds two families
// of its own: one reflection off S (seeded where S's bounding sphere's normal bisects the
// directions to x and y), and two refractions through S where the straight segment misses
// it (light that a ball bends out of its shadow; seeded as the straight family).
// The distinct solutions found form a set S(x, y), a deterministic function of x and y
// (possibly empty), so MNEE is a sampling technique over the paths it can return, each of
// density p_L(y); the NEE side adds every one.
//
// Its estimate, with the Dirac constraints integrated out (Jakob & Marschner 2012,
// Sec. 4.3, the generalized geometry term),
//   F(X) = f_x(w_0) prod_i [f_i |cos_i|] Tr(x .. y) L_e(y, -w_m) D(x -> y),
//   D = d w_0 / dA(y)  (manifold::generalized_geometry without the cosine at x),
// f_x the BSDF times |cos| (surface) or the phase function (medium; sigma_s is in the
// path throughput already), f_i |cos_i| = weight * pdf of the Dirac transmission lobe at
// s_i (radiance mode, as volpath samples it), Tr over every segment (index-matched
// boundaries switch media; ratio tracking in grids), so the NEE side adds
//   beta F(X) / p_L(y) * w_L,   w_L = p_L^2 / (p_L^2 + p_B^2),
// with p_B(X) = p_x(w_0) prod_i P_i D the area density at y of BSDF/phase sampling
// reaching y through the same chain (p_x the BSDF or phase density of w_0, P_i the
// selection probability of each transmission lobe).
//
// The BSDF side. A path that leaves a non-specular vertex x, refracts at s_1 .. s_m and
// hits an area light at y is weighted w_B = p_B^2 / (p_B^2 + p_L^2) if S(x, y) holds that
// very path (its vertices within 1e-3 scene radii), and 1 otherwise -- MNEE cannot
// produce it (a missed or different solution, a reflection in the chain, TIR). Both
// weights are computed from the same solution and its p_L, p_B, so they sum to one on every
// path MNEE can return: the combination is unbiased (Veach 1997, Sec. 9.2), including
// where MNEE misses solutions (near caustic folds), at the cost of variance only.
//
// Light tracing (setting light_tracing; volpath_light.cpp) adds a third technique: a light
// path light -> chain -> x joined to the camera or to the camera-path vertex before x. Its
// density p_T, in the units of p_L and p_B (over the camera path's density of x), joins
// both weights: w = p^2 / (p_L^2 + p_B^2 + p_T^2).
//
// Scope: finite area lights (point, spot and directional lights and environments are left
// to plain NEE), scenes with media (volpath's media variant; the variant without media is
// `path`'s algorithm). Counters `volpath.mnee.*`.
#pragma once

#include <array>

#include "core/math.h"
#include "scene/bsdf/bsdf.h"
#include "scene/emitters/emitter.h"
#include "scene/surface.h"

namespace dp::integrators {

// A surface MNEE refracts through: a smooth dielectric (purely Dirac, with transmission).
inline bool mnee_refracts(const scene::SurfaceHit& h) {
  return h.bsdf && h.bsdf->is_purely_delta() && (h.bsdf->lobes() & scene::kDeltaTransmission) != 0;
}

// The longest chain MNEE solves (VolpathSettings::mnee_max_chain is at most this).
constexpr int kMaxMneeChain = 8;

// The non-specular vertex x an MNEE connection starts from.
struct MneeAnchor {
  bool surface = false;
  scene::SurfaceHit hit;   // surface: the vertex
  Vec3 wi_local{0, 0, 1};  // surface: toward the previous vertex, shading frame
  Vec3 p{0, 0, 0};         // medium: the point
  Vec3 d_in{0, 0, 1};      // medium: the direction the path arrived along
  int medium = -1;         // the medium the path arrived in (medium: the point's)
  int depth = 0;           // segments up to x (volpath's depth at the vertex)
  bool lt = false;          // light tracing can make its paths (a camera-path vertex precedes x)
  const Vec3& position() const { return surface ? hit.p : p; }
  static MneeAnchor at_surface(const scene::SurfaceHit& hit, const Vec3& wi_local, int medium, int depth) {
    MneeAnchor x;
    x.surface = true;
    x.hit = hit;
    x.wi_local = wi_local;
    x.medium = medium;
    x.depth = depth;
    return x;
  }
  static MneeAnchor in_medium(const Vec3& p, const Vec3& d_in, int medium, int depth) {
    MneeAnchor x;
    x.p = p;
    x.d_in = d_in;
    x.medium = medium;
    x.depth = depth;
    return x;
  }
};

// What NEE at a vertex tells MNEE: the light point it sampled, and whether the straight
// shadow ray may have been blocked by a refractive surface (false: plain NEE's case).
struct NeeProbe {
  bool area_light = false;  // a finite, non-Dirac light point was sampled
  Vec3 y{0, 0, 0}, n{0, 0, 1};
  bool try_chain = false;
};

// Records NEE's light sample for MNEE when it is a point of an area light, whichever side
// of it the vertex sees: a chain may turn around (a reflection off a ball below a light
// facing down lights the ceiling behind it). try_chain stays true until NEE's shadow ray
// says otherwise; NEE returns before tracing one when the straight direction carries
// nothing (the light's back, a zero BSDF or phase value), and then MNEE traces it.
inline void set_probe(NeeProbe& probe, const scene::DirectSample& ds) {
  if (!ds.delta && std::isfinite(ds.dist) && ds.pdf_area > 0.0f) probe = NeeProbe{true, ds.p, ds.n, true};
}

// The most seeds (hence solutions) per connection (VolpathSettings::mnee_seeds).
constexpr int kMaxMneeSeeds = 9;
// The most directions one scan of seeds traces (VolpathSettings::mnee_scan), and the most
// seeds it returns (volpath_mnee_scan.cpp).
constexpr int kMaxMneeScan = 64;
constexpr int kMaxMneeScanSeeds = 16;
struct MneeSeeds {
  int count = 0;
  std::array<Vec3, kMaxMneeScanSeeds> d{};
};
// The most specular shapes MNEE tries a reflection off (more: no reflection chains).
constexpr int kMaxMneeShapes = 4;
// The most distinct solutions one connection keeps (further ones are dropped).
constexpr int kMaxMneeSolutions = 16;

// One MNEE solution.
struct MneeConnection {
  bool ok = false;
  Rgb value = Rgb::Zero();  // F(X) / p_L(y) (before the MIS weight)
  double p_light = 0;       // p_L(y), area measure
  double p_bsdf = 0;        // p_B(X), area measure
  double D = 0;             // d w_0 / dA(y)
  double p_trace = 0;       // x.lt: light tracing's density without the camera's of x (0: none)
  Vec3d s1{0, 0, 0};        // s_1 in double (the walked chain's)
  int m = 0;                  // Dirac vertices
  uint32_t reflect_mask = 0;  // bit i: s_{i+1} reflects (else it refracts)
  std::array<Vec3, kMaxMneeChain> verts{};  // s_1 .. s_m
};

// The power heuristic over MNEE's three techniques, for the one of density a:
// a^2 / (a^2 + b^2 + c^2) (c = 0 where light tracing cannot make the path).
inline double mnee_mis(double a, double b, double c) {
  const double a2 = a * a, sum = a2 + b * b + c * c;
  return sum > 0.0 ? a2 / sum : 0.0;
}

// Light tracing's density of solution X over the camera path's density of its anchor
// (p_L's units; 0 without a camera density).
inline double trace_over(const MneeConnection& X, double cam_pdf) { return cam_pdf > 0.0 ? X.p_trace / cam_pdf : 0.0; }

// The distinct solutions S(x, y) that the seeds reach.
struct MneeSolutions {
  int count = 0;
  std::array<MneeConnection, kMaxMneeSolutions> x{};
};

}  // namespace dp::integrators
