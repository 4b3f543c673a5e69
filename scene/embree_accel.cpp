// The only translation unit of the scene layer that includes Embree.
#include "scene/embree_accel.h"

#include <embree3/rtcore.h>

#include "core/error.h"

namespace dp::scene {

namespace {

void sphere_bounds(const RTCBoundsFunctionArguments* args) {
  const auto* sphere = static_cast<const Sphere*>(args->geometryUserPtr);
  const Bounds3 b = sphere->bounds();
  RTCBounds* out = args->bounds_o;
  out->lower_x = b.lo.x(); out->lower_y = b.lo.y(); out->lower_z = b.lo.z();
  out->upper_x = b.hi.x(); out->upper_y = b.hi.y(); out->upper_z = b.hi.z();
}

Ray to_ray(float ox, float oy, float oz, float dx, float dy, float dz, float tnear, float tfar) {
  Ray r;
  r.o = Vec3(ox, oy, oz);
  r.d = Vec3(dx, dy, dz);
  r.tmin = tnear;
  r.tmax = tfar;
  return r;
}

void sphere_intersect(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  DP_CHECK(args->N == 1, "sphere user geometry expects single rays");
  const auto* sphere = static_cast<const Sphere*>(args->geometryUserPtr);
  auto* rh = reinterpret_cast<RTCRayHit*>(args->rayhit);
  const Ray ray = to_ray(rh->ray.org_x, rh->ray.org_y, rh->ray.org_z, rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z,
                         rh->ray.tnear, rh->ray.tfar);
  float t;
  if (!sphere->intersect(ray, t)) return;
  rh->ray.tfar = t;
  const Vec3 n = (ray.at(t) - sphere->center()).normalized();
  rh->hit.Ng_x = n.x(); rh->hit.Ng_y = n.y(); rh->hit.Ng_z = n.z();
  rh->hit.u = 0; rh->hit.v = 0;
  rh->hit.primID = args->primID;
  rh->hit.geomID = args->geomID;
  rh->hit.instID[0] = args->context->instID[0];
}

void sphere_occluded(const RTCOccludedFunctionNArguments* args) {
  if (!args->valid[0]) return;
  DP_CHECK(args->N == 1, "sphere user geometry expects single rays");
  const auto* sphere = static_cast<const Sphere*>(args->geometryUserPtr);
  auto* r = reinterpret_cast<RTCRay*>(args->ray);
  const Ray ray = to_ray(r->org_x, r->org_y, r->org_z, r->dir_x, r->dir_y, r->dir_z, r->tnear, r->tfar);
  float t;
  if (sphere->intersect(ray, t)) r->tfar = -kInfinity;
}

void fill_ray(const Ray& ray, RTCRay& r) {
  r.org_x = ray.o.x(); r.org_y = ray.o.y(); r.org_z = ray.o.z();
  r.dir_x = ray.d.x(); r.dir_y = ray.d.y(); r.dir_z = ray.d.z();
  r.tnear = ray.tmin;
  r.tfar = ray.tmax;
  r.time = 0;
  r.mask = 0xFFFFFFFFu;
  r.id = 0;
  r.flags = 0;
}

// One Embree device per process, shared by every scene (creating a device costs ~10 ms,
// ~100 ms under AddressSanitizer: the loader fuzzer spent most of its time there). Each
// accelerator holds a reference; this function's static holds one more for the process.
RTCDevice shared_device() {
  static const RTCDevice device = rtcNewDevice(nullptr);
  if (!device) throw Error("cannot create the Embree device (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
  rtcRetainDevice(device);
  return device;
}

}  // namespace

struct EmbreeAccel::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

EmbreeAccel::EmbreeAccel(const std::vector<ShapePtr>& shapes) : m_impl(std::make_unique<Impl>()) {
  m_impl->device = shared_device();
  m_impl->scene = rtcNewScene(m_impl->device);
  rtcSetSceneBuildQuality(m_impl->scene, RTC_BUILD_QUALITY_HIGH);
  for (size_t i = 0; i < shapes.size(); ++i) {
    RTCGeometry geom = nullptr;
    if (const auto* mesh = dynamic_cast<const TriangleMesh*>(shapes[i].get())) {
      if (mesh->triangles.empty()) continue;
      geom = rtcNewGeometry(m_impl->device, RTC_GEOMETRY_TYPE_TRIANGLE);
      // Embree-owned buffers are padded as Embree requires (shared buffers would need
      // 16 bytes of readable slack after the last vertex).
      auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                             3 * sizeof(float), mesh->positions.size()));
      for (size_t k = 0; k < mesh->positions.size(); ++k)
        for (int c = 0; c < 3; ++c) v[3 * k + size_t(c)] = mesh->positions[k][c];
      auto* idx = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                  3 * sizeof(uint32_t), mesh->triangles.size()));
      for (size_t k = 0; k < mesh->triangles.size(); ++k)
        for (int c = 0; c < 3; ++c) idx[3 * k + size_t(c)] = mesh->triangles[k][size_t(c)];
    } else if (const auto* sphere = dynamic_cast<const Sphere*>(shapes[i].get())) {
      geom = rtcNewGeometry(m_impl->device, RTC_GEOMETRY_TYPE_USER);
      rtcSetGeometryUserPrimitiveCount(geom, 1);
      rtcSetGeometryUserData(geom, const_cast<Sphere*>(sphere));
      rtcSetGeometryBoundsFunction(geom, sphere_bounds, nullptr);
      rtcSetGeometryIntersectFunction(geom, sphere_intersect);
      rtcSetGeometryOccludedFunction(geom, sphere_occluded);
    } else {
      throw Error("unsupported shape kind for Embree");
    }
    rtcCommitGeometry(geom);
    rtcAttachGeometryByID(m_impl->scene, geom, unsigned(i));
    rtcReleaseGeometry(geom);
  }
  rtcCommitScene(m_impl->scene);
  const RTCError err = rtcGetDeviceError(m_impl->device);
  if (err != RTC_ERROR_NONE) throw Error("Embree scene build failed (error " + std::to_string(int(err)) + ")");
}

EmbreeAccel::~EmbreeAccel() {
  if (m_impl->scene) rtcReleaseScene(m_impl->scene);
  if (m_impl->device) rtcReleaseDevice(m_impl->device);
}

bool EmbreeAccel::intersect(const Ray& ray, RawHit& hit) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRayHit rh;
  fill_ray(ray, rh.ray);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(m_impl->scene, &ctx, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return false;
  hit.t = rh.ray.tfar;
  hit.shape = int(rh.hit.geomID);
  hit.prim = int(rh.hit.primID);
  hit.b = Vec2(rh.hit.u, rh.hit.v);
  hit.ng = Vec3(rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z);
  return true;
}

bool EmbreeAccel::occluded(const Ray& ray) const {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r;
  fill_ray(ray, r);
  rtcOccluded1(m_impl->scene, &ctx, &r);
  return r.tfar < 0.0f;
}

}  // namespace dp::scene
