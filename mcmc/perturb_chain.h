// What the perturbations share (Veach 1997, Sec. 11.4.3; Mitsuba 0.6's mut_lens,
// mut_caustic): re-tracing a path's Dirac chain from a moved start with the path's own
// lobes, and the probabilities those lobes had in a walk.
#pragma once

#include "mcmc/mutator.h"

namespace dp::mcmc {

// Places new vertices in `yv` (a copy of x.v) at indices from + step, from + 2 step, ..,
// end (step = +1 or -1): starting at yv[from] (placed already: the pinhole, a light
// point or a surface vertex) along world direction w, each vertex where x took a Dirac
// lobe is followed with that lobe (`mode`: radiance toward the light, importance toward
// the camera), and the vertex at `end` must be one with a smooth component (delta false).
// ok, walk_ended (a miss, a sidedness violation) or configuration (a Dirac lobe the new
// surface cannot produce, a smooth end that is purely Dirac, no material).
ProposalStatus retrace_chain(const scene::Scene& scene, const PathState& x, std::vector<pathspace::BidirVertex>& yv,
                             int from, int end, const Vec3& w, scene::TransportMode mode);

// The product of the lobe probabilities of the Dirac vertices strictly between indices a
// and b of s, as a walk in `mode` chose them (radiance: arriving from the higher index,
// importance: from the lower): the factor by which a walk's density of the chain exceeds
// a deterministic re-trace's. 0 if a lobe cannot be reproduced.
double dirac_chain_prob(const PathState& s, int a, int b, scene::TransportMode mode);

// The first vertex below the pinhole, walking toward the light over Dirac vertices: the
// lens perturbation's smooth end (x_{K-1} itself when it is smooth).
int first_smooth_from_camera(const PathState& x);

// The raster position moved by r (cos phi, sin phi), r log-uniform on [r1, r2] and phi
// uniform (Veach's lens offset; symmetric); false if it leaves the image.
bool offset_raster(const scene::Scene& scene, const Vec2& raster, double r1, double r2, core::Rng& rng, Vec2& out);

// Unit direction at angle theta (cos given) and azimuth phi about the unit direction w.
Vec3 turn_direction(const Vec3& w, double cos_theta, double phi);

// The end of a perturbation: evaluates y (path_state.h), and requires strategy s to give
// a value and its connection edge to be unoccluded: ok, nonfinite, zero or occluded.
ProposalStatus finish_proposal(const scene::Scene& scene, PathState& y, int s, PathSides& sides);

// Whether strategy s's connection edge of y (evaluated) is unoccluded.
bool connection_visible(const scene::Scene& scene, const PathState& y, int s, PathSides& sides);

}  // namespace dp::mcmc
