#include "pathspace/measure.h"

namespace dp::pathspace {

double geometry_term(const Vertex& a, const Vertex& b) {
  const Vec3d d = (b.p() - a.p()).cast<double>();
  const double d2 = d.squaredNorm();
  if (!(d2 > 0.0)) return 0.0;
  const Vec3d w = d / std::sqrt(d2);
  const double ca = a.kind == VertexKind::surface ? std::abs(a.hit.ng.cast<double>().dot(w)) : 1.0;
  const double cb = b.kind == VertexKind::surface ? std::abs(b.hit.ng.cast<double>().dot(w)) : 1.0;
  return ca * cb / d2;
}

double solid_angle_to_area(const Vertex& from, const Vertex& to) {
  if (to.kind == VertexKind::environment) return 1.0;
  const Vec3d d = (to.p() - from.p()).cast<double>();
  const double d2 = d.squaredNorm();
  if (!(d2 > 0.0)) return 0.0;
  return std::abs(to.hit.ng.cast<double>().dot(d / std::sqrt(d2))) / d2;
}

double pdf_area(const Path& path, int k) {
  return path[k].pdf * solid_angle_to_area(path[k], path[k + 1]);
}

Rgb throughput(const Path& path, int k) {
  Rgb beta = Rgb::Ones();
  for (int m = 1; m < k; ++m) beta *= path[m].f_cos / float(path[m].pdf * double(path[m].rr));
  return beta;
}

Rgb nee_estimate(const Path& path, int k) {
  const LightSample& ls = path.nee[size_t(k)];
  if (!ls.valid || !ls.visible || !(ls.pdf > 0.0)) return Rgb::Zero();
  return throughput(path, k) * ls.f_cos * ls.radiance / float(ls.pdf);
}

Rgb emission_estimate(const Path& path, int k) { return throughput(path, k) * path[k].emission; }

}  // namespace dp::pathspace
