// Target of a Metropolis chain over primary sample space. A Target reads the state's
// coordinates in order from a SampleStream (as many as it needs; the chain creates
// missing ones on demand) and returns the scalar f >= 0 the chain samples
// proportionally to, plus what is splatted: an RGB value at an image position.
// A Target may keep scratch memory (it is not shared between chains).
#pragma once

#include <functional>
#include <memory>

#include "core/math.h"
#include "pathspace/sample_stream.h"

namespace dp::mcmc {

struct TargetValue {
  double f = 0;              // scalar target; NaN/Inf marks an invalid (non-finite) sample
  Rgb value = Rgb::Zero();   // splatted quantity (a path's contribution)
  Vec2 raster{0, 0};         // continuous image position of the splat (pixel = floor)
  // Gradient-domain targets only: a second splat into row `gradient_row` of a gradient
  // buffer (-1: none).
  Rgb gradient = Rgb::Zero();
  int64_t gradient_row = -1;

  bool valid() const { return std::isfinite(f); }
};

class Target {
 public:
  virtual ~Target() = default;
  virtual TargetValue evaluate(pathspace::SampleStream& stream) = 0;
};

using TargetFactory = std::function<std::unique_ptr<Target>()>;

}  // namespace dp::mcmc
