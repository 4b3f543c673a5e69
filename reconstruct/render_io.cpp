#include "reconstruct/render_io.h"

#include "core/error.h"
#include "core/image_io.h"

namespace dp::reconstruct {

namespace {

void check_sizes(const GradientImages& g, const std::string& where) {
  const auto size = [](const core::Image& im) {
    return std::to_string(im.width()) + "x" + std::to_string(im.height());
  };
  const bool pairs = !g.pairs.values.empty();
  if ((!pairs && (!g.primal.same_size(g.dx) || !g.primal.same_size(g.dy))) ||
      (pairs && !g.primal.same_size(g.pairs.values[0])) || (g.direct && !g.primal.same_size(*g.direct)))
    throw ValueError("layer sizes differ: primal " + size(g.primal) +
                         (pairs ? ", pairs.0 " + size(g.pairs.values[0]) : ", dx " + size(g.dx) + ", dy " + size(g.dy)) +
                         (g.direct ? ", direct " + size(*g.direct) : std::string()),
                     where);
  if (g.primal.empty()) throw ValueError("the primal image is empty", where);
}

}  // namespace

GradientImages read_gradient_render(const std::string& path) {
  std::vector<core::NamedLayer> layers = core::read_exr_layers(path);
  const auto take = [&](const std::string& name) -> std::optional<core::Image> {
    for (auto& l : layers)
      if (l.name == name) return std::move(l.image);
    return std::nullopt;
  };
  GradientImages g;
  std::string present;
  for (const auto& l : layers) present += (present.empty() ? "" : ", ") + (l.name.empty() ? "<main>" : l.name);
  g.pairs = take_pair_layers(layers);
  const bool pairs = !g.pairs.values.empty();
  for (const char* name : {"primal", "dx", "dy"}) {
    if (pairs && name[0] == 'd') continue;
    std::optional<core::Image> im = take(name);
    if (!im)
      throw IoError(std::string("missing layer '") + name +
                        "' (a gradient render needs primal and dx, dy or pairs.<k>, pairs.<k>.offset; found: " +
                        (present.empty() ? "none" : present) + ")",
                    path);
    (name[0] == 'p' ? g.primal : name[1] == 'x' ? g.dx : g.dy) = std::move(*im);
  }
  g.direct = take("direct");
  check_sizes(g, path);
  if (g.direct) g.primal -= *g.direct;  // the layer holds indirect + direct (see the header)
  return g;
}

Problem make_render_problem(GradientImages images, float alpha, const std::string& where) {
  if (images.pairs.values.empty()) return make_grid_problem(std::move(images.primal), images.dx, images.dy, alpha);
  Problem p;
  decode_pair_layers(images.pairs, p.kernel, p.b, where);
  p.primal = std::move(images.primal);
  p.alpha = alpha;
  validate(p);
  return p;
}

GradientImages read_gradient_images(const std::string& primal, const std::string& dx, const std::string& dy) {
  GradientImages g;
  g.primal = core::read_exr(primal);
  g.dx = core::read_exr(dx);
  g.dy = core::read_exr(dy);
  check_sizes(g, primal);
  return g;
}

GradientImages read_pair_images(const std::string& primal, const std::string& pairs) {
  GradientImages g;
  g.primal = core::read_exr(primal);
  std::vector<core::NamedLayer> layers = core::read_exr_layers(pairs);
  g.pairs = take_pair_layers(layers);
  if (g.pairs.values.empty()) throw IoError("no pair layers pairs.0, pairs.0.offset", pairs);
  check_sizes(g, pairs);
  return g;
}

}  // namespace dp::reconstruct
