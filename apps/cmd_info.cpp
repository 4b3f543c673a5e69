// `deltapath info SCENE`: size, counts, capability flags and bounding box.
#include <cstdio>

#include "apps/commands.h"
#include "manifold/mesh_normals.h"
#include "scene/loaders/loader.h"

namespace dp::apps {

namespace {
void run_info(const std::string& path) {
  const auto s = scene::load_scene(path, {manifold::normal_estimation_hook()});
  const auto& cam = s->camera();
  const auto& caps = s->caps();
  const auto& b = s->bounds();
  size_t meshes = 0, spheres = 0;
  for (const auto& shape : s->shapes()) (shape->kind() == scene::ShapeKind::mesh ? meshes : spheres)++;
  std::printf("scene:      %s\n", path.c_str());
  std::printf("resolution: %d x %d\n", cam.width(), cam.height());
  std::printf("shapes:     %zu (%zu meshes, %zu spheres), %zu triangles, %zu degenerate skipped\n", s->shapes().size(),
              meshes, spheres, s->triangle_count(), s->degenerate_triangles_skipped());
  std::printf("materials:  %zu\n", s->bsdfs().size());
  std::printf("emitters:   %zu\n", s->emitters().size());
  std::printf("media:      %zu\n", s->media().size());
  std::printf("bounds:     [%g %g %g] - [%g %g %g]\n", double(b.lo.x()), double(b.lo.y()), double(b.lo.z()),
              double(b.hi.x()), double(b.hi.y()), double(b.hi.z()));
  std::printf("caps:       has_specular=%d has_glossy=%d has_media=%d has_textures=%d has_delta_lights=%d has_env=%d\n",
              caps.has_specular, caps.has_glossy, caps.has_media, caps.has_textures, caps.has_delta_lights,
              caps.has_env);
  std::printf("integrator: %s, max_depth %d\n", s->integrator_defaults().type.c_str(), s->integrator_defaults().max_depth);
}
}  // namespace

void register_info(CLI::App& app) {
  auto path = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("info", "print scene size, counts, capability flags and bounds");
  cmd->add_option("scene", *path, "scene file")->required();
  cmd->callback([path] { run_info(*path); });
}

}  // namespace dp::apps
