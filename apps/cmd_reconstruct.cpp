#include "apps/cmd_reconstruct.h"

#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>

#include "apps/cli_checks.h"
#include "core/error.h"
#include "core/image_io.h"
#include "core/log.h"
#include "reconstruct/render_io.h"
#include "reconstruct/solve.h"

namespace dp::apps {

namespace {

struct ReconstructArgs {
  std::string in, primal, dx, dy, pairs, out;
  // L1 is the reference code's robust default (Lehtinen 2013 Sec. 5); l2 is unbiased.
  std::string norm = "l1";
  float alpha = reconstruct::kDefaultAlpha;  // 0.2; 0.3-0.4 keeps sub-pixel detail
  float symmetric_weight = 1.0f;             // weight of rows whose reversed pair is a row too
  int threads = 0;                           // 0 = all hardware threads
};

void run_reconstruct(const ReconstructArgs& a) {
  const bool separate = !a.primal.empty() || !a.dx.empty() || !a.dy.empty() || !a.pairs.empty();
  if (a.in.empty() == !separate)
    throw Error("reconstruct: give either --in RENDER.exr, or --primal with --dx and --dy or with --pairs");
  const bool grid = !a.dx.empty() || !a.dy.empty();
  if (separate && (a.primal.empty() || (grid && !a.pairs.empty()) ||
                   (grid ? (a.dx.empty() || a.dy.empty()) : a.pairs.empty())))
    throw Error("reconstruct: --primal needs either both --dx and --dy or --pairs");
  if (a.norm != "l1" && a.norm != "l2") throw ValueError("reconstruct: --norm must be l1 or l2, got '" + a.norm + "'");
  const std::filesystem::path out(a.out);
  if (out.extension() != ".exr") throw ValueError("reconstruct: --out must name an .exr file", a.out);

  reconstruct::GradientImages g = !separate ? reconstruct::read_gradient_render(a.in)
                                  : grid    ? reconstruct::read_gradient_images(a.primal, a.dx, a.dy)
                                            : reconstruct::read_pair_images(a.primal, a.pairs);
  std::optional<core::Image> direct = std::move(g.direct);
  reconstruct::Problem problem = reconstruct::make_render_problem(std::move(g), a.alpha, separate ? a.primal : a.in);
  if (a.symmetric_weight != 1.0f)
    problem.row_weights = reconstruct::reversed_pair_weights(problem.kernel, a.symmetric_weight);
  reconstruct::SolveOptions options;
  options.threads = a.threads;
  const reconstruct::SolveResult r =
      a.norm == "l1" ? reconstruct::solve_l1(problem, options) : reconstruct::solve_l2(problem, options);
  core::Image image = r.image;
  if (direct) {
    const size_t bad = direct->zero_nonfinite();
    if (bad) log::warn("reconstruct: ", bad, " non-finite pixels in the direct layer were set to 0");
    image += *direct;
  }
  core::write_exr(out.string(), image);
  std::filesystem::path png = out;
  png.replace_extension(".png");
  core::write_png(png.string(), image);
  std::printf("reconstruct: %s (%s, alpha %g) %dx%d in %.3f s, %d CG iterations%s; wrote %s and %s\n",
              a.norm.c_str(), r.method.c_str(), double(a.alpha), image.width(), image.height(), r.seconds,
              r.cg_iterations, direct ? ", direct added" : "", out.string().c_str(), png.string().c_str());
  if (r.input.nonfinite_primal_pixels || r.input.nonfinite_rows)
    std::printf("reconstruct: ignored %lld primal pixels and %lld gradient values with NaN/Inf\n",
                static_cast<long long>(r.input.nonfinite_primal_pixels),
                static_cast<long long>(r.input.nonfinite_rows));
}

}  // namespace

void register_reconstruct(CLI::App& app) {
  auto args = std::make_shared<ReconstructArgs>();
  CLI::App* cmd = app.add_subcommand("reconstruct", "screened Poisson reconstruction (L1 or L2) of a gradient render");
  cmd->add_option("--in", args->in,
                  "gradient render EXR with layers primal and dx, dy or pairs.<k>, pairs.<k>.offset [, direct]");
  cmd->add_option("--primal", args->primal, "primal image EXR (with --dx, --dy)");
  cmd->add_option("--dx", args->dx, "horizontal differences I(x+1,y) - I(x,y), EXR");
  cmd->add_option("--dy", args->dy, "vertical differences I(x,y+1) - I(x,y), EXR");
  cmd->add_option("--pairs", args->pairs,
                  "pair-gradient EXR of any pixel-pair kernel (with --primal): layers pairs.<k> (value I[b] - I[a] "
                  "at pixel b) and pairs.<k>.offset (the pair list: a - b in R, G; B = 1 where the row exists)");
  cmd->add_option("--norm", args->norm, "l1 (robust, default) or l2 (unbiased)");
  cmd->add_option("--alpha", args->alpha, "weight of the primal image (default 0.2)");
  cmd->add_option("--symmetric-weight", args->symmetric_weight,
                  "weight of each row whose reversed pair is also a row (gdmlt's symmetric_weight; default 1)");
  cmd->add_option("--threads", args->threads, "worker threads (0 = all)")->check(thread_count());
  cmd->add_option("--out", args->out, "output EXR (a PNG preview is written beside it)")->required();
  cmd->callback([args] { run_reconstruct(*args); });
}

}  // namespace dp::apps
