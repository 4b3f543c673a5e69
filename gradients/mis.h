// Symmetric two-direction multiple importance sampling for gradient estimation.
// A pixel pair (i, j) samples the same pair of paths {x, T_ij(x)} four ways: pixel i by
// NEE or BSDF sampling (densities p_i,t(x)) and pixel j by NEE or BSDF sampling of the
// offset (densities p_j,t(T(x)) |T'(x)|, expressed in x's measure). The weight of the
// technique that actually produced x is the power heuristic over all four:
//   w = p_self^2 / sum_t (p_i,t(x)^2 + (p_j,t(T x) |T'|)^2)
// (Kettunen et al. 2015, Sec. 4, Eq. 7 symmetric weight w_ij = p_i / (p_i + p_j |T'|),
// generalized to the power heuristic over NEE/BSDF as in Veach 1997, Eq. 9.13; the same
// form is used by Manzi et al. 2014, Sec. 3.2, Eqs. 4-5). The weights of the four ways
// sum to one for every pair, so sum of weighted estimates from both pixels is unbiased
// for I_j - I_i (Lehtinen et al. 2013, Eq. 4). A failed shift drops the offset terms
// (the other pixel cannot produce the pair). Arguments are ratios to p_self (double:
// the products of many pdfs are never formed).
#pragma once

namespace dp::gradients {

// other_base = p_i,other(x) / p_self; offset_* = p_j,t(T x) |T'| / p_self.
inline double symmetric_power_weight(double other_base, double offset_same, double offset_other) {
  const double s = 1.0 + other_base * other_base + offset_same * offset_same + offset_other * offset_other;
  return 1.0 / s;
}

// Path reusing over a tile of pixels (Bauszat et al. 2017, Eq. 3 in the form of Eq. 7):
// the balance heuristic over every sampler of the tile -- each pixel m's two techniques
// (NEE, BSDF) -- for a concrete path x that pixel q's technique `self` sampled and the
// reuse function R shifted to the other pixels:
//   w_q,self(x) = p_q,self(x) / (p_q,self(x) + p_q,other(x) + sum_m sum_t p_m,t(R_qm x) |R'_qm|)
// with the sum over the pixels m != q whose shift produced this concrete path (a failed
// reuse has no sampler that could produce it and drops out; the caller must make "failed"
// mean the same for both techniques of a path, e.g. an occluded light sample as a failed
// NEE reuse when a blocked reconnection fails the BSDF one). The weight depends on x and
// its shifts only, so it is the same for every pixel x is reused in (constant over the
// tile). Arguments are ratios to p_q,self(x): other_base = p_q,other / p_self,
// offsets = sum over m of (p_m,self + p_m,other)(R x) |R'| / p_self.
inline double tile_balance_weight(double other_base, double offsets) { return 1.0 / (1.0 + other_base + offsets); }

}  // namespace dp::gradients
