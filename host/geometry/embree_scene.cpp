#include "geometry/embree_scene.h"

#include <algorithm>
#include <cmath>

#include "core/error.h"
#include "core/parallel_for.h"
#include "geometry/embree_device.h"

namespace kasha {

// Embree's filter for both queries: a candidate hit failing the alpha test is rejected, and the
// traversal goes on (kernels/shared/alpha_test.h, as bvh_traversal.h's).
static void alpha_filter(const RTCFilterFunctionNArguments* args) {
  const auto* tables = static_cast<const AlphaTables*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const float ray[6] = {
        RTCRayN_org_x(args->ray, args->N, i), RTCRayN_org_y(args->ray, args->N, i),
        RTCRayN_org_z(args->ray, args->N, i), RTCRayN_dir_x(args->ray, args->N, i),
        RTCRayN_dir_y(args->ray, args->N, i), RTCRayN_dir_z(args->ray, args->N, i)};
    const int prim = static_cast<int>(RTCHitN_primID(args->hit, args->N, i));
    if (!alpha_keeps(tables, prim, RTCHitN_u(args->hit, args->N, i),
                     RTCHitN_v(args->hit, args->N, i), ray))
      args->valid[i] = 0;
  }
}

// Triangles [first, first + count) as one Embree geometry, primID counted from `first`.
RTCGeometry EmbreeScene::triangle_geometry(size_t first, size_t count,
                                           const std::vector<KTriangle>& triangles) {
  RTCGeometry geom = rtcNewGeometry(embree_device(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), 3 * count));
  auto* idx = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(unsigned), count));
  if (!v || !idx) throw Error("Embree: cannot allocate geometry buffers");
  for (size_t i = 0; i < count; ++i) {
    const KTriangle& t = triangles[first + i];
    std::copy(t.v0, t.v0 + 3, v + 9 * i);
    std::copy(t.v1, t.v1 + 3, v + 9 * i + 3);
    std::copy(t.v2, t.v2 + 3, v + 9 * i + 6);
    idx[3 * i] = 3 * i, idx[3 * i + 1] = 3 * i + 1, idx[3 * i + 2] = 3 * i + 2;
  }
  if (!alpha_.empty()) {
    // The tables seen from this geometry's primIDs (tables_ was reserved: pointers stay).
    tables_.push_back({triangles_.data() + first, alpha_.texcoords.data() + first,
                       alpha_.textures.data(), alpha_.values.data(), alpha_.ops.data()});
    rtcSetGeometryUserData(geom, &tables_.back());
    rtcSetGeometryIntersectFilterFunction(geom, alpha_filter);
    rtcSetGeometryOccludedFilterFunction(geom, alpha_filter);
  }
  rtcCommitGeometry(geom);
  return geom;
}

EmbreeScene::EmbreeScene(const std::vector<KTriangle>& triangles, const AlphaCutouts& alpha,
                         const SceneInstances& instances) {
  RTCDevice device = embree_device();
  scene_ = rtcNewScene(device);
  rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
  if (!alpha.empty()) {
    triangles_ = triangles;
    alpha_ = alpha;
  }
  tables_.reserve(instances.objects.size() + 1);
  const size_t own = instances.empty() ? triangles.size() : size_t(instances.world_triangles);
  if (own > 0) {
    RTCGeometry geom = triangle_geometry(0, own, triangles);
    rtcAttachGeometryByID(scene_, geom, 0);
    rtcReleaseGeometry(geom);
  }
  if (!instances.empty()) {
    own_instance_ = own > 0 ? 0 : -1;
    instance_first_.assign(own > 0 ? 1 : 0, 0);
    for (const ObjectRange& o : instances.objects) {
      objects_.push_back(rtcNewScene(device));
      rtcSetSceneFlags(objects_.back(), RTC_SCENE_FLAG_ROBUST);
      RTCGeometry geom = triangle_geometry(o.first_triangle, o.triangle_count, triangles);
      rtcAttachGeometry(objects_.back(), geom);
      rtcReleaseGeometry(geom);
      rtcCommitScene(objects_.back());
    }
    for (const Placement& p : instances.placements) {
      RTCGeometry geom = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_INSTANCE);
      rtcSetGeometryInstancedScene(geom, objects_[p.object]);
      float m[12];
      for (int i = 0; i < 12; ++i) m[i] = static_cast<float>(p.world_from_object[i]);
      rtcSetGeometryTransform(geom, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, m);
      rtcCommitGeometry(geom);
      rtcAttachGeometryByID(scene_, geom, static_cast<unsigned>(instance_first_.size()));
      rtcReleaseGeometry(geom);
      instance_first_.push_back(instances.objects[p.object].first_triangle);
    }
  }
  rtcCommitScene(scene_);
}

EmbreeScene::~EmbreeScene() {
  rtcReleaseScene(scene_);
  for (RTCScene s : objects_) rtcReleaseScene(s);
}

KHit EmbreeScene::intersect(const KRay& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = ray.org[0], rh.ray.org_y = ray.org[1], rh.ray.org_z = ray.org[2];
  rh.ray.dir_x = ray.dir[0], rh.ray.dir_y = ray.dir[1], rh.ray.dir_z = ray.dir[2];
  rh.ray.tnear = ray.tmin;
  rh.ray.tfar = ray.tmax;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(scene_, &context, &rh);
  KHit hit{ray.tmax, -1, 0, 0, -1};
  if (rh.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
    hit.t = rh.ray.tfar;
    hit.prim = static_cast<int>(rh.hit.primID);
    hit.u = rh.hit.u;
    hit.v = rh.hit.v;
    hit.instance = own_instance_;
    if (rh.hit.instID[0] != RTC_INVALID_GEOMETRY_ID) {
      hit.instance = static_cast<int>(rh.hit.instID[0]);
      hit.prim += instance_first_[hit.instance];
    }
  }
  return hit;
}

bool EmbreeScene::occluded(const KRay& ray) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRay r{};
  r.org_x = ray.org[0], r.org_y = ray.org[1], r.org_z = ray.org[2];
  r.dir_x = ray.dir[0], r.dir_y = ray.dir[1], r.dir_z = ray.dir[2];
  r.tnear = ray.tmin;
  r.tfar = ray.tmax;
  r.mask = 0xFFFFFFFFu;
  rtcOccluded1(scene_, &context, &r);
  return r.tfar < 0;  // Embree sets tfar = -inf on a hit
}

void EmbreeScene::intersect_all(const std::vector<KRay>& rays, std::vector<KHit>& hits) const {
  hits.resize(rays.size());
  parallel_for(rays.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) hits[i] = intersect(rays[i]);
  });
}

void EmbreeScene::occluded_all(const std::vector<KRay>& rays, std::vector<int>& occluded) const {
  occluded.resize(rays.size());
  parallel_for(rays.size(), [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) occluded[i] = this->occluded(rays[i]) ? 1 : 0;
  });
}

}  // namespace kasha
