// The concrete paths of a base walk and of its shifted offset, term by term: for every
// vertex x_k the NEE path (x_0..x_k, light sample) and the BSDF path ending at x_k (when
// the base or the offset vertex emits). Each term carries what a gradient estimator needs:
//   fb = f_i(x) / p(x)             the base path's unweighted Monte Carlo contribution
//   fo = f_j(T x) |T'(x)| / p(x)   the offset's, in the base's measure (0 without offset)
//   b_other = p_i,other(x) / p_self(x)       (the other strategy of the base, NEE <-> BSDF)
//   c = p_j,self(T x) |T'| / p_self(x), d = p_j,other(T x) |T'| / p_self(x)
//   jacobian = |T'(x)| of this concrete path (prefix factors times the NEE factor)
// with p_self the density of the strategy that produced x (Kettunen et al. 2015, Sec. 5.3:
// throughputs as f/p and pdfs as ratios to the base's, in double; Russian roulette follows
// the base). The strategy weights follow from the ratios: the base's power-heuristic weight
// among its own two strategies is 1 / (1 + b_other^2) (as the reference path tracer), the
// offset's c^2 / (c^2 + d^2), G-PT's symmetric weight gradients::symmetric_power_weight.
// Directly visible emitters (1 segment) are never terms (integrators add them apart).
#pragma once

#include <vector>

#include "core/math.h"
#include "gradients/shift.h"
#include "pathspace/path.h"
#include "scene/scene.h"

namespace dp::gradients {

struct PairTerm {
  int segments = 0;  // path length: NEE at x_k has k + 1 segments, a BSDF path ending at x_k has k
  bool nee = false;
  Rgbd fb = Rgbd::Zero(), fo = Rgbd::Zero();
  double b_other = 0, c = 0, d = 0;
  double jacobian = 1;
  bool has_offset = false;  // the shift produced this concrete path (fo may still be 0: not visible)
  // NEE paths: the light sample is visible from the base's / the offset's vertex (BSDF
  // paths: true; a BSDF path exists only where its last segment is unoccluded).
  bool base_visible = true, offset_visible = true;

  double base_strategy_weight() const { return 1.0 / (1.0 + b_other * b_other); }
  double offset_strategy_weight() const { return c > 0.0 ? c * c / (c * c + d * d) : 0.0; }
};

// Scratch memory for one thread (reused from sample to sample).
class PairTerms {
 public:
  // Prepares the base walk (throughputs; lazily its light densities); `nee`: the walk did
  // next-event estimation. `scene` and `base` must outlive the calls to terms().
  void set_base(const scene::Scene& scene, bool nee, const pathspace::Path& base);
  // Every concrete path of the base (and of `offset`, null = no offset, e.g. a neighbour
  // outside the image) with at least `min_segments` segments and a nonzero base or
  // offset value. The vector is reused by the next call.
  // `keep_zero`: also the concrete paths whose base and offset values are both zero, with
  // their densities (c, d): a balance heuristic over many pixels (path reusing, Bauszat
  // et al. 2017, Eq. 3) counts a sampler's density even where its own path carries no light.
  const std::vector<PairTerm>& terms(const ShiftResult* offset, int min_segments, bool keep_zero = false);

 private:
  void prepare_offset(const ShiftResult* offset);
  bool nee_at(const pathspace::Vertex& v) const;
  double base_bsdf_other(int k);  // b_other of the BSDF path ending at x_k, cached per base
  const scene::Scene* m_scene = nullptr;
  bool m_nee = true;
  const pathspace::Path* m_base = nullptr;
  std::vector<Rgbd> m_beta, m_beta_o;
  std::vector<double> m_ratio, m_jprefix, m_b_other_bsdf;
  std::vector<PairTerm> m_terms;
};

}  // namespace dp::gradients
