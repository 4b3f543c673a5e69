#include "reconstruct/solve.h"

#include <cmath>
#include <memory>
#include <numeric>

#include "core/error.h"
#include "core/log.h"
#include "core/timer.h"
#include "reconstruct/dct_solver.h"
#include "reconstruct/grid_operator.h"
#include "reconstruct/laplacian.h"
#include "reconstruct/multigrid.h"
#include "reconstruct/pcg.h"

namespace dp::reconstruct {

namespace {

// Inputs with non-finite values replaced (see solve.h for the policy).
struct Prepared {
  std::vector<float> g;        // primal, RGB interleaved
  std::vector<Rgb> b;          // finite copy of b
  std::vector<float> row_w;    // empty = all 1
  std::vector<float> pixel_w;  // empty = all 1
  InputReport report;
};

int find_root(std::vector<int32_t>& parent, int32_t i) {
  while (parent[size_t(i)] != i) {
    parent[size_t(i)] = parent[size_t(parent[size_t(i)])];  // path halving
    i = parent[size_t(i)];
  }
  return i;
}

Prepared prepare(const Problem& problem) {
  validate(problem);
  Prepared out;
  const size_t n = problem.kernel.pixels(), rows = problem.kernel.rows();
  out.g.resize(3 * n);
  out.row_w = problem.row_weights;
  out.pixel_w = problem.pixel_weights;
  for (size_t i = 0; i < n; ++i) {
    const Rgb& v = problem.primal[i];
    const bool ok = is_finite(v);
    for (size_t c = 0; c < 3; ++c) out.g[3 * i + c] = ok ? v[int(c)] : 0.0f;
    if (ok) continue;
    ++out.report.nonfinite_primal_pixels;
    if (out.pixel_w.empty()) out.pixel_w.assign(n, 1.0f);
    out.pixel_w[i] = 0.0f;
  }
  out.b = problem.b;
  for (size_t r = 0; r < rows; ++r) {
    if (is_finite(out.b[r])) continue;
    ++out.report.nonfinite_rows;
    out.b[r] = Rgb::Zero();
    if (out.row_w.empty()) out.row_w.assign(rows, 1.0f);
    out.row_w[r] = 0.0f;
  }
  if (out.report.nonfinite_primal_pixels > 0) {
    // A connected component (over rows of positive weight) without any data term would
    // make the system singular: anchor its pixels to 0 with weight 1.
    std::vector<int32_t> parent(n);
    std::iota(parent.begin(), parent.end(), 0);
    for (size_t r = 0; r < rows; ++r) {
      if (!out.row_w.empty() && !(out.row_w[r] > 0.0f)) continue;
      const PixelPair& p = problem.kernel.pairs()[r];
      const int32_t a = find_root(parent, p.i), c = find_root(parent, p.j);
      if (a != c) parent[size_t(a)] = c;
    }
    std::vector<char> anchored(n, 0);
    for (size_t i = 0; i < n; ++i)
      if (out.pixel_w[i] > 0.0f) anchored[size_t(find_root(parent, int32_t(i)))] = 1;
    for (size_t i = 0; i < n; ++i) {
      if (out.pixel_w[i] > 0.0f || anchored[size_t(find_root(parent, int32_t(i)))]) continue;
      out.pixel_w[i] = 1.0f;
      ++out.report.anchored_pixels;
    }
  }
  if (out.report.nonfinite_primal_pixels > 0 || out.report.nonfinite_rows > 0)
    log::warn("reconstruct: ignored ", out.report.nonfinite_primal_pixels, " primal pixels and ",
              out.report.nonfinite_rows, " gradient rows with NaN/Inf values (", out.report.anchored_pixels,
              " pixels anchored to 0)");
  return out;
}

core::Image to_image(int width, int height, const std::vector<Vec4>& v) {
  core::Image img(width, height);
  for (size_t i = 0; i < img.size(); ++i) img[i] = to_rgb(v[i]);
  return img;
}

// The CG operator: the index-free GridOperator for forward-difference grid kernels,
// the CSR Laplacian for any other kernel.
class Operator {
 public:
  Operator(const Kernel& k, GridSolver solver) {
    if (k.is_forward_difference_grid()) {
      m_grid = std::make_unique<GridOperator>(k.width(), k.height());
      if (solver == GridSolver::multigrid) {
        m_mg = std::make_unique<GridMultigrid>();
        m_grid->set_factor_preconditioner(false);
      }
    } else {
      m_csr = std::make_unique<Laplacian>(k);
    }
  }
  const char* preconditioner() const { return m_mg ? "multigrid" : "block_ic"; }
  // Preconditioned CG from x (warm start) with the current weights.
  CgStats solve(const std::vector<Vec4>& rhs, std::vector<Vec4>& x, const CgSettings& s, CgWorkspace* ws) {
    if (m_mg) {
      m_mg->build(*m_grid, s.threads);
      return mg_pcg(*m_grid, *m_mg, rhs.data(), x.data(), s, ws);
    }
    return pcg(op(), rhs.data(), x.data(), s, ws);
  }
  // One IRLS reweighting at x and the warm-started CG that follows, for the multigrid
  // grid solver: the fused reweight_start (grid_operator.h) replaces setting the weights,
  // forming the right-hand side and the CG's first residual (the first V-cycle forms its
  // own first red half-step).
  CgStats reweight_solve(std::vector<Vec4>& x, const std::vector<Rgb>& b, const std::vector<Vec4>& g4, double reg,
                         float alpha, const float* user_rows, const float* user_pixels, const CgSettings& s,
                         CgWorkspace& ws) {
    const size_t h = size_t(m_grid->height());
    ws.r.resize(x.size());
    ws.z.resize(x.size());
    m_row_rr.resize(h);
    m_row_bb.resize(h);
    m_grid->reweight_start(x.data(), b, g4.data(), reg, alpha, user_rows, user_pixels, ws.r.data(), nullptr,
                           m_row_rr.data(), m_row_bb.data(), s.threads);
    const CgStart start{m_row_rr.data(), m_row_bb.data(), false};
    // The last reweightings usually start converged: no hierarchy needed for them.
    if (!cg_start_converged(start, m_grid->height(), s.tolerance)) m_mg->build(*m_grid, s.threads);
    return mg_pcg(*m_grid, *m_mg, nullptr, x.data(), s, &ws, &start);
  }
  bool fused_reweighting() const { return m_mg != nullptr; }
  GridOperator* grid() { return m_grid.get(); }
  const ChunkedOperator& op() const {
    if (m_grid) return *m_grid;
    return *m_csr;
  }
  void set_weights(const std::vector<float>& rw, const std::vector<float>& pw, float alpha, int threads) {
    const float* r = rw.empty() ? nullptr : rw.data();
    const float* p = pw.empty() ? nullptr : pw.data();
    if (m_grid)
      m_grid->set_weights(r, p, alpha, threads);
    else
      m_csr->set_weights(r, p, alpha, threads);
  }
  // out = H^T W b + alpha^2 P g; g given both RGB interleaved and as Vec4.
  void rhs(const std::vector<Rgb>& b, const std::vector<float>& g, const std::vector<Vec4>& g4,
           std::vector<Vec4>& out, int threads) const {
    out.resize(g4.size());
    if (m_grid) {
      m_grid->rhs(b, g4.data(), out.data(), threads);
      return;
    }
    std::vector<float> tmp(g.size());
    m_csr->rhs(b, g.data(), tmp.data(), threads);
    out = to_vec4(tmp);
  }

 private:
  std::unique_ptr<GridOperator> m_grid;
  std::unique_ptr<GridMultigrid> m_mg;
  std::unique_ptr<Laplacian> m_csr;
  std::vector<Vec4d> m_row_rr, m_row_bb;
};

// H^T b + alpha^2 g for the forward-difference grid (unit weights):
// (H^T b)(x,y) = dx(x-1,y) - dx(x,y) + dy(x,y-1) - dy(x,y), absent rows omitted.
void grid_rhs(const Kernel& k, const std::vector<Rgb>& b, const std::vector<float>& g, float alpha,
              std::vector<float>& out, int threads) {
  const int w = k.width(), h = k.height();
  const double a2 = double(alpha) * double(alpha);
  out.resize(g.size());
  run_team(threads, [&](int t) {
    const int y0 = int(part_begin(size_t(h), threads, t)), y1 = int(part_begin(size_t(h), threads, t + 1));
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        const size_t i = size_t(y) * size_t(w) + size_t(x);
        Rgbd acc = Rgbd::Zero();
        if (x > 0) acc += b[k.grid_dx_row(x - 1, y)].cast<double>();
        if (x + 1 < w) acc -= b[k.grid_dx_row(x, y)].cast<double>();
        if (y > 0) acc += b[k.grid_dy_row(x, y - 1)].cast<double>();
        if (y + 1 < h) acc -= b[k.grid_dy_row(x, y)].cast<double>();
        for (size_t c = 0; c < 3; ++c) out[3 * i + c] = float(acc[int(c)] + a2 * double(g[3 * i + c]));
      }
  });
}

bool direct_applicable(const Problem& problem, const Prepared& in) {
  return problem.kernel.is_forward_difference_grid() && in.row_w.empty() && in.pixel_w.empty();
}

// The L2 solve shared by solve_l2 and IRLS iteration 0. Writes x; returns CG stats
// (iterations 0 for the DCT).
CgStats l2_into(const Problem& problem, const Prepared& in, const std::vector<Vec4>& g4, const SolveOptions& options,
                bool use_direct, int cg_iterations, double cg_tolerance, Operator* A, std::vector<Vec4>& x) {
  const int threads = resolve_threads(options.threads);
  if (use_direct) {
    std::vector<float> rhs;
    grid_rhs(problem.kernel, in.b, in.g, problem.alpha, rhs, threads);
    // Bhat et al. 2008: (H^T H + alpha^2 I) I = H^T b + alpha^2 I_g, diagonalized by the DCT.
    dct_solve(problem.kernel.width(), problem.kernel.height(), rhs.data(), rhs.data(), 1.0,
              double(problem.alpha) * double(problem.alpha), threads);
    x = to_vec4(rhs);
    return {};
  }
  A->set_weights(in.row_w, in.pixel_w, problem.alpha, threads);
  std::vector<Vec4> rhs;
  A->rhs(in.b, in.g, g4, rhs, threads);
  x = g4;  // warm start from the primal
  CgSettings s;
  s.max_iterations = cg_iterations;
  s.tolerance = cg_tolerance;
  s.threads = threads;
  return A->solve(rhs, x, s, nullptr);
}

bool choose_direct(const Problem& problem, const Prepared& in, L2Method method) {
  const bool can = direct_applicable(problem, in);
  if (method == L2Method::direct && !can)
    throw ValueError(
        "reconstruct: the direct (DCT) solve needs the forward-difference grid kernel with uniform weights "
        "and finite inputs");
  return method != L2Method::cg && can;
}

}  // namespace

SolveResult solve_l2(const Problem& problem, const SolveOptions& options) {
  const core::Timer timer;
  const Prepared in = prepare(problem);
  const bool direct = choose_direct(problem, in, options.method);
  std::vector<Vec4> x;
  SolveResult result;
  if (direct) {
    l2_into(problem, in, {}, options, true, 0, 0.0, nullptr, x);
    result.method = "dct";
  } else {
    Operator A(problem.kernel, options.grid_solver);
    result.preconditioner = A.preconditioner();
    const CgStats st = l2_into(problem, in, to_vec4(in.g), options, false, options.cg_max_iterations,
                               options.cg_tolerance, &A, x);
    result.method = "pcg";
    result.cg_iterations = st.iterations;
    result.relative_residual = st.relative_residual;
    if (!st.converged)
      log::warn("reconstruct: L2 CG stopped after ", st.iterations, " iterations at relative residual ",
                st.relative_residual);
  }
  result.image = to_image(problem.kernel.width(), problem.kernel.height(), x);
  result.input = in.report;
  result.seconds = timer.seconds();
  return result;
}

SolveResult solve_l1(const Problem& problem, const SolveOptions& options) {
  const core::Timer timer;
  if (options.reweightings < 0) throw ValueError("reconstruct: reweightings must be >= 0");
  const Prepared in = prepare(problem);
  const bool direct = choose_direct(problem, in, options.method);
  const Kernel& k = problem.kernel;
  const size_t n = k.pixels(), rows = k.rows();
  const int threads = resolve_threads(options.threads);
  Operator A(k, options.grid_solver);
  const std::vector<Vec4> g4 = to_vec4(in.g);
  std::vector<Vec4> x, rhs;
  SolveResult result;
  result.method = direct ? "irls+dct" : "irls+pcg";
  if (!direct || options.reweightings > 0) result.preconditioner = A.preconditioner();
  // IRLS iteration 0: plain L2.
  CgStats st =
      l2_into(problem, in, g4, options, direct, options.irls_cg_iterations, options.irls_cg_tolerance, &A, x);
  result.cg_iterations += st.iterations;

  // Weights of the generic path (the grid operator keeps its own).
  std::vector<float> row_w(A.grid() ? 0 : rows), pixel_w(A.grid() ? 0 : n);
  CgWorkspace workspace;
  const float alpha = problem.alpha;
  const auto& pairs = k.pairs();
  struct alignas(64) Sum {
    double v = 0.0;
  };
  std::vector<Sum> sums(static_cast<size_t>(threads));
  for (int it = 1; it <= options.reweightings; ++it) {
    if (options.stop && options.stop->load(std::memory_order_relaxed)) {
      result.interrupted = true;
      break;
    }
    // Reference IRLS schedule (ALGORITHMS.md): reg = 0.05 * 0.5^(k-1), w = 1/(|e|_2 + reg).
    const double reg = 0.05 * std::pow(0.5, it - 1);
    CgSettings cg;
    cg.max_iterations = options.irls_cg_iterations;
    cg.tolerance = options.irls_cg_tolerance;
    cg.threads = threads;
    if (A.fused_reweighting()) {
      st = A.reweight_solve(x, in.b, g4, reg, alpha, in.row_w.empty() ? nullptr : in.row_w.data(),
                            in.pixel_w.empty() ? nullptr : in.pixel_w.data(), cg, workspace);
    } else if (GridOperator* grid = A.grid()) {
      // The same weights without the kernel's index arrays.
      grid->set_irls_weights(x.data(), in.b, g4.data(), reg, alpha, in.row_w.empty() ? nullptr : in.row_w.data(),
                             in.pixel_w.empty() ? nullptr : in.pixel_w.data(), threads);
    } else {
      run_team(threads, [&](int t) {
        double s = 0.0;
        for (size_t r = part_begin(rows, threads, t), r1 = part_begin(rows, threads, t + 1); r < r1; ++r) {
          const PixelPair& p = pairs[r];
          double e2 = 0.0;
          for (size_t c = 0; c < 3; ++c) {
            const double e = double(x[size_t(p.j)][c]) - double(x[size_t(p.i)][c]) - double(in.b[r][int(c)]);
            e2 += e * e;
          }
          const double w = 1.0 / (std::sqrt(e2) + reg);
          row_w[r] = float(w);
          s += w;
        }
        for (size_t i = part_begin(n, threads, t), i1 = part_begin(n, threads, t + 1); i < i1; ++i) {
          double e2 = 0.0;
          for (size_t c = 0; c < 3; ++c) {
            const double e = double(alpha) * (double(x[i][c]) - double(in.g[3 * i + c]));
            e2 += e * e;
          }
          const double w = 1.0 / (std::sqrt(e2) + reg);
          pixel_w[i] = float(w);
          s += w;
        }
        sums[size_t(t)].v = s;
      });
      double total = 0.0;
      for (const Sum& s : sums) total += s.v;
      // Normalize to mean 1 over all rows (gradient and primal), then apply user weights.
      const float scale = float(double(rows + n) / total);
      run_team(threads, [&](int t) {
        for (size_t r = part_begin(rows, threads, t), r1 = part_begin(rows, threads, t + 1); r < r1; ++r)
          row_w[r] *= scale * (in.row_w.empty() ? 1.0f : in.row_w[r]);
        for (size_t i = part_begin(n, threads, t), i1 = part_begin(n, threads, t + 1); i < i1; ++i)
          pixel_w[i] *= scale * (in.pixel_w.empty() ? 1.0f : in.pixel_w[i]);
      });
      A.set_weights(row_w, pixel_w, alpha, threads);
    }
    if (!A.fused_reweighting()) {
      A.rhs(in.b, in.g, g4, rhs, threads);
      st = A.solve(rhs, x, cg, &workspace);  // warm start from the current image
    }
    result.cg_iterations += st.iterations;
    result.relative_residual = st.relative_residual;
    result.reweightings = it;
  }
  result.image = to_image(k.width(), k.height(), x);
  result.input = in.report;
  result.seconds = timer.seconds();
  return result;
}

}  // namespace dp::reconstruct
