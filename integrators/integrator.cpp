#include "integrators/integrator.h"

#include "core/error.h"

namespace dp::integrators {

RenderResult Integrator::finish(const core::RawImage&, const RenderOptions&) const {
  throw ValueError("integrator " + name() + " does not support --partial yet");
}

void check_scene_support(const Integrator& integrator, const scene::Scene& scene) {
  if (!scene.caps().has_media || integrator.renders_media()) return;
  std::string able;  // only on the error path: every registered integrator at its defaults
  for (const auto& name : integrator_names()) {
    Settings s;
    if (make_integrator(name, s)->renders_media()) able += (able.empty() ? "" : ", ") + name;
  }
  throw ValueError("integrator " + integrator.name() + " does not render participating media, and the scene has " +
                   std::to_string(scene.media().size()) + " medium/media (it would render them as vacuum); use " +
                   able);
}

}  // namespace dp::integrators
