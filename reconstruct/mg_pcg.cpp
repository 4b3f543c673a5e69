// mg_pcg (multigrid.h): CG on the grid operator preconditioned by the multigrid V-cycle.
// Per iteration: the V-cycle (two pipelined passes over level 0), the direction
// p = z + beta p_old with q = A p and p.q, and the update x += alpha p, r -= alpha q.
// A run that starts converged (a given start, CgStart) returns before anything else: the
// hierarchy need not be built for it (solve_l1 builds it only when needed).
//
// (Tried for issue 18: fusing the update into the next V-cycle's first pass, with A p
// recomputed there instead of stored. IRLS runs end after ~2 iterations on average and
// the fused pass is wasted when the run ends, so it measured ~10% more CPU time per
// iteration single-threaded; dropped, bench/RESULTS.md.)
#include <algorithm>
#include <barrier>
#include <cmath>

#include "core/error.h"
#include "reconstruct/laplacian.h"
#include "reconstruct/multigrid.h"

namespace dp::reconstruct {

namespace {

// out = A v on row y of the grid operator; up / down are rows y-1 / y+1 of v (nullptr at
// the image border). Returns sum v . (A v) over the row.
Vec4d stencil_row(const GridOperator& A, int y, const Vec4* up, const Vec4* mid, const Vec4* down, Vec4* out) {
  const int w = A.width();
  const size_t base = size_t(y) * size_t(w);
  const float* wx = A.weights_x() + base;
  const float* wy = A.weights_y() + base;
  const float* wu = up ? A.weights_y() + base - size_t(w) : nullptr;
  const float* dg = A.diagonal() + base;
  const auto pixel = [&](int i) {
    Vec4 a = dg[i] * mid[i];
    if (i > 0) a -= wx[i - 1] * mid[i - 1];
    if (i + 1 < w) a -= wx[i] * mid[i + 1];
    if (up) a -= wu[i] * up[i];
    if (down) a -= wy[i] * down[i];
    out[i] = a;
  };
  if (up && down && w > 2) {
    pixel(0);
    for (int i = 1; i + 1 < w; ++i)
      out[i] = dg[i] * mid[i] - wx[i - 1] * mid[i - 1] - wx[i] * mid[i + 1] - wu[i] * up[i] - wy[i] * down[i];
    pixel(w - 1);
  } else {
    for (int i = 0; i < w; ++i) pixel(i);
  }
  Vec4d s;
  for (int i = 0; i < w; ++i) accumulate(s, mid[i] * out[i]);
  return s;
}

}  // namespace

bool cg_start_converged(const CgStart& start, int height, double tolerance) {
  Vec4d rr, bb;
  for (int y = 0; y < height; ++y) {
    rr += start.row_rr[y];
    bb += start.row_bb[y];
  }
  for (int c = 0; c < 3; ++c)
    if (std::sqrt(rr[c]) > tolerance * std::sqrt(std::max(bb[c], 1e-60))) return false;
  return true;
}

CgStats mg_pcg(const GridOperator& A, GridMultigrid& M, const Vec4* rhs, Vec4* x, const CgSettings& settings,
               CgWorkspace* workspace, const CgStart* start) {
  DP_CHECK(settings.max_iterations >= 0, "max_iterations must be >= 0");
  DP_CHECK(!start || (workspace && workspace->r.size() == A.pixels() && workspace->z.size() == A.pixels()),
           "mg_pcg: a given start needs the workspace holding r and z");
  DP_CHECK(start || rhs, "mg_pcg: no right-hand side");
  if (start && cg_start_converged(*start, A.height(), settings.tolerance)) {
    double rr[3], bb[3];
    const bool active[3] = {false, false, false};
    Vec4d s_rr, s_bb;
    for (int y = 0; y < A.height(); ++y) {
      s_rr += start->row_rr[y];
      s_bb += start->row_bb[y];
    }
    for (int c = 0; c < 3; ++c) {
      rr[c] = s_rr[c];
      bb[c] = s_bb[c];
    }
    return cg_stats(0, active, rr, bb);
  }
  DP_CHECK(!M.levels().empty() && M.levels()[0].w == A.width() && M.levels()[0].h == A.height(),
           "mg_pcg: multigrid not built for this operator");
  const int w = A.width(), h = A.height();
  const size_t n = A.pixels();
  CgWorkspace local;
  CgWorkspace& ws = workspace ? *workspace : local;
  for (std::vector<Vec4>* v : {&ws.r, &ws.z, &ws.q, &ws.pa, &ws.pb}) v->resize(n);
  Vec4* r = ws.r.data();
  Vec4* z = ws.z.data();
  Vec4* q = ws.q.data();
  Vec4* p_old = ws.pa.data();
  Vec4* p_new = ws.pb.data();

  // Thread split of the rows in units the multigrid levels can halve.
  const int align = M.row_alignment();
  const int units = (h + align - 1) / align;
  const int threads = std::max(1, std::min(resolve_threads(settings.threads), units));
  std::vector<int> rows(size_t(threads) + 1);
  for (int t = 0; t <= threads; ++t) rows[size_t(t)] = std::min(h, int(part_begin(size_t(units), threads, t)) * align);
  ws.scratch.resize(2 * size_t(w) * size_t(threads));
  // Per-row partial sums, added in row order: the result does not depend on the split.
  const size_t hs = static_cast<size_t>(h);
  std::vector<Vec4d> row_rz(hs), row_pq(hs), row_rr(hs), row_bb(hs);
  const auto total = [](const std::vector<Vec4d>& v) {
    Vec4d s;
    for (const Vec4d& e : v) s += e;
    return s;
  };
  std::barrier<> barrier(threads);
  const std::function<void()> sync = threads > 1 ? std::function<void()>([&] { barrier.arrive_and_wait(); })
                                                 : std::function<void()>([] {});
  // Whether z holds the first V-cycle's first red half-sweep.
  const bool first_red_given = start && start->first_red_done;
  const Vec4 zero = {};
  double rr[3] = {}, bb[3] = {};
  bool active[3] = {false, false, false};
  int it = 0;

  run_team(threads, [&](int t) {
    const int y0 = rows[size_t(t)], y1 = rows[size_t(t) + 1];
    Vec4* halo_up = ws.scratch.data() + 2 * size_t(w) * size_t(t);
    Vec4* halo_down = halo_up + w;
    // r = rhs - A x and the norms of r and rhs (unless given).
    for (int y = y0; y < y1 && start; ++y) {
      row_rr[size_t(y)] = start->row_rr[y];
      row_bb[size_t(y)] = start->row_bb[y];
    }
    for (int y = y0; y < y1 && !start; ++y) {
      const size_t base = size_t(y) * size_t(w);
      stencil_row(A, y, y > 0 ? x + base - size_t(w) : nullptr, x + base, y + 1 < h ? x + base + size_t(w) : nullptr,
                  q + base);
      Vec4d srr, sbb;
      for (size_t i = base; i < base + size_t(w); ++i) {
        r[i] = rhs[i] - q[i];
        accumulate(srr, r[i] * r[i]);
        accumulate(sbb, rhs[i] * rhs[i]);
      }
      row_rr[size_t(y)] = srr;
      row_bb[size_t(y)] = sbb;
    }
    sync();
    double my_rr[3], my_bb[3], my_limit[3], my_rz[3] = {};
    bool my_active[3];
    {
      const Vec4d s_rr = total(row_rr), s_bb = total(row_bb);
      for (int c = 0; c < 3; ++c) {
        my_rr[c] = s_rr[c];
        my_bb[c] = s_bb[c];
        // An all-zero right-hand side has the solution 0: stop at a tiny absolute residual.
        my_limit[c] = settings.tolerance * std::sqrt(std::max(my_bb[c], 1e-60));
        my_active[c] = std::sqrt(my_rr[c]) > my_limit[c];
      }
    }
    int my_it = 0;
    Vec4* po = p_old;
    Vec4* pn = p_new;
    while (my_it < settings.max_iterations && (my_active[0] || my_active[1] || my_active[2])) {
      // z = M^-1 r (in the first iteration its first red half-sweep may be given in z), the row
      // sums of r.z.
      M.vcycle(r, z, rows, t, threads, sync, my_it == 0 && first_red_given, row_rz.data());
      sync();
      Vec4 beta = zero;
      {
        const Vec4d s = total(row_rz);
        for (int c = 0; c < 3; ++c) {
          if (my_it > 0 && my_active[c] && my_rz[c] > 0.0) beta[c] = float(s[c] / my_rz[c]);
          if (my_active[c]) my_rz[c] = s[c];
        }
      }
      // p = z + beta p_old (the first direction is z) and q = A p, p.q. The halo rows of
      // the neighbouring threads are formed into scratch.
      const bool first = my_it == 0;
      const auto form = [&](int y, Vec4* dst) {
        const size_t base = size_t(y) * size_t(w);
        if (first)
          for (int i = 0; i < w; ++i) dst[i] = z[base + size_t(i)];
        else
          for (int i = 0; i < w; ++i) dst[i] = z[base + size_t(i)] + beta * po[base + size_t(i)];
      };
      if (y0 > 0) form(y0 - 1, halo_up);
      if (y0 < y1) form(y0, pn + size_t(y0) * size_t(w));
      for (int y = y0; y < y1; ++y) {
        Vec4* mid = pn + size_t(y) * size_t(w);
        const Vec4* down = nullptr;
        if (y + 1 < y1) {
          form(y + 1, mid + w);
          down = mid + w;
        } else if (y + 1 < h) {
          form(y + 1, halo_down);
          down = halo_down;
        }
        const Vec4* up = y == 0 ? nullptr : y == y0 ? halo_up : mid - w;
        row_pq[size_t(y)] = stencil_row(A, y, up, mid, down, q + size_t(y) * size_t(w));
      }
      sync();
      Vec4 alpha = zero;
      {
        const Vec4d pq = total(row_pq);
        for (int c = 0; c < 3; ++c) alpha[c] = my_active[c] && pq[c] > 0.0 ? float(my_rz[c] / pq[c]) : 0.0f;
      }
      // x += alpha p, r -= alpha q, r.r. (The next V-cycle's first red half-sweep is its
      // own first step: written here, z would be one more stream per iteration.)
      for (int y = y0; y < y1; ++y) {
        const size_t base = size_t(y) * size_t(w);
        Vec4d srr;
        for (size_t i = base; i < base + size_t(w); ++i) {
          x[i] += alpha * pn[i];
          r[i] -= alpha * q[i];
          accumulate(srr, r[i] * r[i]);
        }
        row_rr[size_t(y)] = srr;
      }
      sync();
      {
        const Vec4d s = total(row_rr);
        for (int c = 0; c < 3; ++c) {
          if (!my_active[c]) continue;
          my_rr[c] = s[c];
          my_active[c] = std::sqrt(my_rr[c]) > my_limit[c];
        }
      }
      std::swap(po, pn);
      ++my_it;
    }
    if (t == 0) {
      for (int c = 0; c < 3; ++c) {
        rr[c] = my_rr[c];
        bb[c] = my_bb[c];
        active[c] = my_active[c];
      }
      it = my_it;
    }
  });

  return cg_stats(it, active, rr, bb);
}

}  // namespace dp::reconstruct
