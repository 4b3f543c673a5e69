#include "experiments/reference.h"

#include <filesystem>
#include <fstream>
#include <sstream>

#include "core/error.h"
#include "core/image_io.h"
#include "core/log.h"
#include "core/timer.h"
#include "experiments/integrator_setup.h"

namespace dp::experiments {

namespace {
std::string read_bytes(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  if (!f) throw IoError("cannot read scene file", path);
  std::ostringstream ss;
  ss << f.rdbuf();
  return ss.str();
}

void check_size(const ExperimentConfig& config, const core::Image& img, const scene::Scene& scene,
                const std::string& what) {
  const auto& cam = scene.camera();
  if (img.width() != cam.width() || img.height() != cam.height())
    throw ValueError(what + " is " + std::to_string(img.width()) + "x" + std::to_string(img.height()) +
                         " but the scene renders " + std::to_string(cam.width()) + "x" + std::to_string(cam.height()),
                     config.file, config.reference.line);
}
}  // namespace

std::string reference_cache_name(const ExperimentConfig& config, const scene::Scene& scene) {
  const ReferenceSpec& r = config.reference;
  const PreparedIntegrator p = prepare_integrator(scene, r.integrator, {}, config.file, r.line);
  std::string key = "deltapath-reference-v1\n";
  key += read_bytes(config.scene);
  key += "\nintegrator=" + r.integrator + "\nsettings=" + p.settings_text;
  key += "\nspp=" + std::to_string(r.spp) + "\nmax_depth=" + std::to_string(scene.integrator_defaults().max_depth);
  key += "\nseed=" + std::to_string(kReferenceSeed);
  return r.integrator + "-" + std::to_string(r.spp) + "spp-" + hex64(fnv1a(key)) + ".exr";
}

Reference obtain_reference(const ExperimentConfig& config, const scene::Scene& scene, const RenderContext& ctx,
                           const std::string& cache_dir) {
  Reference ref;
  if (!config.reference.file.empty()) {
    if (!std::filesystem::exists(config.reference.file))
      throw IoError("reference image '" + config.reference.file + "' does not exist", config.file, config.reference.line);
    ref.path = config.reference.file;
    ref.image = core::read_image(ref.path);
    check_size(config, ref.image, scene, "reference " + ref.path);
    return ref;
  }
  ref.path = (std::filesystem::path(cache_dir) / reference_cache_name(config, scene)).string();
  if (std::filesystem::exists(ref.path)) {
    log::info("reference: using cached ", ref.path);
    ref.image = core::read_exr(ref.path);
    check_size(config, ref.image, scene, "cached reference " + ref.path);
    return ref;
  }
  PreparedIntegrator p = prepare_integrator(scene, config.reference.integrator, {}, config.file, config.reference.line);
  integrators::RenderOptions opt;
  opt.spp = int(config.reference.spp);
  opt.seed = kReferenceSeed;
  opt.threads = ctx.threads;
  opt.max_depth = scene.integrator_defaults().max_depth;
  opt.quiet = ctx.quiet;
  opt.stop = ctx.stop;
  log::info("reference: rendering ", config.reference.integrator, " at ", config.reference.spp, " spp -> ", ref.path);
  core::Timer timer;
  integrators::RenderResult result = p.integrator->render(scene, opt);
  if (result.partial) throw Error("reference render interrupted; nothing cached", config.file, config.reference.line);
  ref.image = std::move(result.layers.at(0).image);
  if (const size_t bad = ref.image.count_nonfinite(); bad > 0)
    throw ValueError("reference render has " + std::to_string(bad) + " non-finite pixels", config.file,
                     config.reference.line);
  std::filesystem::create_directories(cache_dir);
  core::write_exr(ref.path, ref.image);  // atomic: a killed run leaves no truncated cache entry
  log::info("reference: rendered in ", timer.seconds(), " s");
  ref.rendered = true;
  return ref;
}

}  // namespace dp::experiments
