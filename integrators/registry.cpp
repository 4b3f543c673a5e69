// The integrator registry: adding an integrator is one line in kRegistry.
#include <algorithm>

#include "core/error.h"
#include "integrators/integrator.h"
#include "integrators/bdpt/bdpt_integrator.h"
#include "integrators/beam/beam_integrator.h"
#include "integrators/plane/plane_integrator.h"
#include "integrators/bre/bre_integrator.h"
#include "integrators/gdmlt/gdmlt_integrator.h"
#include "integrators/gbdpt/gbdpt_integrator.h"
#include "integrators/gpm/gpm_integrator.h"
#include "integrators/gvcm/gvcm_integrator.h"
#include "integrators/gvpm/gvpm_integrator.h"
#include "integrators/gpr/gpr_integrator.h"
#include "integrators/gpt/gpt_integrator.h"
#include "integrators/mlt/mlt_integrator.h"
#include "integrators/path/path_integrator.h"
#include "integrators/pr/pr_integrator.h"
#include "integrators/vcm/vcm_integrator.h"
#include "integrators/volpath/volpath_integrator.h"
#include "integrators/vpm/vpm_integrator.h"

namespace dp::integrators {

namespace {
template <typename T>
std::unique_ptr<Integrator> make(Settings& s) {
  return std::make_unique<T>(s);
}

struct Entry {
  const char* name;
  IntegratorFactory factory;
  const char* description;
};

const std::vector<Entry>& registry() {
  static const std::vector<Entry> kRegistry = {
      {"path", make<PathIntegrator>, "unidirectional path tracer, NEE + MIS (reference); delegates to volpath on a scene with media"},
      {"volpath", make<VolpathIntegrator>, "volumetric path tracer: homogeneous media, free-flight sampling, NEE through index-matched boundaries, MIS with the phase function"},
      {"vpm", make<VpmIntegrator>, "progressive volumetric photon mapping: photons at medium scattering events, point queries along camera segments in media, 3D kernel (Jensen & Christensen 1998; Gruson et al. 2018, Sec. 4)"},
      {"bre", make<BreIntegrator>, "progressive beam radiance estimate: camera segments in media as beam queries against medium photons, 2D kernel (Jarosz et al. 2008; Gruson et al. 2018, Sec. 5.1)"},
      {"beam", make<BeamIntegrator>, "progressive photon beams: light paths' medium segments as short beams in a BVH, camera segments in media gather them with the Beam-Beam 3D estimate (kernel: 1d for Beam x Beam 1D) (Jarosz et al. 2011; Gruson et al. 2018, Sec. 5.2, 6.1)"},
      {"plane", make<PlaneIntegrator>, "progressive photon planes: each medium scattering event of a light path keeps its segment x sampled direction as a plane, camera segments in media take the 0D plane estimate (1/|det|, a shadow ray per hit), light from light/surface vertices by Beam-Beam 3D (Bitterli & Jarosz 2017; Gruson et al. 2018, Sec. 5.3)"},
      {"gvpm", make<GvpmIntegrator>, "gradient-domain volumetric photon mapping: vpm's primary-ray gathers shifted (distance copy, mixed photon shift, reconnection to the photon's parent, Eq. 19 MIS), L1/L2 reconstruction (Gruson et al. 2018, Sec. 4)"},
      {"gbre", GvpmIntegrator::make_gbre, "gradient-domain beam radiance estimate: each primary-ray segment in a medium a Point-Beam 3D query (a gather point per photon, uniform on its chord), shifted as gvpm's, L1/L2 reconstruction (Gruson et al. 2018, Sec. 5.1)"},
      {"gbeam", GvpmIntegrator::make_gbeam, "gradient-domain photon beams: each primary-ray segment in a medium gathers the light paths' short beams with Beam-Beam 3D (a photon uniform on each beam's chord, a gather point uniform on the camera chord around it), shifted as gbre's with the photon reconnected to its beam's start, L1/L2 reconstruction (Gruson et al. 2018, Sec. 5.2)"},
      {"gplane", GvpmIntegrator::make_gplane, "gradient-domain photon planes: each primary-ray segment in a medium meets the photon planes (0D), every hit shifted by rotating its plane about the light segment to hold the offset gather point (distance copied; Jacobian |det'|/|det| t1/t1', Eq. 19 MIS), beams from light/surface vertices unshifted; L1/L2 reconstruction (Gruson et al. 2018, Sec. 5.3)"},
      {"bdpt", make<BdptIntegrator>, "bidirectional path tracing, all s/t strategies, power/balance MIS (Veach 1997)"},
      {"vcm", make<VcmIntegrator>, "vertex connection and merging (Georgiev et al. 2012); modes vcm, bpt, vm, ppm, lt"},
      {"gpt", make<GptIntegrator>, "gradient-domain path tracing (Kettunen et al. 2015), L1/L2 reconstruction"},
      {"pr", make<PrIntegrator>, "generalized path reusing over jittered tiles (Bauszat et al. 2017, Sec. 3.1, Eq. 7)"},
      {"gpr", make<GprIntegrator>, "gradient-domain path reusing over jittered tiles with a one-pixel border (Bauszat et al. 2017, Sec. 3.2, Eq. 8), L1/L2 reconstruction"},
      {"gbdpt", make<GbdptIntegrator>, "gradient-domain bidirectional path tracing (Manzi et al. 2015), L1/L2 reconstruction"},
      {"gpm", make<GpmIntegrator>, "gradient-domain photon mapping (G-PM as Sun et al. 2017 implement it), L1/L2 reconstruction"},
      {"gvcm", make<GvcmIntegrator>, "gradient-domain vertex connection and merging (Sun et al. 2017), L1/L2 reconstruction"},
      {"mlt", make<MltIntegrator>, "primary-sample-space Metropolis light transport (Kelemen et al. 2002)"},
      {"memlt", make_memlt, "manifold exploration MLT (Jakob & Marschner 2012): path-space MLT with bidirectional, lens, caustic, multi-chain and manifold mutations"},
      {"gdmlt", make<GdmltIntegrator>, "gradient-domain MLT on the extended path space (Manzi et al. 2014)"},
  };
  return kRegistry;
}
}  // namespace

std::unique_ptr<Integrator> make_integrator(const std::string& name, Settings& settings) {
  for (const auto& e : registry()) {
    if (name != e.name) continue;
    auto integrator = e.factory(settings);
    settings.check_all_used(name);
    return integrator;
  }
  std::string known;
  for (const auto& e : registry()) known += (known.empty() ? "" : ", ") + std::string(e.name);
  throw ValueError("unknown integrator '" + name + "' (available: " + known + ")");
}

std::vector<std::string> integrator_names() {
  std::vector<std::string> names;
  for (const auto& e : registry()) names.emplace_back(e.name);
  return names;
}

}  // namespace dp::integrators
