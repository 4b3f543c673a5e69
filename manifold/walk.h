// Manifold walks (Jakob & Marschner 2012, Sec. 5): move the end x_n of a specular chain
// to a target position on its surface while every interior constraint keeps its target
// (ideal specular, or a prescribed half vector). Newton steps in the tangent plane of
// the end: the tangent map gives the move of x_1, and the chain is re-traced from the
// pinned start through the new x_1, reflecting/refracting about the prescribed local
// microfacet normals. A step is rejected (and halved) if a ray misses or hits another
// object than the chain vertex, if refraction fails (TIR), or if the distance to the
// target grew; after an accepted step the step size doubles (at most 1).
//
// Convergence: |x_n - target| < tolerance * scale (the distance in x_n's tangent plane:
// a float target off the surface by round-off stays reachable), scale = max(max_k |target_k|,
// |target - x_{n-1}|) (ALGORITHMS.md: distance / max|target| < 1e-7; the segment
// length guards targets near the origin). Iterations count every re-trace attempt.
#pragma once

#include "manifold/chain.h"
#include "manifold/walk_stats.h"
#include "scene/scene.h"

namespace dp::manifold {

struct WalkSettings {
  int max_iterations = 20;         // J&M 2012 / Mitsuba 0.6 (G-PM uses 5)
  double tolerance = 1e-7;         // relative end-point distance (see header)
  double min_step = 1.0 / 1024;    // step halving below this fails (step_too_small)
  double reverse_tolerance = 1e-5; // reversibility: relative to the scene radius
  bool check_reversible = false;   // walk back after every successful walk (--paranoid)
  // The input chain already meets its constraints in double (just re-traced, as by
  // walk_exact): skip walk()'s own initial re-trace (one of ~6 per walk).
  bool exact_input = false;
  // Also converged once |x_n - target| < accept_distance (absolute, world units): the
  // relaxed acceptance of Gruson et al. 2018, Sec. 6 (the end need only land inside a
  // density-estimation kernel). 0: off.
  double accept_distance = 0;
};

struct WalkResult {
  WalkStatus status = WalkStatus::invalid_input;
  Chain chain;         // the walked chain (valid when status == ok)
  int iterations = 0;  // re-trace attempts
  double distance = 0; // final |x_n - target| in x_n's tangent plane
  bool ok() const { return status == WalkStatus::ok; }
};

// Re-traces `base` from its pinned start through the point x1 (for Pin::direction:
// along start_dir through x1), reflecting/refracting at every interior vertex about the
// microfacet normal given by the vertex's target in its new local frame, until the end's
// surface (or the virtual plane of a Chain::end_plane end). `out` receives the new chain (types, etas, targets, shapes kept).
WalkStatus retrace(const scene::Scene& scene, const Chain& base, const Vec3d& x1, Chain& out);

// Scatters w_a (unit, pointing from the vertex toward where the light came from) about
// the microfacet normal encoded by the vertex's target, in its local frame: reflection,
// or refraction with the vertex's eta (sides from the geometric normal). Fails on TIR,
// index-matched refraction, grazing directions, or a result on the wrong side.
WalkStatus scatter(const ChainVertex& v, const Vec3d& w_a, Vec3d& w_b);

WalkResult walk(const scene::Scene& scene, const Chain& chain, const Vec3d& target, const WalkSettings& settings,
                WalkStats* stats = nullptr);

// A walk from the chain's exact form: re-traces `chain` (start x_0 pinned .. end x_n) in
// double from its end x_n through `x_next` (its x_{n-1} in the path's float position: the
// direction a path sampled at x_n, the parameterization's coordinate), so the re-traced
// hit replaces the start (`exact`, every constraint to double precision), then walks that
// chain's end to `target` (c pinned). A float path meets the specular constraints only to
// ~1e-6, which near caustic folds perturbs the generalized geometry term by up to ~1e-3.
// stats->traces counts the re-trace; stats records a failed re-trace as a walk failure.
WalkStatus walk_exact(const scene::Scene& scene, const Chain& chain, const Vec3d& x_next, const Vec3d& target,
                      const WalkSettings& settings, Chain& exact, WalkResult& w, WalkStats& stats);

// Walks `walked` back to the end of `original` and requires every vertex to come back
// within settings.reverse_tolerance * scene radius.
WalkStatus check_reversible(const scene::Scene& scene, const Chain& original, const Chain& walked,
                            const WalkSettings& settings, WalkStats* stats = nullptr);

}  // namespace dp::manifold
