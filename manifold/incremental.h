// Incremental manifold walk (Manzi et al. 2014, Sec. 3.4): after the offset's first
// connectable vertex y_0 = x_b moved to y~_0, vertices y_1, y_2, ... are examined one at
// a time in ascending order; a pluggable decision (which must not look at y_i itself,
// only at y_{i-1} / y~_{i-1}) declares y_i specular. A declared vertex is moved by a
// manifold walk on (y~_{i-1}, y_i, y_{i+1}) that keeps its half vector h_i (computed on
// the base triple) with y_{i+1} pinned; the first vertex not declared, y_k, is where the
// offset reconnects (y~_i = y_i for i >= k). Declaring a diffuse vertex specular makes
// the near-singular G(y~_0 <-> y~_1) cancel against the Jacobian (Manzi 2014, Sec. 3.4,
// via Kaplanyan et al. 2014's half-vector parameterization).
//
// Jacobian (area measure of y_1..y_{k-1}, ends y_0 -> y~_0 and y_k fixed): the step
// equations h_i(y~_{i-1}, y~_i, y_{i+1}) = h_i(y_{i-1}, y_i, y_{i+1}) differentiate to
//   a~_i dy~_{i-1} + b~_i dy~_i = a_i dy_{i-1} + b_i dy_i + (c_i - c~_i) dy_{i+1},
// so |dy~/dy| = |det R| / prod |det b~_i| with R block tridiagonal (diagonal b_i,
// sub-diagonal a_i, super-diagonal c_i - c~_i), det R by block LU. This equals Manzi's
// per-step product prod |det b_i| / |det b~_i| only when c~_i = c_i; we use the exact form.
#pragma once

#include <functional>
#include <vector>

#include "manifold/walk.h"

namespace dp::manifold {

// decide(i, base y_{i-1}, offset y~_{i-1}): declare base vertex y_i specular?
using SpecularDecision = std::function<bool(int i, const ChainVertex& base_prev, const ChainVertex& offset_prev)>;

struct IncrementalResult {
  WalkStatus status = WalkStatus::invalid_input;
  std::vector<ChainVertex> offset;  // y~_0 .. y~_m
  int reconnect = -1;               // k: first vertex kept (offset rejoins the base)
  double jacobian = 1;              // |d y~_{1..k-1} / d y_{1..k-1}| (1 if k = 1)
  double per_step_product = 1;      // Manzi's prod |det b_i| / |det b~_i| (diagnostic)
  bool ok() const { return status == WalkStatus::ok; }
};

// base: y_0 .. y_m (y_m may be a point without surface, e.g. a point light); every
// vertex that can be declared must have a surface and its Interaction set. new_start:
// y~_0 on y_0's surface (local frame filled, e.g. by local_frame()).
IncrementalResult incremental_walk(const scene::Scene& scene, const std::vector<ChainVertex>& base,
                                   const ChainVertex& new_start, const SpecularDecision& decide,
                                   const WalkSettings& settings, WalkStats* stats = nullptr);

}  // namespace dp::manifold
