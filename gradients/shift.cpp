#include "gradients/shift.h"

namespace dp::gradients {

const char* to_string(ShiftStatus s) {
  switch (s) {
    case ShiftStatus::ok: return "ok";
    case ShiftStatus::not_invertible: return "not_invertible";
    case ShiftStatus::occluded: return "occluded";
    case ShiftStatus::miss: return "miss";
    case ShiftStatus::zero_contribution: return "zero_contribution";
  }
  return "?";
}

const char* to_string(StepKind k) {
  switch (k) {
    case StepKind::none: return "none";
    case StepKind::primary: return "primary";
    case StepKind::reconnect: return "reconnect";
    case StepKind::half_vector: return "half_vector";
    case StepKind::dirac: return "dirac";
    case StepKind::copy: return "copy";
    case StepKind::nee_reconnect: return "nee_reconnect";
    case StepKind::nee_half_vector: return "nee_half_vector";
    case StepKind::nee_copy: return "nee_copy";
    case StepKind::manifold: return "manifold";
  }
  return "?";
}

void ShiftResult::reset(int n) {
  path.clear();
  jacobian.assign(size_t(n), 1.0);
  step.assign(size_t(n), StepKind::none);
  nee_status.assign(size_t(n), ShiftStatus::ok);
  nee_jacobian.assign(size_t(n), 1.0);
  nee_step.assign(size_t(n), StepKind::none);
  status = ShiftStatus::ok;
  alive = 0;
  reconnected = -1;
  walk_status = -1;
  walk_refused = false;
  walk_iterations = 0;
  walk_traces = 0;
  declared = 0;
  class_mismatch = false;
}

double ShiftResult::prefix_jacobian(int k) const {
  double j = 1.0;
  for (int m = 0; m < k; ++m) j *= jacobian[size_t(m)];
  return j;
}

void IdentityShift::shift(const pathspace::Path& base, const Vec2& raster_offset, ShiftResult& out) const {
  (void)raster_offset;
  out.reset(base.size());
  out.path = base;
  for (int k = 0; k < base.size(); ++k) {
    out.step[size_t(k)] = StepKind::copy;
    if (base.nee[size_t(k)].valid) out.nee_step[size_t(k)] = StepKind::nee_copy;
  }
  out.alive = base.size();
}

}  // namespace dp::gradients
