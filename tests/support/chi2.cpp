#include "tests/support/chi2.h"

#include <algorithm>
#include <boost/math/special_functions/gamma.hpp>
#include <numeric>
#include <sstream>
#include <vector>

namespace dp::test {

namespace {
Vec3 dir_from(double cos_theta, double phi) {
  const double s = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
  return Vec3(float(s * std::cos(phi)), float(s * std::sin(phi)), float(cos_theta));
}

// Midpoint-rule integration of pdf over the cell [z0,z1] x [p0,p1] (measure dz dphi =
// dω). The midpoint rule never evaluates on cell boundaries, where pdfs are often
// discontinuous (the horizon z = 0).
double midpoint_cell(const DirectionPdf& pdf, double z0, double z1, double p0, double p1, int res) {
  const double hz = (z1 - z0) / res, hp = (p1 - p0) / res;
  double sum = 0;
  for (int i = 0; i < res; ++i)
    for (int j = 0; j < res; ++j) {
      const double v = pdf(dir_from(z0 + (i + 0.5) * hz, p0 + (j + 0.5) * hp));
      sum += std::isfinite(v) ? v : 0.0;
    }
  return sum * hz * hp;
}

// Adaptive refinement: where the 8x8 and 16x16 midpoint estimates disagree (a sharp
// edge or peak inside the cell, e.g. a small cone light), the cell is split in four,
// down to `depth` levels.
double integrate_cell(const DirectionPdf& pdf, double z0, double z1, double p0, double p1, int depth) {
  const double coarse = midpoint_cell(pdf, z0, z1, p0, p1, 8);
  const double fine = midpoint_cell(pdf, z0, z1, p0, p1, 16);
  if (depth <= 0 || std::abs(fine - coarse) <= 1e-4 * std::abs(fine) + 1e-12) return fine;
  const double zm = 0.5 * (z0 + z1), pm = 0.5 * (p0 + p1);
  return integrate_cell(pdf, z0, zm, p0, pm, depth - 1) + integrate_cell(pdf, zm, z1, p0, pm, depth - 1) +
         integrate_cell(pdf, z0, zm, pm, p1, depth - 1) + integrate_cell(pdf, zm, z1, pm, p1, depth - 1);
}
}  // namespace

double integrate_sphere(const DirectionPdf& pdf, int theta_res, int phi_res) {
  double total = 0;
  const int tb = theta_res / 8, pb = phi_res / 8;
  for (int i = 0; i < tb; ++i)
    for (int j = 0; j < pb; ++j)
      total += integrate_cell(pdf, -1.0 + 2.0 * i / tb, -1.0 + 2.0 * (i + 1) / tb, 2 * kPiD * j / pb,
                              2 * kPiD * (j + 1) / pb, 2);
  return total;
}

Chi2Result chi2_sphere(const DirectionSampler& sample, const DirectionPdf& pdf, const Chi2Options& opt) {
  const int nt = opt.theta_bins, np = opt.phi_bins, cells = nt * np;
  std::vector<double> observed(size_t(cells), 0.0), expected(size_t(cells), 0.0);
  core::Rng rng(opt.seed, 0);
  int hits = 0;
  for (int k = 0; k < opt.samples; ++k) {
    const auto w = sample(rng);
    if (!w) continue;
    ++hits;
    const double z = std::clamp(double(w->z()), -1.0, 1.0);
    double phi = std::atan2(double(w->y()), double(w->x()));
    if (phi < 0) phi += 2 * kPiD;
    const int it = std::min(nt - 1, int((z + 1.0) * 0.5 * nt));
    const int ip = std::min(np - 1, int(phi / (2 * kPiD) * np));
    observed[size_t(it * np + ip)] += 1;
  }
  Chi2Result r;
  r.sampled_fraction = double(hits) / opt.samples;
  for (int it = 0; it < nt; ++it)
    for (int ip = 0; ip < np; ++ip) {
      const double z0 = -1.0 + 2.0 * it / nt, z1 = -1.0 + 2.0 * (it + 1) / nt;
      const double p0 = 2 * kPiD * ip / np, p1 = 2 * kPiD * (ip + 1) / np;
      const double e = integrate_cell(pdf, z0, z1, p0, p1, 4);
      r.integral += e;
      expected[size_t(it * np + ip)] = e * opt.samples;
    }
  // Pool every cell with expected count < 5 into one cell (the chi-square
  // approximation needs expected counts >= 5; Mitsuba's harness does the same).
  std::vector<int> order(static_cast<size_t>(cells));
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](int a, int b) { return expected[size_t(a)] < expected[size_t(b)]; });
  double pooled_obs = 0, pooled_exp = 0, stat = 0;
  int dof = 0;
  std::ostringstream rep;
  for (int idx : order) {
    const double o = observed[size_t(idx)], e = expected[size_t(idx)];
    if (e < 5.0) {  // every low-expectation cell goes into the pooled cell
      pooled_obs += o;
      pooled_exp += e;
      continue;
    }
    stat += (o - e) * (o - e) / e;
    ++dof;
    if (std::abs(o - e) > 3 * std::sqrt(e))
      rep << "cell(theta " << idx / np << ", phi " << idx % np << "): observed " << o << " expected " << e << "\n";
  }
  if (pooled_exp > 0) {
    stat += (pooled_obs - pooled_exp) * (pooled_obs - pooled_exp) / pooled_exp;
    ++dof;
  } else if (pooled_obs > 0) {
    stat = std::numeric_limits<double>::infinity();
    rep << pooled_obs << " samples fell where the pdf is zero\n";
  }
  // Samples that returned a direction must match the pdf's mass; the total count of
  // absorbed samples is part of the fit as one more cell.
  const double absorbed_obs = opt.samples - hits, absorbed_exp = opt.samples * (1.0 - r.integral);
  if (absorbed_exp >= 5.0) {
    stat += (absorbed_obs - absorbed_exp) * (absorbed_obs - absorbed_exp) / absorbed_exp;
    ++dof;
  }
  dof -= 1;
  r.statistic = stat;
  r.dof = dof;
  r.p_value = (dof > 0 && std::isfinite(stat)) ? boost::math::gamma_q(dof / 2.0, stat / 2.0) : 0.0;
  const double alpha = 1.0 - std::pow(1.0 - opt.significance, 1.0 / std::max(1, opt.test_count));
  r.passed = r.p_value > alpha;
  std::ostringstream head;
  head << "chi2 = " << stat << ", dof = " << dof << ", p = " << r.p_value << " (alpha " << alpha
       << "), pdf integral = " << r.integral << ", sampled fraction = " << r.sampled_fraction << "\n";
  r.report = head.str() + rep.str();
  return r;
}

}  // namespace dp::test
