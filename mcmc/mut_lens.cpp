#include "mcmc/mut_lens.h"

#include <cmath>

#include "mcmc/perturb_chain.h"

namespace dp::mcmc {

using pathspace::BidirKind;

LensPerturbation::LensPerturbation(const scene::Scene& scene, const LensSettings& settings)
    : m_scene(scene),
      m_r1(settings.r1),
      m_r2(std::sqrt(settings.area_fraction * double(scene.camera().width()) * double(scene.camera().height()) / kPiD)) {
  if (m_r2 < m_r1) m_r2 = m_r1;  // tiny images: a fixed radius
}

bool LensPerturbation::suitable(const PathState& x) const {
  const int c = first_smooth_from_camera(x);
  return c >= 1 && x.v[size_t(c)].kind == BidirKind::surface && !x.v[size_t(c - 1)].delta;
}

ProposalStatus LensPerturbation::sample(const PathState& x, PathState& y, MutationRecord& rec, core::Rng& rng,
                                        PathSides& sides) const {
  const int K = x.depth(), c = first_smooth_from_camera(x);
  rec.l = c - 1;
  Vec2 raster;
  if (!offset_raster(m_scene, x.raster, m_r1, m_r2, rng, raster)) return ProposalStatus::off_image;
  const auto& cam = m_scene.camera();
  y.v = x.v;
  const ProposalStatus st =
      retrace_chain(m_scene, x, y.v, K, c, cam.generate_ray(raster).d, scene::TransportMode::radiance);
  if (st != ProposalStatus::ok) return st;
  return finish_proposal(m_scene, y, c, sides);
}

double LensPerturbation::ratio(const PathState& x, const PathState& y, const MutationRecord& rec) const {
  const int c = rec.l + 1, K = x.depth();
  const double px = dirac_chain_prob(x, c, K, scene::TransportMode::radiance);
  const double py = dirac_chain_prob(y, c, K, scene::TransportMode::radiance);
  const double num = x.inv_c[size_t(c)] * py, den = y.inv_c[size_t(c)] * px;
  return den > 0.0 ? num / den : 0.0;
}

}  // namespace dp::mcmc
