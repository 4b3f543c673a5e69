#include "gradients/pair_terms.h"

#include <cmath>
#include <limits>

#include "pathspace/scatter.h"

namespace dp::gradients {

using pathspace::Vertex;

void PairTerms::set_base(const scene::Scene& scene, bool nee, const pathspace::Path& base) {
  m_scene = &scene;
  m_nee = nee;
  m_base = &base;
  const int n = base.size();
  // Base throughput f/p of every prefix, in double.
  m_beta.assign(size_t(n), Rgbd::Ones());
  for (int k = 1; k + 1 < n; ++k)
    m_beta[size_t(k + 1)] = m_beta[size_t(k)] * base[k].f_cos.cast<double>() / (base[k].pdf * double(base[k].rr));
  m_b_other_bsdf.assign(size_t(n), std::numeric_limits<double>::quiet_NaN());
}

// NEE is performed at vertex m of a walk (so NEE can produce the path through x_m).
bool PairTerms::nee_at(const Vertex& v) const {
  return m_nee && v.is_surface() && v.hit.bsdf && !v.hit.bsdf->is_purely_delta() && !v.delta_lobe();
}

double PairTerms::base_bsdf_other(int k) {
  double& b = m_b_other_bsdf[size_t(k)];
  if (std::isnan(b)) {
    const pathspace::Path& base = *m_base;
    const int m = k - 1;
    b = nee_at(base[m]) ? pathspace::light_pdf(*m_scene, base[m].p(), base[k]) / base[m].pdf : 0.0;
  }
  return b;
}

void PairTerms::prepare_offset(const ShiftResult* res) {
  const pathspace::Path& base = *m_base;
  const int n = base.size();
  const int alive = res ? res->alive : 0;
  // Offset throughput relative to the base density, and pdf ratios p_j(T x)|T'| / p_i(x)
  // per prefix (Kettunen et al. 2015, Sec. 5.3).
  m_beta_o.assign(size_t(n), Rgbd::Zero());
  m_ratio.assign(size_t(n), 0.0);
  m_jprefix.assign(size_t(n), 1.0);
  if (alive >= 2) m_beta_o[1] = Rgbd::Ones(), m_ratio[1] = 1.0;
  for (int k = 1; k + 1 < alive; ++k) {
    const Vertex& o = res->path[k];
    const double J = res->jacobian[size_t(k)];
    m_beta_o[size_t(k + 1)] = m_beta_o[size_t(k)] * o.f_cos.cast<double>() * J / (base[k].pdf * double(base[k].rr));
    // A walk stops where its sampled BSDF weight is black (pathspace/path_builder.cpp), so
    // pixel j's walk cannot continue through an offset vertex of black f: density 0.
    m_ratio[size_t(k + 1)] = is_black(o.f_cos) ? 0.0 : m_ratio[size_t(k)] * o.pdf * J / base[k].pdf;
    m_jprefix[size_t(k + 1)] = m_jprefix[size_t(k)] * J;
  }
}

const std::vector<PairTerm>& PairTerms::terms(const ShiftResult* res, int min_segments, bool keep_zero) {
  const pathspace::Path& base = *m_base;
  const int n = base.size();
  prepare_offset(res);
  const int alive = res ? res->alive : 0;
  m_terms.clear();
  // NEE paths (x_0..x_k, light sample): k + 1 segments.
  for (int k = std::max(1, min_segments - 1); k < n; ++k) {
    const pathspace::LightSample& bl = base.nee[size_t(k)];
    if (!bl.valid || !(bl.pdf > 0.0)) continue;
    PairTerm t;
    t.segments = k + 1;
    t.nee = true;
    t.base_visible = bl.visible;
    if (bl.visible) {
      t.fb = m_beta[size_t(k)] * (bl.f_cos * bl.radiance).cast<double>() / bl.pdf;
      // BSDF sampling cannot produce the path where f toward the light is black (the walk
      // stops there), whatever the direction's pdf.
      t.b_other = is_black(bl.f_cos) ? 0.0 : bl.bsdf_pdf / bl.pdf;
    }
    t.has_offset = res && res->nee_ok(k);
    if (t.has_offset) {
      const pathspace::LightSample& ol = res->path.nee[size_t(k)];
      const double J = res->nee_jacobian[size_t(k)];
      t.offset_visible = ol.visible;
      t.c = m_ratio[size_t(k)] * J * ol.pdf / bl.pdf;
      t.d = ol.visible && !is_black(ol.f_cos) ? m_ratio[size_t(k)] * J * ol.bsdf_pdf / bl.pdf : 0.0;
      t.jacobian = m_jprefix[size_t(k)] * J;
      if (ol.visible) t.fo = m_beta_o[size_t(k)] * (ol.f_cos * ol.radiance).cast<double>() * (J / bl.pdf);
    }
    if (!keep_zero && (t.fb == 0.0).all() && (t.fo == 0.0).all()) continue;
    m_terms.push_back(t);
  }
  // BSDF paths (x_0..x_k) whose last vertex may emit: k segments. The light densities (for
  // the MIS weights) are only needed where the base or the offset vertex emits.
  for (int k = std::max(2, min_segments); k < n; ++k) {
    const int m = k - 1;
    const Vertex& bv = base[k];
    const bool has_offset = k < alive;
    const bool base_emits = !is_black(bv.emission);
    if (!keep_zero && !base_emits && !(has_offset && !is_black(res->path[k].emission))) continue;
    PairTerm t;
    t.segments = k;
    t.has_offset = has_offset;
    if (base_emits) t.fb = m_beta[size_t(k)] * bv.emission.cast<double>();
    t.b_other = base_bsdf_other(k);
    if (has_offset) {
      const Vertex& om = res->path[m];
      const Vertex& ov = res->path[k];
      t.c = m_ratio[size_t(k)];
      t.d = nee_at(om) ? m_ratio[size_t(m)] * res->jacobian[size_t(m)] * pathspace::light_pdf(*m_scene, om.p(), ov) /
                             base[m].pdf
                       : 0.0;
      t.jacobian = m_jprefix[size_t(k)];
      t.fo = m_beta_o[size_t(k)] * ov.emission.cast<double>();
    }
    if (!keep_zero && (t.fb == 0.0).all() && (t.fo == 0.0).all()) continue;
    m_terms.push_back(t);
  }
  return m_terms;
}

}  // namespace dp::gradients
