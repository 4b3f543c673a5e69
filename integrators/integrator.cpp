#include "integrators/integrator.h"

#include "core/error.h"

namespace dp::integrators {

RenderResult Integrator::finish(const core::RawImage&, const RenderOptions&) const {
  throw ValueError("integrator " + name() + " does not support --partial yet");
}

void check_scene_support(const Integrator& integrator, const scene::Scene& scene) {
  if (!scene.caps().has_media) return;
  size_t grids = 0;
  for (const auto& m : scene.media()) grids += m.heterogeneous() ? 1 : 0;
  const bool ok = grids > 0 ? integrator.renders_grid_media() : integrator.renders_media();
  if (ok) return;
  std::string able;  // only on the error path: every registered integrator at its defaults
  for (const auto& name : integrator_names()) {
    Settings s;
    const auto in = make_integrator(name, s);
    if (grids > 0 ? in->renders_grid_media() : in->renders_media()) able += (able.empty() ? "" : ", ") + name;
  }
  if (grids > 0 && integrator.renders_media())
    throw ValueError("integrator " + integrator.name() + " renders homogeneous media only, and the scene has " +
                     std::to_string(grids) + " grid medium/media; use " + able);
  throw ValueError("integrator " + integrator.name() + " does not render participating media, and the scene has " +
                   std::to_string(scene.media().size()) + " medium/media (it would render them as vacuum); use " +
                   able);
}

}  // namespace dp::integrators
