// A local chart of unit directions around `w` for finite-difference Jacobian tests:
// at(a, b) = normalize(w + a s + b t), coords() its inverse to first order.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <functional>
#include <vector>

#include "core/math.h"

namespace dp::test {

struct DirectionChart {
  Vec3d w, s, t;
  explicit DirectionChart(const Vec3d& dir) : w(dir.normalized()) {
    const Vec3d a = std::abs(w.x()) > 0.9 ? Vec3d(0, 1, 0) : Vec3d(1, 0, 0);
    s = w.cross(a).normalized();
    t = w.cross(s);
  }
  Vec3d at(double a, double b) const { return (w + a * s + b * t).normalized(); }
  Eigen::Vector2d coords(const Vec3d& v) const { return {v.normalized().dot(s), v.normalized().dot(t)}; }
};

// |det| of the central-difference Jacobian (step 1e-6) of `map` from m directions (in
// their charts `in`) to m directions (in charts `out`): 2m chart coordinates each. NaN
// where `map` fails.
inline double fd_det(const std::vector<DirectionChart>& in, const std::vector<DirectionChart>& out,
                     const std::function<bool(const std::vector<Vec3d>&, std::vector<Vec3d>&)>& map) {
  const int m = int(in.size());
  const double h = 1e-6;
  Eigen::MatrixXd J(2 * m, 2 * m);
  for (int c = 0; c < 2 * m; ++c) {
    Eigen::VectorXd col(2 * m);
    for (int sgn = -1; sgn <= 1; sgn += 2) {
      std::vector<Vec3d> x(static_cast<size_t>(m)), y;
      for (int i = 0; i < m; ++i)
        x[size_t(i)] = in[size_t(i)].at(c == 2 * i ? sgn * h : 0.0, c == 2 * i + 1 ? sgn * h : 0.0);
      if (!map(x, y)) return std::nan("");
      Eigen::VectorXd v(2 * m);
      for (int i = 0; i < m; ++i) v.segment<2>(2 * i) = out[size_t(i)].coords(y[size_t(i)]);
      if (sgn < 0) col = -v;
      else col += v;
    }
    J.col(c) = col / (2 * h);
  }
  return std::abs(J.determinant());
}

}  // namespace dp::test
