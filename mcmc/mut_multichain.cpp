#include "mcmc/mut_multichain.h"

#include <cmath>

#include "mcmc/perturb_chain.h"

namespace dp::mcmc {

using pathspace::BidirKind;

MultiChainPerturbation::MultiChainPerturbation(const scene::Scene& scene, double r1, double r2)
    : m_scene(scene), m_r1(r1), m_r2(r2), m_theta1(1e-4 * kPiD / 180.0), m_theta2(0.1 * kPiD / 180.0) {}

std::vector<int> MultiChainPerturbation::smooth_ends(const PathState& x) const {
  std::vector<int> ends;
  int c = first_smooth_from_camera(x);
  while (c >= 1) {
    if (x.v[size_t(c)].kind != BidirKind::surface) return {};
    ends.push_back(c);
    if (!x.v[size_t(c - 1)].delta) break;  // x_{c-1} smooth: the connection (c-1, c)
    c = c - 1;
    while (c >= 0 && x.v[size_t(c)].delta) --c;  // through the next chain
  }
  if (c < 1 || ends.size() < 2) return {};
  return ends;
}

bool MultiChainPerturbation::suitable(const PathState& x) const { return !smooth_ends(x).empty(); }

ProposalStatus MultiChainPerturbation::sample(const PathState& x, PathState& y, MutationRecord& rec, core::Rng& rng,
                                              PathSides& sides) const {
  const std::vector<int> ends = smooth_ends(x);
  const int K = x.depth(), c = ends.back();
  rec.l = c - 1;
  Vec2 raster;
  if (!offset_raster(m_scene, x.raster, m_r1, m_r2, rng, raster)) return ProposalStatus::off_image;
  y.v = x.v;
  Vec3 w = m_scene.camera().generate_ray(raster).d;
  int from = K;
  for (size_t k = 0; k < ends.size(); ++k) {
    const ProposalStatus st = retrace_chain(m_scene, x, y.v, from, ends[k], w, scene::TransportMode::radiance);
    if (st != ProposalStatus::ok) return st;
    from = ends[k];
    if (k + 1 == ends.size()) break;
    // Turn x's direction onward from this smooth vertex by a log-uniform angle.
    const double theta = m_theta2 * std::exp(-std::log(m_theta2 / m_theta1) * rng.uniform_double());
    const double phi = 2.0 * kPiD * rng.uniform_double();
    w = turn_direction(direction_between(x.v[size_t(from)], x.v[size_t(from - 1)]), std::cos(theta), phi);
  }
  return finish_proposal(m_scene, y, c, sides);
}

double MultiChainPerturbation::ratio(const PathState& x, const PathState& y, const MutationRecord& rec) const {
  const int c = rec.l + 1, K = x.depth();
  const std::vector<int> ends = smooth_ends(x);
  auto density = [&](const PathState& s) {
    double d = dirac_chain_prob(s, c, K, scene::TransportMode::radiance);
    for (size_t k = 0; k + 1 < ends.size(); ++k) {
      const int i = ends[k];
      const pathspace::BidirVertex& v = s.v[size_t(i)];
      d *= double(pathspace::bsdf_pdf(v, direction_between(v, s.v[size_t(i + 1)]),
                                      direction_between(v, s.v[size_t(i - 1)]), scene::TransportMode::radiance));
    }
    return d;
  };
  const double num = x.inv_c[size_t(c)] * density(y), den = y.inv_c[size_t(c)] * density(x);
  return den > 0.0 ? num / den : 0.0;
}

}  // namespace dp::mcmc
