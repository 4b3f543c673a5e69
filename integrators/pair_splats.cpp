#include "integrators/pair_splats.h"

#include <cmath>

namespace dp::integrators {

void PairSplats::pair(int nb, int px, int py, const Rgbd& base, const Rgbd* off, double w, double w_base) {
  const int qx = px + kPairDx[nb], qy = py + kPairDy[nb];
  Rgbd g;
  if (off) {
    g = w * (*off - base);
    if (pair_primal) {
      add(px, py, 0, 0.25 * w * base);
      add(qx, qy, 0, 0.25 * w * *off);
    }
  } else {
    g = -w_base * base;
    if (pair_primal) add(px, py, 0, 0.25 * w_base * base);
  }
  // g estimates I_j - I_i; the buffers hold forward differences.
  if (kPairDx[nb] == 1) add(px, py, 2, g);
  else if (kPairDx[nb] == -1) add(qx, qy, 2, -g);
  else if (kPairDy[nb] == 1) add(px, py, 3, g);
  else add(qx, qy, 3, -g);
}

bool PairSplats::mis_pair(int nb, int px, int py, const Rgbd& base, double w_base, bool shifted, const Rgbd& off,
                          double w_off, double R, double beta, bool ignore_offset) {
  if (!shifted || off.isZero() || !(w_off > 0.0) || !(R > 0.0) || !std::isfinite(R)) {
    pair(nb, px, py, base, nullptr, 0.0, w_base);
    return false;
  }
  const double rb = beta == 1.0 ? R : beta == 2.0 ? R * R : std::pow(R, beta);
  const double w = ignore_offset ? w_base : 1.0 / (1.0 / w_base + rb / w_off);
  pair(nb, px, py, base, &off, w, w_base);
  return true;
}

void PairSplats::unpaired(int px, int py, const Rgbd& base, double w_base) {
  if (pair_primal) add(px, py, 0, 0.25 * w_base * base);
}

bool PairSplats::flush(gradients::GradientBuffers& buf, int px, int py) const {
  for (const PairSplat& a : adds)
    if (!a.v.isFinite().all()) {
      buf.add_samples(px, py, 1);
      return false;
    }
  for (const PairSplat& a : adds) {
    if (a.layer == 0) buf.add_primal(a.x, a.y, a.v);
    else if (a.layer == 1) buf.add_direct(a.x, a.y, a.v);
    else if (a.layer == 2) buf.add_dx(a.x, a.y, a.v);
    else buf.add_dy(a.x, a.y, a.v);
  }
  buf.add_samples(px, py, 1);
  return true;
}

}  // namespace dp::integrators
