#include "reconstruct/render_io.h"

#include "core/error.h"
#include "core/image_io.h"

namespace dp::reconstruct {

namespace {

void check_sizes(const GradientImages& g, const std::string& where) {
  const auto size = [](const core::Image& im) {
    return std::to_string(im.width()) + "x" + std::to_string(im.height());
  };
  if (!g.primal.same_size(g.dx) || !g.primal.same_size(g.dy) || (g.direct && !g.primal.same_size(*g.direct)))
    throw ValueError("layer sizes differ: primal " + size(g.primal) + ", dx " + size(g.dx) + ", dy " + size(g.dy) +
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
  for (const char* name : {"primal", "dx", "dy"}) {
    std::optional<core::Image> im = take(name);
    if (!im)
      throw IoError(std::string("missing layer '") + name + "' (a gradient render needs primal, dx, dy; found: " +
                        (present.empty() ? "none" : present) + ")",
                    path);
    (name[0] == 'p' ? g.primal : name[1] == 'x' ? g.dx : g.dy) = std::move(*im);
  }
  g.direct = take("direct");
  check_sizes(g, path);
  return g;
}

GradientImages read_gradient_images(const std::string& primal, const std::string& dx, const std::string& dy) {
  GradientImages g;
  g.primal = core::read_exr(primal);
  g.dx = core::read_exr(dx);
  g.dy = core::read_exr(dy);
  check_sizes(g, primal);
  return g;
}

}  // namespace dp::reconstruct
