#include "mcmc/mut_caustic.h"

#include <algorithm>
#include <cmath>

#include "mcmc/perturb_chain.h"
#include "pathspace/bidir_light.h"

namespace dp::mcmc {

using pathspace::BidirKind;
using pathspace::BidirVertex;

namespace {

double angle_pdf(double theta, double t1, double t2) {
  if (!(theta >= t1 && theta <= t2) || !(t2 > t1)) return 0.0;
  return 1.0 / (2.0 * kPiD * std::log(t2 / t1) * theta * std::sin(theta));
}

// The light walk's solid-angle density of leaving x_l toward x_{l+1}.
double leave_density(const PathState& s, int l) {
  const BidirVertex& v = s.v[size_t(l)];
  const Vec3 wo = direction_between(v, s.v[size_t(l + 1)]);
  if (v.kind == BidirKind::light) return double(pathspace::light_pdf_dir(v, wo));
  return double(pathspace::bsdf_pdf(v, direction_between(v, s.v[size_t(l - 1)]), wo, scene::TransportMode::importance));
}

}  // namespace

CausticPerturbation::CausticPerturbation(const scene::Scene& scene, double r1, double r2)
    : m_scene(scene), m_r1(r1), m_r2(r2) {
  const scene::CameraDesc& d = scene.camera().desc();
  const double t = std::tan(double(d.fov_deg) * kPiD / 360.0), aspect = double(d.width) / double(d.height);
  const double tx = d.fov_axis_x ? t : t * aspect, ty = d.fov_axis_x ? t / aspect : t;
  m_rad_per_pixel = std::min(2.0 * std::atan(tx) / double(d.width), 2.0 * std::atan(ty) / double(d.height));
}

int CausticPerturbation::kept_end(const PathState& x) const {
  const int K = x.depth();
  if (K < 2 || x.v[size_t(K - 1)].delta || x.v[size_t(K - 1)].kind != BidirKind::surface) return -1;
  int l = K - 2;
  while (l >= 0 && x.v[size_t(l)].delta) --l;
  if (l < 0) return -1;
  const BidirVertex& v = x.v[size_t(l)];
  if (v.kind == BidirKind::light) {
    const auto kind = v.emitter->kind();
    if (kind != scene::EmitterKind::area && kind != scene::EmitterKind::point && kind != scene::EmitterKind::spot) return -1;
  } else if (v.kind != BidirKind::surface || !v.bsdf) {
    return -1;
  }
  return l;
}

bool CausticPerturbation::suitable(const PathState& x) const { return kept_end(x) >= 0; }

void CausticPerturbation::angle_range(const PathState& s, int l, double& theta1, double& theta2) const {
  const int K = s.depth();
  double chain = 0.0;
  for (int i = l; i <= K - 2; ++i) chain += double((s.v[size_t(i + 1)].sp.p - s.v[size_t(i)].sp.p).norm());
  const double eye = double((s.v[size_t(K)].sp.p - s.v[size_t(K - 1)].sp.p).norm());
  const double factor = chain > 0.0 ? eye / chain : 1.0;
  theta2 = std::min(m_rad_per_pixel * m_r2 * factor, 0.999 * kPiD);
  theta1 = std::min(m_rad_per_pixel * m_r1 * factor, 0.01 * theta2);
}

ProposalStatus CausticPerturbation::sample(const PathState& x, PathState& y, MutationRecord& rec, core::Rng& rng,
                                           PathSides& sides) const {
  const int K = x.depth(), l = kept_end(x);
  rec.l = l;
  double t1 = 0, t2 = 0;
  angle_range(x, l, t1, t2);
  const double theta = t2 * std::exp(-std::log(t2 / t1) * rng.uniform_double());
  const double phi = 2.0 * kPiD * rng.uniform_double();
  rec.theta = theta;
  const Vec3 w = turn_direction(direction_between(x.v[size_t(l)], x.v[size_t(l + 1)]), std::cos(theta), phi);
  y.v = x.v;
  const ProposalStatus s = retrace_chain(m_scene, x, y.v, l, K - 1, w, scene::TransportMode::importance);
  if (s != ProposalStatus::ok) return s;
  return finish_proposal(m_scene, y, K, sides);
}

double CausticPerturbation::ratio(const PathState& x, const PathState& y, const MutationRecord& rec) const {
  const int K = x.depth(), l = rec.l;
  double x1 = 0, x2 = 0, y1 = 0, y2 = 0;
  angle_range(x, l, x1, x2);
  angle_range(y, l, y1, y2);
  const double fwd = y.inv_c[size_t(K)] * leave_density(x, l) * dirac_chain_prob(x, l, K - 1, scene::TransportMode::importance) *
                     angle_pdf(rec.theta, x1, x2);
  const double rev = x.inv_c[size_t(K)] * leave_density(y, l) * dirac_chain_prob(y, l, K - 1, scene::TransportMode::importance) *
                     angle_pdf(rec.theta, y1, y2);
  return fwd > 0.0 ? rev / fwd : 0.0;
}

}  // namespace dp::mcmc
