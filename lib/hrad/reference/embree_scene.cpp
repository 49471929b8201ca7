#include "hrad/reference/embree_scene.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include "hrad/core/error.h"
#include "hrad/geometry/patch_plane.h"

namespace hrad {

struct EmbreeScene::Impl {
  const Scene* scene = nullptr;
  RTCDevice device = nullptr;
  RTCScene bvh = nullptr;
  Vec3 centre = Vec3::Zero();        ///< subtracted before rounding to float (precision where the scene is)
  std::vector<int> triangle_patch;   ///< Embree primitive id -> patch
  std::vector<Vec3> plane_normal;    ///< per patch: unit front normal
  std::vector<double> plane_offset;  ///< per patch: normal . (a point of the plane)
  double tolerance = 0.0;

  bool on_plane(int patch, const Vec3& x) const {
    const auto p = static_cast<std::size_t>(patch);
    return std::abs(plane_normal[p].dot(x) - plane_offset[p]) <= tolerance;
  }
  /// Patches a and b lie in one plane and face the same way.
  bool same_plane_same_side(int a, int b) const {
    const auto i = static_cast<std::size_t>(a), j = static_cast<std::size_t>(b);
    return plane_normal[i].dot(plane_normal[j]) >= 1.0 - 1e-12 &&
           std::abs(plane_offset[i] - plane_offset[j]) <= tolerance;
  }

  ~Impl() {
    if (bvh) rtcReleaseScene(bvh);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

// What the filter needs to know about one query: the ray's ends in double precision.
struct FilterContext {
  RTCIntersectContext embree;  // first member: Embree hands the filter a pointer to it
  const EmbreeScene::Impl* impl;
  Vec3 origin;
  Vec3 end;
  bool has_end;
  int skip_backs_like = -1;  ///< also ignore patches in this patch's plane facing its way (-1: none)

  FilterContext(const EmbreeScene::Impl& scene, const Vec3& from, const Vec3* to)
      : impl(&scene), origin(from), end(to ? *to : from), has_end(to != nullptr) {
    rtcInitIntersectContext(&embree);
  }
};

// Rejects candidate hits on patches whose plane passes through the ray's origin or end (see the header).
void ignore_planes_through_ends(const RTCFilterFunctionNArguments* args) {
  const auto* ctx = reinterpret_cast<const FilterContext*>(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    const unsigned triangle = RTCHitN_primID(args->hit, args->N, i);
    const int patch = ctx->impl->triangle_patch[triangle];
    if (ctx->impl->on_plane(patch, ctx->origin) || (ctx->has_end && ctx->impl->on_plane(patch, ctx->end)) ||
        (ctx->skip_backs_like >= 0 && ctx->impl->same_plane_same_side(patch, ctx->skip_backs_like)))
      args->valid[i] = 0;
  }
}

void check(RTCDevice device, const char* what) {
  const RTCError e = rtcGetDeviceError(device);
  if (e != RTC_ERROR_NONE) throw Error(fmt::format("embree: {} failed (error {})", what, static_cast<int>(e)));
}

void set_ray(RTCRay& ray, const Vec3& origin, const Vec3& direction, float tfar) {
  ray.org_x = static_cast<float>(origin.x());
  ray.org_y = static_cast<float>(origin.y());
  ray.org_z = static_cast<float>(origin.z());
  ray.dir_x = static_cast<float>(direction.x());
  ray.dir_y = static_cast<float>(direction.y());
  ray.dir_z = static_cast<float>(direction.z());
  ray.tnear = 0.0f;
  ray.tfar = tfar;
  ray.time = 0.0f;
  ray.mask = 0xffffffffu;
  ray.id = 0;
  ray.flags = 0;
}

}  // namespace

EmbreeScene::EmbreeScene(const Scene& scene) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  m.scene = &scene;
  m.device = rtcNewDevice(nullptr);
  if (m.device == nullptr) throw Error("embree: cannot create a device");

  const auto [lo, hi] = scene.bounds();
  double size = 0.0;
  if (!scene.patches.empty()) {
    m.centre = (lo + hi) / 2;
    size = std::max({(hi - lo).norm(), lo.cwiseAbs().maxCoeff(), hi.cwiseAbs().maxCoeff()});
  }
  m.tolerance = 1e-9 * size;

  std::size_t vertex_count = 0, triangle_count = 0;
  for (const Patch& p : scene.patches) {
    vertex_count += p.vertices.size();
    triangle_count += p.vertices.size() - 2;
  }
  m.plane_normal.reserve(scene.patches.size());
  m.plane_offset.reserve(scene.patches.size());
  for (const Patch& p : scene.patches) {
    m.plane_normal.push_back(p.normal);
    m.plane_offset.push_back(detail::plane_offset(p));
  }

  m.bvh = rtcNewScene(m.device);
  rtcSetSceneFlags(m.bvh, RTC_SCENE_FLAG_ROBUST);  // watertight along shared edges
  rtcSetSceneBuildQuality(m.bvh, RTC_BUILD_QUALITY_HIGH);
  if (triangle_count > 0) {
    RTCGeometry geometry = rtcNewGeometry(m.device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                                                 3 * sizeof(float), vertex_count));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                                                   3 * sizeof(unsigned), triangle_count));
    check(m.device, "allocating the triangle buffers");
    m.triangle_patch.reserve(triangle_count);
    unsigned next_vertex = 0;
    for (std::size_t pi = 0; pi < scene.patches.size(); ++pi) {
      const Patch& p = scene.patches[pi];
      const unsigned first = next_vertex;
      for (const Vec3& v : p.vertices) {
        const Vec3 local = v - m.centre;
        for (int c = 0; c < 3; ++c) *vertices++ = static_cast<float>(local[c]);
        ++next_vertex;
      }
      // A fan from vertex 0: patches are convex.
      for (unsigned k = 1; k + 1 < p.vertices.size(); ++k) {
        *indices++ = first;
        *indices++ = first + k;
        *indices++ = first + k + 1;
        m.triangle_patch.push_back(static_cast<int>(pi));
      }
    }
    rtcSetGeometryIntersectFilterFunction(geometry, ignore_planes_through_ends);
    rtcSetGeometryOccludedFilterFunction(geometry, ignore_planes_through_ends);
    rtcCommitGeometry(geometry);
    rtcAttachGeometry(m.bvh, geometry);
    rtcReleaseGeometry(geometry);
  }
  rtcCommitScene(m.bvh);
  check(m.device, "building the BVH");
}

EmbreeScene::~EmbreeScene() = default;

const Scene& EmbreeScene::scene() const { return *impl_->scene; }

double EmbreeScene::plane_tolerance() const { return impl_->tolerance; }

RayHit EmbreeScene::closest_hit(const Vec3& origin, const Vec3& direction, RayCounts& counts) const {
  const Impl& m = *impl_;
  FilterContext ctx(m, origin, nullptr);
  const auto cast = [&] {
    RTCRayHit rh;
    set_ray(rh.ray, origin - m.centre, direction, std::numeric_limits<float>::infinity());
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m.bvh, &ctx.embree, &rh);
    ++counts.closest_hit;
    return rh;
  };
  RTCRayHit rh = cast();
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return {};
  int patch = m.triangle_patch[rh.hit.primID];
  if (m.plane_normal[static_cast<std::size_t>(patch)].dot(direction) >= 0.0) {
    // A back. Where two patches lie back to back (a wall of zero thickness), both are hit at the
    // same distance and Embree may report either; the ray meets the front that faces it, so look
    // again past the backs of this plane and take a patch of the same plane if there is one.
    ctx.skip_backs_like = patch;
    const RTCRayHit again = cast();
    if (again.hit.geomID != RTC_INVALID_GEOMETRY_ID) {
      const int twin = m.triangle_patch[again.hit.primID];
      const auto t = static_cast<std::size_t>(twin);
      if (m.plane_normal[t].dot(direction) < 0.0 &&
          std::abs(m.plane_normal[t].dot(m.plane_normal[static_cast<std::size_t>(patch)]) + 1.0) <= 1e-12 &&
          std::abs(m.plane_offset[t] + m.plane_offset[static_cast<std::size_t>(patch)]) <= m.tolerance) {
        rh = again;
        patch = twin;
      }
    }
  }

  RayHit hit;
  hit.patch = patch;
  const auto p = static_cast<std::size_t>(patch);
  const Vec3& n = m.plane_normal[p];
  hit.front = n.dot(direction) < 0.0;
  // Embree's distance is single precision; put the point back on the patch's plane.
  const Vec3 approximate = origin + static_cast<double>(rh.ray.tfar) * direction;
  hit.point = approximate - n * (n.dot(approximate) - m.plane_offset[p]);
  return hit;
}

bool EmbreeScene::blocked(const Vec3& a, const Vec3& b, RayCounts& counts) const {
  const Impl& m = *impl_;
  FilterContext ctx(m, a, &b);
  RTCRay ray;
  set_ray(ray, a - m.centre, b - a, 1.0f);
  rtcOccluded1(m.bvh, &ctx.embree, &ray);
  ++counts.shadow;
  return ray.tfar < 0.0f;  // Embree marks an occluded ray with tfar = -inf
}

}  // namespace hrad
