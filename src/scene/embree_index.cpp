// The only translation unit that sees Embree.
#include "scene/embree_index.hpp"

#include <embree3/rtcore.h>
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <stdexcept>

namespace j232::scene {

namespace {

// The float ray starts this far behind the double origin (Embree's segments start at or
// after the origin, and the float origin may sit ~1e-7 m off the double one).
constexpr double kBack = 1e-4;

// The float tfar that surely covers a double distance d from the double origin.
float covering_tfar(double d) {
  return std::nextafter(static_cast<float>((d + kBack) * (1 + 1e-5) + 1e-5), std::numeric_limits<float>::infinity());
}

// What a query carries through Embree to the primitive callback: Embree 3 passes the
// intersect context, so the query's own data follow it in one struct.
struct QueryContext {
  RTCIntersectContext embree;  // first: Embree sees only this part
  const RayQuery* query;
  const Skip* skip;
  const std::vector<TriangleEdges>* triangles;
  NearestHit* best;
};

// A float box around a double triangle, widened so that no ray that meets the triangle in
// double precision misses its box in single precision.
void triangle_bounds(const RTCBoundsFunctionArguments* args) {
  const auto& triangles = *static_cast<const std::vector<TriangleEdges>*>(args->geometryUserPtr);
  const TriangleEdges& t = triangles[args->primID];
  const Vec3 a = t[0], b = t[0] + t[1], c = t[0] + t[2];
  const Vec3 lo = a.cwiseMin(b).cwiseMin(c), hi = a.cwiseMax(b).cwiseMax(c);
  const double pad = 1e-6 * (1.0 + std::max(lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()));
  auto down = [&](double v) { return std::nextafter(static_cast<float>(v - pad), -std::numeric_limits<float>::infinity()); };
  auto up = [&](double v) { return std::nextafter(static_cast<float>(v + pad), std::numeric_limits<float>::infinity()); };
  RTCBounds* o = args->bounds_o;
  o->lower_x = down(lo.x()), o->lower_y = down(lo.y()), o->lower_z = down(lo.z());
  o->upper_x = up(hi.x()), o->upper_y = up(hi.y()), o->upper_z = up(hi.z());
}

void triangle_intersect(const RTCIntersectFunctionNArguments* args) {
  if (!args->valid[0]) return;
  auto* ctx = reinterpret_cast<QueryContext*>(args->context);
  const double before = ctx->best->distance;
  ctx->best->offer(*ctx->query, (*ctx->triangles)[args->primID], args->primID, *ctx->skip);
  if (ctx->best->distance < before) {
    // Let Embree prune beyond the new best, a little past it so that faces as near (the
    // tie rule) are still visited.
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCRayN_tfar(ray, args->N, 0) = covering_tfar(ctx->best->distance);
  }
}

}  // namespace

struct EmbreeIndex::Impl {
  const std::vector<TriangleEdges>* triangles;
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
};

EmbreeIndex::EmbreeIndex(const std::vector<TriangleEdges>& triangles) : impl_(std::make_unique<Impl>()) {
  impl_->triangles = &triangles;
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) throw std::runtime_error(fmt::format("Embree: no device (error {})", static_cast<int>(rtcGetDeviceError(nullptr))));
  impl_->scene = rtcNewScene(impl_->device);
  rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_ROBUST);
  rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
  RTCGeometry geometry = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_USER);
  rtcSetGeometryUserPrimitiveCount(geometry, static_cast<unsigned>(triangles.size()));
  rtcSetGeometryUserData(geometry, const_cast<std::vector<TriangleEdges>*>(&triangles));
  rtcSetGeometryBoundsFunction(geometry, triangle_bounds, nullptr);
  rtcSetGeometryIntersectFunction(geometry, triangle_intersect);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(impl_->scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(impl_->scene);
  if (rtcGetDeviceError(impl_->device) != RTC_ERROR_NONE) throw std::runtime_error("Embree: the scene could not be built");
}

EmbreeIndex::~EmbreeIndex() {
  if (impl_->scene) rtcReleaseScene(impl_->scene);
  if (impl_->device) rtcReleaseDevice(impl_->device);
}

void EmbreeIndex::closest(const RayQuery& q, const Skip& skip, NearestHit& best) const {
  QueryContext ctx;
  rtcInitIntersectContext(&ctx.embree);
  ctx.query = &q;
  ctx.skip = &skip;
  ctx.triangles = impl_->triangles;
  ctx.best = &best;
  RTCRayHit rh;
  const Vec3 start = q.origin - kBack * q.dir;
  rh.ray.org_x = static_cast<float>(start.x());
  rh.ray.org_y = static_cast<float>(start.y());
  rh.ray.org_z = static_cast<float>(start.z());
  rh.ray.dir_x = static_cast<float>(q.dir.x());
  rh.ray.dir_y = static_cast<float>(q.dir.y());
  rh.ray.dir_z = static_cast<float>(q.dir.z());
  // A little wider than the search's segment at both ends; the exact test decides.
  rh.ray.tnear = 0.0f;
  rh.ray.tfar = covering_tfar(best.distance);
  rh.ray.time = 0;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.ray.id = 0;
  rh.ray.flags = 0;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene, &ctx.embree, &rh);
}

}  // namespace j232::scene
