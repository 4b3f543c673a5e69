#include "reconstruct/multigrid.h"

#include <algorithm>
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
  const float* id = L.inv_diag + base;
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

// The first red half-sweep from x = 0 (x_i = b_i / d_i on red pixels) and the black
// half-sweep after it, on row y in one step: a black pixel's red neighbours are formed
// from b as b_j / d_j (the values the red half-sweep writes, bitwise), so the step reads
// no other row of x and needs no barrier between the two half-sweeps.
void first_red_black_row(const GridMultigrid::Level& L, const Vec4* b, Vec4* x, int y) {
  const int w = L.w;
  const size_t base = size_t(y) * size_t(w);
  const float* wx = L.wx + base;
  const float* wy = L.wy + base;
  const float* wu = y > 0 ? L.wy + base - size_t(w) : nullptr;
  const float* id = L.inv_diag + base;
  const float* id_up = y > 0 ? id - w : nullptr;
  const float* id_down = y + 1 < L.h ? id + w : nullptr;
  const Vec4* bb = b + base;
  const Vec4* up = y > 0 ? bb - w : nullptr;
  const Vec4* down = y + 1 < L.h ? bb + w : nullptr;
  Vec4* xx = x + base;
  const auto red = [&](int i) { return bb[i] * id[i]; };
  // Same sums in the same order as relax_row.
  const auto black = [&](int i) {
    Vec4 s = bb[i];
    if (i > 0) s += wx[i - 1] * red(i - 1);
    if (i + 1 < w) s += wx[i] * red(i + 1);
    if (up) s += wu[i] * (up[i] * id_up[i]);
    if (down) s += wy[i] * (down[i] * id_down[i]);
    xx[i] = s * id[i];
  };
  // Reads come from b only: the red and the black pixels can be written in any order.
  for (int i = y & 1; i < w; i += 2) xx[i] = red(i);
  int i = (y + 1) & 1;
  if (i == 0) {
    black(0);
    i = 2;
  }
  if (up && down) {
    for (; i + 1 < w; i += 2)
      xx[i] = (bb[i] + wx[i - 1] * red(i - 1) + wx[i] * red(i + 1) + wu[i] * (up[i] * id_up[i]) +
               wy[i] * (down[i] * id_down[i])) *
              id[i];
  } else {
    for (; i + 1 < w; i += 2) black(i);
  }
  if (i < w) black(i);
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
      if (!m_levels.empty()) {
        const size_t n = size_t(w) * size_t(h);
        L.own_wx.resize(n);
        L.own_wy.resize(n);
        L.own_diag.resize(n);
        L.own_data.resize(n);
        L.own_inv_diag.resize(n);
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
        L.inv_diag = L.own_inv_diag.data();
      }
  }
  Level& L0 = m_levels[0];
  L0.wx = A.weights_x();
  L0.wy = A.weights_y();
  L0.diag = A.diagonal();
  L0.data = A.data_weights();
  L0.inv_diag = A.inverse_diagonal();
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
          c.own_inv_diag[I] = d > 0.0f ? 1.0f / d : 0.0f;
        }
    });
  }
}

namespace {

// One step of a sweep sequence applied to a single row (see run_steps).
struct Step {
  enum Kind { first_red_black, relax, restrict_residual, prolong, dot } kind;
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
      case Step::first_red_black:
        first_red_black_row(L, b, x, y);
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
    steps.push_back(first_red_done ? Step{Step::relax, 1} : Step{Step::first_red_black, 0});
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
  steps.push_back(first_red_done ? Step{Step::relax, 1} : Step{Step::first_red_black, 0});
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

}  // namespace dp::reconstruct
