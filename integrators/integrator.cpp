#include "integrators/integrator.h"

#include "core/error.h"

namespace dp::integrators {

RenderResult Integrator::finish(const core::RawImage&, const RenderOptions&) const {
  throw ValueError("integrator " + name() + " does not support --partial yet");
}

}  // namespace dp::integrators
