#include "reconstruct/multigrid.h"

#include <algorithm>
#include <barrier>
#include <cmath>

#include "core/error.h"
#include "reconstruct/laplacian.h"

namespace dp::reconstruct {

namespace {

size_t pixels(const GridMultigrid::Level& L) { return size_t(L.w) * size_t(L.h); }

// Red-black Gauss-Seidel on row y for the pixels with (x + y) % 2 == color:
// x_i = (b_i + sum_j w_ij x_j) / d_i over the 4 neighbours.
void relax_row(const GridMultigrid::Level& L, const Vec4* b, Vec4* x, int y, int color) {
  const int w = L.w;
  const size_t base = size_t(y) * size_t(w);
  const float* wx = L.wx + base;
  const float* wy = L.wy + base;
  const float* wu = y > 0 ? L.wy + base - size_t(w) : nullptr;
  const float* id = L.inv_diag.data() + base;
  const Vec4* bb = b + base;
  Vec4* xx = x + base;
  const Vec4* up = y > 0 ? xx - w : nullptr;
  const Vec4* down = y + 1 < L.h ? xx + w : nullptr;
  const auto pixel = [&](int i) {
    Vec4 s = bb[i];
    if (i > 0) s += wx[i - 1] * xx[i - 1];
    if (i + 1 < w) s += wx[i] * xx[i + 1];
    if (up) s += wu[i] * up[i];
    if (down) s += wy[i] * down[i];
    xx[i] = s * id[i];
  };
  int i = (color + y) & 1;
  if (i == 0) {
    pixel(0);
    i = 2;
  }
  if (up && down) {
    for (; i + 1 < w; i += 2)
      xx[i] = (bb[i] + wx[i - 1] * xx[i - 1] + wx[i] * xx[i + 1] + wu[i] * up[i] + wy[i] * down[i]) * id[i];
  } else {
    for (; i + 1 < w; i += 2) pixel(i);
  }
  if (i < w) pixel(i);
}

// The first red half-sweep from x = 0: x_i = b_i / d_i on red pixels, 0 on black ones.
void first_red_row(const GridMultigrid::Level& L, const Vec4* b, Vec4* x, int y) {
  const size_t base = size_t(y) * size_t(L.w);
  const float* id = L.inv_diag.data() + base;
  const Vec4 zero = {};
  for (int i = 0; i < L.w; ++i) x[base + size_t(i)] = ((i + y) & 1) ? zero : b[base + size_t(i)] * id[i];
}

// Residual b - A x of fine row y into res[0..w).
void residual_row(const GridMultigrid::Level& f, const Vec4* b, const Vec4* x, int y, Vec4* res) {
  const int w = f.w;
  const size_t base = size_t(y) * size_t(w);
  const float* wx = f.wx + base;
  const float* wy = f.wy + base;
  const float* wu = y > 0 ? f.wy + base - size_t(w) : nullptr;
  const float* dg = f.diag + base;
  const Vec4* bb = b + base;
  const Vec4* xx = x + base;
  const Vec4* up = y > 0 ? xx - w : nullptr;
  const Vec4* down = y + 1 < f.h ? xx + w : nullptr;
  const auto pixel = [&](int i) {
    Vec4 s = bb[i] - dg[i] * xx[i];
    if (i > 0) s += wx[i - 1] * xx[i - 1];
    if (i + 1 < w) s += wx[i] * xx[i + 1];
    if (up) s += wu[i] * up[i];
    if (down) s += wy[i] * down[i];
    res[i] = s;
  };
  if (w < 3 || !up || !down) {
    for (int i = 0; i < w; ++i) pixel(i);
    return;
  }
  pixel(0);
  for (int i = 1; i + 1 < w; ++i)
    res[i] = bb[i] - dg[i] * xx[i] + wx[i - 1] * xx[i - 1] + wx[i] * xx[i + 1] + wu[i] * up[i] + wy[i] * down[i];
  pixel(w - 1);
}

// Coarse row Y = y / 2 of the restricted residual: the 2x2 block sums of b - A x over
// fine rows 2Y and 2Y+1 (if present), always added in the same order. Runs when the
// pipeline reaches the block's last fine row y; `tmp` holds 2 fine rows.
void restrict_row(const GridMultigrid::Level& f, const Vec4* b, const Vec4* x, GridMultigrid::Level& c, int y,
                  Vec4* tmp) {
  if ((y & 1) == 0 && y + 1 < f.h) return;  // the block's second row comes later
  const int w = f.w, Y = y >> 1;
  Vec4* r0 = tmp;
  Vec4* r1 = tmp + w;
  residual_row(f, b, x, 2 * Y, r0);
  const bool two = 2 * Y + 1 < f.h;
  if (two) residual_row(f, b, x, 2 * Y + 1, r1);
  Vec4* out = c.b.data() + size_t(Y) * size_t(c.w);
  for (int X = 0; X < c.w; ++X) {
    const int i = 2 * X;
    const bool right = i + 1 < w;
    Vec4 s = right ? r0[i] + r0[i + 1] : r0[i];
    if (two) s += right ? r1[i] + r1[i + 1] : r1[i];
    out[X] = s;
  }
}

// x += P e on fine row y (the coarse value of the pixel's 2x2 block).
void prolong_row(const GridMultigrid::Level& f, Vec4* x, const GridMultigrid::Level& c, int y) {
  const size_t base = size_t(y) * size_t(f.w);
  const Vec4* e = c.x.data() + size_t(y >> 1) * size_t(c.w);
  for (int i = 0; i < f.w; ++i) x[base + size_t(i)] += e[i >> 1];
}

}  // namespace

void GridMultigrid::build(const GridOperator& A, int threads) {
  threads = resolve_threads(threads);
  const int w0 = A.width(), h0 = A.height();
  if (m_levels.empty() || m_levels[0].w != w0 || m_levels[0].h != h0 || m_built_coarsest != coarsest_pixels) {
    m_levels.clear();
    m_built_coarsest = coarsest_pixels;
    int w = w0, h = h0;
    for (;;) {
      Level L;
      L.w = w;
      L.h = h;
      L.inv_diag.resize(size_t(w) * size_t(h));
      if (!m_levels.empty()) {
        const size_t n = size_t(w) * size_t(h);
        L.own_wx.resize(n);
        L.own_wy.resize(n);
        L.own_diag.resize(n);
        L.own_data.resize(n);
        L.x.resize(n);
        L.b.resize(n);
      }
      m_levels.push_back(std::move(L));
      if (size_t(w) * size_t(h) <= coarsest_pixels || (w == 1 && h == 1)) break;
      w = (w + 1) / 2;
      h = (h + 1) / 2;
    }
    for (Level& L : m_levels)
      if (!L.own_wx.empty()) {
        L.wx = L.own_wx.data();
        L.wy = L.own_wy.data();
        L.diag = L.own_diag.data();
        L.data = L.own_data.data();
      }
  }
  Level& L0 = m_levels[0];
  L0.wx = A.weights_x();
  L0.wy = A.weights_y();
  L0.diag = A.diagonal();
  L0.data = A.data_weights();
  {
    const size_t n = pixels(L0);
    run_team(threads, [&](int t) {
      for (size_t i = part_begin(n, threads, t), i1 = part_begin(n, threads, t + 1); i < i1; ++i)
        L0.inv_diag[i] = L0.diag[i] > 0.0f ? 1.0f / L0.diag[i] : 0.0f;
    });
  }
  for (size_t l = 1; l < m_levels.size(); ++l) {
    const Level& f = m_levels[l - 1];
    Level& c = m_levels[l];
    const int W = c.w, H = c.h, w = f.w, h = f.h;
    const int team = pixels(c) >= serial_pixels ? threads : 1;
    run_team(team, [&](int t) {
      for (int Y = int(part_begin(size_t(H), team, t)), Y1 = int(part_begin(size_t(H), team, t + 1)); Y < Y1; ++Y)
        for (int X = 0; X < W; ++X) {
          const size_t I = size_t(Y) * size_t(W) + size_t(X);
          const size_t i00 = size_t(2 * Y) * size_t(w) + size_t(2 * X);
          const bool right = 2 * X + 1 < w, below = 2 * Y + 1 < h;
          // Edges between blocks: the two fine edges leaving the block's right column
          // (resp. bottom row); data: the block's sum.
          float wx = 0.0f, wy = 0.0f, d = f.data[i00];
          if (right) d += f.data[i00 + 1];
          if (below) d += f.data[i00 + size_t(w)];
          if (right && below) d += f.data[i00 + size_t(w) + 1];
          if (X + 1 < W) {
            wx = f.wx[i00 + 1];
            if (below) wx += f.wx[i00 + size_t(w) + 1];
          }
          if (Y + 1 < H) {
            wy = f.wy[i00 + size_t(w)];
            if (right) wy += f.wy[i00 + size_t(w) + 1];
          }
          c.own_wx[I] = wx;
          c.own_wy[I] = wy;
          c.own_data[I] = d;
        }
    });
    run_team(team, [&](int t) {
      for (int Y = int(part_begin(size_t(H), team, t)), Y1 = int(part_begin(size_t(H), team, t + 1)); Y < Y1; ++Y)
        for (int X = 0; X < W; ++X) {
          const size_t I = size_t(Y) * size_t(W) + size_t(X);
          float d = c.own_data[I] + c.own_wx[I] + c.own_wy[I];
          if (X > 0) d += c.own_wx[I - 1];
          if (Y > 0) d += c.own_wy[I - size_t(W)];
          c.own_diag[I] = d;
          c.inv_diag[I] = d > 0.0f ? 1.0f / d : 0.0f;
        }
    });
  }
}

namespace {

// One step of a sweep sequence applied to a single row (see run_steps).
struct Step {
  enum Kind { first_red, relax, restrict_residual, prolong, dot } kind;
  int color = 0;
};

// Applies steps[0..k) to rows [y0, y1) of level L in one pass: step j runs on row y - j
// while step 0 runs on row y, so each row is loaded once for the whole sequence (the
// sweeps are memory bound). Step j on row y needs step j-1 on rows y-1..y+1, so next to a
// border shared with another thread (top_shared / bottom_shared) step j waits for the
// neighbour: it is deferred on the j rows nearest that border and run after j barriers.
// `sync` is only called when a border is shared.
void run_steps(const GridMultigrid::Level& L, const Vec4* b, Vec4* x, GridMultigrid::Level* C, const Step* steps,
               int k, int y0, int y1, bool top_shared, bool bottom_shared, const std::function<void()>& sync,
               Vec4d* row_dot) {
  std::vector<Vec4> tmp;
  for (int j = 0; j < k; ++j)
    if (steps[j].kind == Step::restrict_residual) tmp.resize(2 * size_t(L.w));
  const auto run = [&](int j, int y) {
    const Step& st = steps[j];
    switch (st.kind) {
      case Step::first_red:
        first_red_row(L, b, x, y);
        break;
      case Step::relax:
        relax_row(L, b, x, y, st.color);
        break;
      case Step::restrict_residual:
        restrict_row(L, b, x, *C, y, tmp.data());
        break;
      case Step::prolong:
        prolong_row(L, x, *C, y);
        break;
      case Step::dot: {
        const size_t base = size_t(y) * size_t(L.w);
        Vec4d s;
        for (int i = 0; i < L.w; ++i) accumulate(s, b[base + size_t(i)] * x[base + size_t(i)]);
        row_dot[y] = s;
        break;
      }
    }
  };
  // The restriction of fine row y also reads back to row y - 2 (its block's first row's
  // upper neighbour): one more row of margin at the top.
  const auto lo = [&](int j) {
    return y0 + (top_shared ? j + (steps[j].kind == Step::restrict_residual ? 1 : 0) : 0);
  };
  const auto hi = [&](int j) { return y1 - (bottom_shared ? j : 0); };
  for (int y = y0; y < y1 + k - 1; ++y)
    for (int j = 0; j < k; ++j) {
      const int row = y - j;
      if (row >= lo(j) && row < hi(j)) run(j, row);
    }
  if (!top_shared && !bottom_shared) return;
  for (int j = 1; j < k; ++j) {
    sync();
    for (int row = y0; row < std::min(lo(j), y1); ++row) run(j, row);
    for (int row = std::max(hi(j), std::max(lo(j), y0)); row < y1; ++row) run(j, row);
  }
}

}  // namespace

int GridMultigrid::row_alignment() const {
  int a = 2;
  for (size_t l = 1; l < m_levels.size() && pixels(m_levels[l]) >= serial_pixels; ++l) a *= 2;
  return a;
}

void GridMultigrid::cycle(size_t l, const Vec4* b, Vec4* x, const std::vector<int>& rows, int t, int threads,
                          const std::function<void()>& sync, bool first_red_done, Vec4d* row_dot) {
  const Level& L = m_levels[l];
  const auto range = [&](size_t level, int tt) {
    return tt == threads ? m_levels[level].h : std::min(m_levels[level].h, rows[size_t(tt)] >> level);
  };
  const int y0 = range(l, t), y1 = range(l, t + 1);
  const bool top = y0 > 0 && threads > 1, bottom = y1 < L.h && threads > 1;
  std::vector<Step> steps;
  steps.reserve(size_t(4 * std::max(pre_sweeps, coarsest_sweeps) + 3));
  if (l + 1 == m_levels.size()) {
    // Coarsest level (one thread): palindromic R B (R B)^(k-1) (B R)^k.
    if (!first_red_done) steps.push_back({Step::first_red, 0});
    steps.push_back({Step::relax, 1});
    for (int i = 1; i < coarsest_sweeps; ++i) {
      steps.push_back({Step::relax, 0});
      steps.push_back({Step::relax, 1});
    }
    for (int i = 0; i < coarsest_sweeps; ++i) {
      steps.push_back({Step::relax, 1});
      steps.push_back({Step::relax, 0});
    }
    if (row_dot) steps.push_back({Step::dot, 0});
    run_steps(L, b, x, nullptr, steps.data(), int(steps.size()), y0, y1, top, bottom, sync, row_dot);
    return;
  }
  Level& C = m_levels[l + 1];
  // Pre-smoothing (red, black) x pre_sweeps from x = 0, then the residual summed into
  // the coarse right-hand side, all in one pass.
  if (!first_red_done) steps.push_back({Step::first_red, 0});
  steps.push_back({Step::relax, 1});
  for (int i = 1; i < pre_sweeps; ++i) {
    steps.push_back({Step::relax, 0});
    steps.push_back({Step::relax, 1});
  }
  steps.push_back({Step::restrict_residual, 0});
  run_steps(L, b, x, &C, steps.data(), int(steps.size()), y0, y1, top, bottom, sync, nullptr);
  sync();
  if (threads == 1 || pixels(C) < serial_pixels) {
    if (t == 0) {
      const std::function<void()> none = [] {};
      const std::vector<int> one = {0, C.h << (l + 1)};
      cycle(l + 1, C.b.data(), C.x.data(), one, 0, 1, none, false, nullptr);
    }
  } else {
    cycle(l + 1, C.b.data(), C.x.data(), rows, t, threads, sync, false, nullptr);
  }
  sync();
  // Coarse correction and post-smoothing (black, red) x pre_sweeps, one pass.
  steps.clear();
  steps.push_back({Step::prolong, 0});
  for (int i = 0; i < pre_sweeps; ++i) {
    steps.push_back({Step::relax, 1});
    steps.push_back({Step::relax, 0});
  }
  if (row_dot) steps.push_back({Step::dot, 0});
  run_steps(L, b, x, &C, steps.data(), int(steps.size()), y0, y1, top, bottom, sync, row_dot);
}

void GridMultigrid::vcycle(const Vec4* r, Vec4* z, const std::vector<int>& rows, int t, int threads,
                           const std::function<void()>& sync, bool first_red_done, Vec4d* row_dot) {
  cycle(0, r, z, rows, t, threads, sync, first_red_done, row_dot);
}

void GridMultigrid::apply(const Vec4* r, Vec4* z) {
  DP_CHECK(!m_levels.empty(), "GridMultigrid: build() first");
  const std::vector<int> rows = {0, m_levels[0].h};
  const std::function<void()> none = [] {};
  vcycle(r, z, rows, 0, 1, none, false, nullptr);
}

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

CgStats mg_pcg(const GridOperator& A, GridMultigrid& M, const Vec4* rhs, Vec4* x, const CgSettings& settings,
               CgWorkspace* workspace) {
  DP_CHECK(settings.max_iterations >= 0, "max_iterations must be >= 0");
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
  const GridMultigrid::Level& L0 = M.levels()[0];
  // z = the V-cycle's first red half-sweep of r on row y (fused into the CG update).
  const auto first_red = [&](int y) {
    const size_t base = size_t(y) * size_t(w);
    const float* id = L0.inv_diag.data() + base;
    const Vec4 zero = {};
    for (int i = 0; i < w; ++i) z[base + size_t(i)] = ((i + y) & 1) ? zero : r[base + size_t(i)] * id[i];
  };

  const Vec4 zero = {};
  double rr[3] = {}, bb[3] = {};
  bool active[3] = {false, false, false};
  int it = 0;

  run_team(threads, [&](int t) {
    const int y0 = rows[size_t(t)], y1 = rows[size_t(t) + 1];
    Vec4* halo_up = ws.scratch.data() + 2 * size_t(w) * size_t(t);
    Vec4* halo_down = halo_up + w;
    // r = rhs - A x, the norms of r and rhs.
    for (int y = y0; y < y1; ++y) {
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
      first_red(y);
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
      // z = M^-1 r (its first red half-sweep is already in z) and the row sums of r.z.
      M.vcycle(r, z, rows, t, threads, sync, true, row_rz.data());
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
      // x += alpha p, r -= alpha q, r.r, and the next V-cycle's first half-sweep.
      for (int y = y0; y < y1; ++y) {
        const size_t base = size_t(y) * size_t(w);
        Vec4d srr;
        for (size_t i = base; i < base + size_t(w); ++i) {
          x[i] += alpha * pn[i];
          r[i] -= alpha * q[i];
          accumulate(srr, r[i] * r[i]);
        }
        row_rr[size_t(y)] = srr;
        first_red(y);
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
