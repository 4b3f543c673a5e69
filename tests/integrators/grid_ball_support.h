// Shared by the grid-media render tests (test_volpath_grid, test_bdpt_grid): a sphere
// (index-matched boundary) of smoke under a uniform environment above a diffuse floor at
// 32x32, as a homogeneous medium and as grid media written here (a constant grid of
// density 1 with the same sigma_t and albedo, and a ramp along x), and the image's
// block statistics for Welch tests.
#pragma once

#include <filesystem>
#include <memory>
#include <string>
#include <unistd.h>
#include <vector>

#include "core/image.h"
#include "integrators/integrator.h"
#include "scene/loaders/loader.h"
#include "scene/media/density_grid.h"

namespace dp::test {

inline std::string grid_ball_scene_text(const std::string& medium) {
  return "version: 1\n"
         "camera: {position: [0, 1.5, 5], look_at: [0, 0.3, 0], fov: 40, resolution: [32, 32]}\n"
         "materials: {floor: {type: diffuse, albedo: [0.7, 0.7, 0.7]}}\n"
         "media:\n  smoke: " + medium + "\n"
         "shapes:\n"
         "  - {type: quad, vertices: [[-4, -1, -4], [-4, -1, 4], [4, -1, 4], [4, -1, -4]], material: floor}\n"
         "  - {type: sphere, center: [0, 0, 0], radius: 1, material: none, interior: smoke}\n"
         "lights: [{type: environment, radiance: [1, 1, 1]}]\n";
}

// The image mean (of the channel sums), then the block x block means.
inline std::vector<double> image_blocks(const core::Image& img, int block) {
  std::vector<double> out;
  double total = 0;
  for (const auto& p : img.pixels()) total += double(p.sum());
  out.push_back(total / double(img.size()));
  for (int by = 0; by < img.width() / block; ++by)
    for (int bx = 0; bx < img.width() / block; ++bx) {
      double s = 0;
      for (int y = by * block; y < (by + 1) * block; ++y)
        for (int x = bx * block; x < (bx + 1) * block; ++x) s += double(img(x, y).sum());
      out.push_back(s / (block * block));
    }
  return out;
}

// The three scenes of the tests (the .vol files in a temporary folder, removed after).
struct GridBallScenes {
  std::filesystem::path dir;
  std::unique_ptr<scene::Scene> homogeneous, grid, ramp;
  explicit GridBallScenes(const std::string& tag) {
    dir = std::filesystem::temp_directory_path() / ("dp_" + tag + "_" + std::to_string(::getpid()));
    std::filesystem::create_directories(dir);
    scene::DensityGrid g;
    g.nx = g.ny = g.nz = 4;
    g.lo = Vec3(-1.2f, -1.2f, -1.2f);
    g.hi = Vec3(1.2f, 1.2f, 1.2f);
    g.values.assign(64, 1.0f);
    g.finalize("test");
    scene::write_vol_file((dir / "one.vol").string(), g);
    for (int z = 0; z < 4; ++z)  // a ramp along x from 0 to 3
      for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x) g.values[size_t((z * 4 + y) * 4 + x)] = float(x);
    g.finalize("test");
    scene::write_vol_file((dir / "ramp.vol").string(), g);
    const std::string path = (dir / "s.yaml").string();
    homogeneous = scene::load_scene_yaml_string(
        grid_ball_scene_text("{type: homogeneous, sigma_a: [0.2, 0.6, 1.0], sigma_s: [1.8, 1.4, 1.0], phase: {type: hg, g: 0.3}}"),
        path);
    grid = scene::load_scene_yaml_string(
        grid_ball_scene_text("{type: grid, file: one.vol, sigma_t: 2, albedo: [0.9, 0.7, 0.5], phase: {type: hg, g: 0.3}}"), path);
    ramp = scene::load_scene_yaml_string(
        grid_ball_scene_text("{type: grid, file: ramp.vol, sigma_t: 2, albedo: [0.9, 0.7, 0.5], phase: {type: hg, g: 0.3}}"),
                                         path);
  }
  ~GridBallScenes() { std::filesystem::remove_all(dir); }
};
 
// The render options of these tests: spp, seed, 2 threads, max_depth 8, quiet.
inline integrators::RenderOptions grid_render_options(int spp, uint64_t seed) {
  integrators::RenderOptions opt;
  opt.spp = spp;
  opt.seed = seed;
  opt.threads = 2;
  opt.max_depth = 8;
  opt.quiet = true;
  return opt;
}

}  // namespace dp::test
