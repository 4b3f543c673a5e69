#include "mcmc/path_target.h"

#include <cmath>

#include "pathspace/scatter.h"

namespace dp::mcmc {

namespace {
// Power heuristic, beta = 2 (Veach 1997, Eq. 9.13).
double power(double pdf_a, double pdf_b) {
  const double a = pdf_a * pdf_a, b = pdf_b * pdf_b;
  return a > 0.0 ? a / (a + b) : 0.0;
}
}  // namespace

Rgb pt_contribution(const scene::Scene& scene, const pathspace::Path& path, bool nee) {
  Rgb sum = Rgb::Zero();
  Rgb beta = Rgb::Ones();  // f / p of x_0..x_k on arrival at x_k (pathspace::throughput)
  for (int k = 1; k < path.size(); ++k) {
    const pathspace::Vertex& v = path[k];
    if (!is_black(v.emission)) {
      double w = 1.0;
      const pathspace::Vertex& prev = path[k - 1];
      if (k >= 2 && nee && !prev.delta_lobe()) w = power(prev.pdf, pathspace::light_pdf(scene, prev.p(), v));
      sum += beta * v.emission * float(w);
    }
    const pathspace::LightSample& ls = path.nee[size_t(k)];
    if (ls.valid && ls.visible && ls.pdf > 0.0) {
      const double w = ls.delta ? 1.0 : power(ls.pdf, ls.bsdf_pdf);
      sum += beta * ls.f_cos * ls.radiance * float(w / ls.pdf);
    }
    if (!v.continued()) break;
    beta *= v.f_cos / float(v.pdf * double(v.rr));
  }
  return sum;
}

PathTarget::PathTarget(const scene::Scene& scene, const pathspace::WalkOptions& options)
    : m_builder(scene, options),
      m_width(float(scene.camera().width())),
      m_height(float(scene.camera().height())) {}

TargetValue PathTarget::evaluate(pathspace::SampleStream& stream) {
  const Vec2 u = stream.next2();
  // u < 1, but u * W may round up to W: keep the raster position inside the image.
  const Vec2 raster(std::min(u.x() * m_width, std::nextafter(m_width, 0.0f)),
                    std::min(u.y() * m_height, std::nextafter(m_height, 0.0f)));
  m_builder.build_from_raster(raster, stream, m_path);
  TargetValue t;
  t.raster = raster;
  t.value = pt_contribution(m_builder.scene(), m_path, m_builder.options().nee);
  t.f = is_finite(t.value) ? std::max(0.0, double(luminance(t.value))) : std::nan("");
  return t;
}

}  // namespace dp::mcmc
