// Manzi et al. 2014, Fig. 11: eigenvectors of the reconstruction's Laplacian H^T H for
// the standard 4-neighbour kernel and for the structure-adaptive kernel (Sec. 3.5) of a
// small image crop. The low-frequency eigenvectors of the standard kernel ignore the
// scene's structure; the adaptive kernel's follow its edges (pairs do not cross them), so
// noise in those modes stays inside regions.
//
//   manzi2014_fig11 SCENE OUT.png [--crop X Y W H] [--count N] [--feature-spp S]
//
// Features (normal, albedo, depth) are rendered at the scene's resolution, the crop taken
// and re-normalized to [0, 1], both kernels built on it, and the N eigenvectors of
// H^T H + 1e-6 I with the smallest eigenvalues (the first is the constant image for a
// connected kernel) drawn as rows of tiles: standard kernel on top, adaptive below, each
// tile mapped from [-max|v|, max|v|] to [0, 1] and drawn 3x enlarged. The eigenvalues are printed. Dense solve:
// keep W H <= ~2500.
#include <Eigen/Dense>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>

#include "core/image.h"
#include "core/image_io.h"
#include "kernels_adaptive/features.h"
#include "kernels_adaptive/pair_kernel.h"
#include "scene/loaders/loader.h"

using namespace dp;

namespace {

constexpr int kZoom = 3;  // pixels per crop pixel in the figure

kernels_adaptive::Features crop(const kernels_adaptive::Features& f, int x0, int y0, int w, int h) {
  kernels_adaptive::Features c;
  c.width = w;
  c.height = h;
  for (int y = y0; y < y0 + h; ++y)
    for (int x = x0; x < x0 + w; ++x) {
      const size_t i = size_t(y) * size_t(f.width) + size_t(x);
      c.normal.push_back(f.normal[i]);
      c.albedo.push_back(f.albedo[i]);
      c.depth.push_back(f.depth[i]);
    }
  kernels_adaptive::normalize_features(c);
  return c;
}

Eigen::MatrixXd laplacian(const kernels_adaptive::PairKernel& k) {
  const int n = k.width * k.height;
  Eigen::MatrixXd L = Eigen::MatrixXd::Identity(n, n) * 1e-6;
  for (const auto& r : k.rows) {  // (H I)_r = I[b] - I[a]: H^T H += (e_b - e_a)(e_b - e_a)^T
    L(r.i, r.i) += 1;
    L(r.j, r.j) += 1;
    L(r.i, r.j) -= 1;
    L(r.j, r.i) -= 1;
  }
  return L;
}

void draw(const kernels_adaptive::PairKernel& k, int count, int row, const char* label, core::Image& out) {
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(laplacian(k));
  std::printf("%s kernel (%zu rows): smallest eigenvalues", label, k.rows.size());
  for (int e = 0; e < count; ++e) {
    const Eigen::VectorXd v = es.eigenvectors().col(e);
    std::printf(" %.4g", es.eigenvalues()(e));
    const double m = std::max(1e-12, v.cwiseAbs().maxCoeff());
    for (int y = 0; y < k.height; ++y)
      for (int x = 0; x < k.width; ++x) {
        const float t = float(0.5 + 0.5 * v(y * k.width + x) / m);
        for (int sy = 0; sy < kZoom; ++sy)
          for (int sx = 0; sx < kZoom; ++sx)
            out((e * (k.width + 2) + x) * kZoom + sx, (row * (k.height + 2) + y) * kZoom + sy) = Rgb::Constant(t);
      }
  }
  std::printf("\n");
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc < 3) {
      std::fprintf(stderr, "usage: %s SCENE OUT.png [--crop X Y W H] [--count N] [--feature-spp S]\n", argv[0]);
      return 2;
    }
    int x0 = -1, y0 = -1, w = 40, h = 30, count = 6, spp = 16;
    for (int a = 3; a < argc; ++a) {
      const std::string o = argv[a];
      if (o == "--crop" && a + 4 < argc) {
        x0 = std::atoi(argv[++a]);
        y0 = std::atoi(argv[++a]);
        w = std::atoi(argv[++a]);
        h = std::atoi(argv[++a]);
      } else if (o == "--count" && a + 1 < argc) {
        count = std::atoi(argv[++a]);
      } else if (o == "--feature-spp" && a + 1 < argc) {
        spp = std::atoi(argv[++a]);
      } else {
        std::fprintf(stderr, "unknown or incomplete option '%s'\n", o.c_str());
        return 2;
      }
    }
    const auto scene = scene::load_scene(argv[1]);
    const int sw = scene->camera().width(), sh = scene->camera().height();
    if (x0 < 0) x0 = (sw - w) / 2, y0 = (sh - h) / 2;
    if (w < 2 || h < 2 || x0 < 0 || y0 < 0 || x0 + w > sw || y0 + h > sh || w * h > 4000 || count < 1 ||
        count > w * h) {
      std::fprintf(stderr, "%s: crop %d %d %d %d does not fit the %dx%d image (or is larger than 4000 pixels)\n",
                   argv[1], x0, y0, w, h, sw, sh);
      return 2;
    }
    const auto features = crop(kernels_adaptive::render_features(*scene, spp, 1, 0), x0, y0, w, h);
    core::Image out(count * (w + 2) * kZoom, 2 * (h + 2) * kZoom, Rgb(1.0f, 0.2f, 0.2f));  // red gutters
    draw(kernels_adaptive::standard_kernel(w, h), count, 0, "standard", out);
    draw(kernels_adaptive::adaptive_kernel(features), count, 1, "adaptive", out);
    core::write_png(argv[2], out);
    std::printf("wrote %s (top: standard, bottom: adaptive; crop %d %d %d %d)\n", argv[2], x0, y0, w, h);
    return 0;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
}
