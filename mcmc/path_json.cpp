#include "mcmc/path_json.h"

namespace dp::mcmc {

namespace {
core::Json vec(const Vec3& v) {
  core::Json a = core::Json::array();
  for (int i = 0; i < 3; ++i) a.push_back(double(v[i]));
  return a;
}
const char* kind_name(pathspace::BidirKind k) {
  switch (k) {
    case pathspace::BidirKind::camera: return "camera";
    case pathspace::BidirKind::light: return "light";
    case pathspace::BidirKind::surface: return "surface";
    case pathspace::BidirKind::medium: return "medium";
  }
  return "?";
}
}  // namespace

core::Json path_state_json(const PathState& s) {
  core::Json j = core::Json::object();
  core::Json verts = core::Json::array();
  for (const auto& v : s.v) {
    core::Json o = core::Json::object();
    o["kind"] = kind_name(v.kind);
    o["p"] = vec(v.sp.p);
    o["ng"] = vec(v.sp.ng);
    o["dirac"] = v.delta;
    if (v.delta) o["lobe"] = double(v.lobe);
    o["shape"] = double(v.shape);
    o["prim"] = double(v.prim);
    o["emitter"] = v.emitter != nullptr;
    verts.push_back(o);
  }
  j["depth"] = double(s.depth());
  j["vertices"] = verts;
  core::Json raster = core::Json::array();
  raster.push_back(double(s.raster.x()));
  raster.push_back(double(s.raster.y()));
  j["raster"] = raster;
  core::Json c = core::Json::array();
  for (int i = 0; i < 3; ++i) c.push_back(double(s.c_ref[i]));
  j["c_ref"] = c;
  j["lum_c_ref"] = double(luminance(s.c_ref));
  j["ref_strategy"] = double(s.ref);
  core::Json inv = core::Json::array();
  for (double x : s.inv_c) inv.push_back(x);
  j["inv_c"] = inv;
  return j;
}

}  // namespace dp::mcmc
