#include "sim/render/embree_scene.h"

#include <stdexcept>

#if APERTURE_HAVE_EMBREE
#include <embree3/rtcore.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "control/constants.h"
#endif

namespace aperture::sim {

#if APERTURE_HAVE_EMBREE

namespace {

// Relative and absolute padding of the user geometry's float bounds: covers the rounding of the
// bounds computed in double and stored as float.
constexpr double kEmbreeBoundsPadRelative = 1e-6;
constexpr double kEmbreeBoundsPad_m = 1e-6;
// Rays per Embree packet of NearestN (rtcIntersect16; Embree picks its SIMD width at run time:
// on this AVX-512 machine 16 was a little faster than 8, docs/results/speed.md).
constexpr int kEmbreePacket = 16;

Eigen::Vector3d ToCamera(const FrameObject& f, const Eigen::Vector3d& p_O) {
  return f.R_OC.transpose() * (p_O - f.p_OC);  // p_C = R_CO (p_O - p_OC)
}

// The context of one rtcIntersect call: Embree's own first (the callbacks get a pointer to it and
// cast it back), then, per ray (RTCRay::id = lane), the exact hit our callbacks last accepted, so
// the nearest object's hit record is not computed twice when Embree reached it through one.
struct ExactHitContext {
  RTCIntersectContext embree;
  std::array<unsigned, kEmbreePacket> geometry;  // RTC_INVALID_GEOMETRY_ID: no hit stored
  std::array<LocalHit, kEmbreePacket> hits;

  explicit ExactHitContext(RTCIntersectContextFlags flags) {
    rtcInitIntersectContext(&embree);
    embree.flags = flags;
    geometry.fill(RTC_INVALID_GEOMETRY_ID);
  }
  static ExactHitContext* Of(const RTCIntersectContext* context) {
    return reinterpret_cast<ExactHitContext*>(const_cast<RTCIntersectContext*>(context));
  }
  void Store(unsigned lane, unsigned geometry_id, const LocalHit& hit) {
    geometry[lane] = geometry_id;
    hits[lane] = hit;
  }
};

// Ray i of an Embree ray packet as (origin, direction) in O of the object f.
void RayInObject(const FrameObject& f, RTCRayN* ray, unsigned n, unsigned i, Eigen::Vector3d* o_O,
                 Eigen::Vector3d* d_O) {
  const Eigen::Vector3d o_C(RTCRayN_org_x(ray, n, i), RTCRayN_org_y(ray, n, i),
                            RTCRayN_org_z(ray, n, i));
  const Eigen::Vector3d d_C(RTCRayN_dir_x(ray, n, i), RTCRayN_dir_y(ray, n, i),
                            RTCRayN_dir_z(ray, n, i));
  *o_O = f.R_OC * o_C + f.p_OC;
  *d_O = f.R_OC * d_C;
}

// Holed rectangles: a triangle hit counts only where the exact test hits (outside the holes).
void HoleFilter(const RTCFilterFunctionNArguments* args) {
  const FrameObject& f = *static_cast<const FrameObject*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    Eigen::Vector3d o_O, d_O;
    RayInObject(f, args->ray, args->N, i, &o_O, &d_O);
    LocalHit hit;
    if (IntersectPrimitive(*f.primitive, o_O, d_O, RTCRayN_tnear(args->ray, args->N, i),
                           std::numeric_limits<double>::infinity(), &hit)) {
      ExactHitContext::Of(args->context)
          ->Store(RTCRayN_id(args->ray, args->N, i), RTCHitN_geomID(args->hit, args->N, i), hit);
    } else {
      args->valid[i] = 0;
    }
  }
}

// Curved primitives: the exact test is the intersect callback.
void ExactIntersect(const RTCIntersectFunctionNArguments* args) {
  const FrameObject& f = *static_cast<const FrameObject*>(args->geometryUserPtr);
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] == 0) continue;
    Eigen::Vector3d o_O, d_O;
    RayInObject(f, ray, args->N, i, &o_O, &d_O);
    LocalHit local;
    if (!IntersectPrimitive(*f.primitive, o_O, d_O, RTCRayN_tnear(ray, args->N, i),
                            RTCRayN_tfar(ray, args->N, i), &local)) {
      continue;
    }
    const Eigen::Vector3d n_C = f.R_OC.transpose() * local.n_O;
    RTCRayN_tfar(ray, args->N, i) = static_cast<float>(local.t_m);
    RTCHitN_Ng_x(hit, args->N, i) = static_cast<float>(n_C.x());
    RTCHitN_Ng_y(hit, args->N, i) = static_cast<float>(n_C.y());
    RTCHitN_Ng_z(hit, args->N, i) = static_cast<float>(n_C.z());
    RTCHitN_u(hit, args->N, i) = 0.0f;
    RTCHitN_v(hit, args->N, i) = 0.0f;
    RTCHitN_primID(hit, args->N, i) = args->primID;
    RTCHitN_geomID(hit, args->N, i) = args->geomID;
    RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
    ExactHitContext::Of(args->context)->Store(RTCRayN_id(ray, args->N, i), args->geomID, local);
  }
}

// Axis-aligned box in C around the curved primitive (its box in O, transformed), padded.
void CurvedBounds(const RTCBoundsFunctionArguments* args) {
  const FrameObject& f = *static_cast<const FrameObject*>(args->geometryUserPtr);
  Eigen::Vector3d lower_O, upper_O;
  if (const auto* c = std::get_if<Cylinder>(f.primitive)) {
    lower_O = Eigen::Vector3d(-c->radius_m, -c->radius_m, 0.0);
    upper_O = Eigen::Vector3d(c->radius_m, c->radius_m, c->height_m);
  } else {
    const double r = std::get<Sphere>(*f.primitive).radius_m;
    lower_O = Eigen::Vector3d::Constant(-r);
    upper_O = Eigen::Vector3d::Constant(r);
  }
  Eigen::Vector3d lower_C = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d upper_C = -lower_C;
  for (int corner = 0; corner < 8; ++corner) {
    const Eigen::Vector3d p_O((corner & 1) ? upper_O.x() : lower_O.x(),
                              (corner & 2) ? upper_O.y() : lower_O.y(),
                              (corner & 4) ? upper_O.z() : lower_O.z());
    const Eigen::Vector3d p_C = ToCamera(f, p_O);
    lower_C = lower_C.cwiseMin(p_C);
    upper_C = upper_C.cwiseMax(p_C);
  }
  const Eigen::Vector3d pad =
      Eigen::Vector3d::Constant(kEmbreeBoundsPad_m) +
      kEmbreeBoundsPadRelative * lower_C.cwiseAbs().cwiseMax(upper_C.cwiseAbs());
  lower_C -= pad;
  upper_C += pad;
  RTCBounds* b = args->bounds_o;
  b->lower_x = static_cast<float>(lower_C.x());
  b->lower_y = static_cast<float>(lower_C.y());
  b->lower_z = static_cast<float>(lower_C.z());
  b->upper_x = static_cast<float>(upper_C.x());
  b->upper_y = static_cast<float>(upper_C.y());
  b->upper_z = static_cast<float>(upper_C.z());
}

// Triangles of a Rectangle (corners in O, z_O = 0) or a Box (8 corners, 12 triangles).
struct Mesh {
  std::vector<Eigen::Vector3d> vertices_O;
  std::vector<std::array<unsigned, 3>> triangles;
};

Mesh RectangleMesh(const Rectangle& r) {
  const double hx = 0.5 * r.size_m.x();
  const double hy = 0.5 * r.size_m.y();
  return {{{-hx, -hy, 0.0}, {hx, -hy, 0.0}, {hx, hy, 0.0}, {-hx, hy, 0.0}}, {{0, 1, 2}, {0, 2, 3}}};
}

Mesh BoxMesh(const Box& box) {
  Mesh mesh;
  const Eigen::Vector3d half = 0.5 * box.size_m;
  for (int corner = 0; corner < 8; ++corner) {  // bit a set: +half along axis a
    mesh.vertices_O.emplace_back((corner & 1) ? half.x() : -half.x(),
                                 (corner & 2) ? half.y() : -half.y(),
                                 (corner & 4) ? half.z() : -half.z());
  }
  // Each face: the 4 corners with bit a fixed, as two triangles (winding is irrelevant: both
  // sides are hit).
  for (unsigned axis = 0; axis < 3; ++axis) {
    const unsigned bit = 1u << axis;
    const unsigned u = 1u << ((axis + 1) % 3);
    const unsigned v = 1u << ((axis + 2) % 3);
    for (const unsigned side : {0u, bit}) {
      mesh.triangles.push_back({side, side | u, side | u | v});
      mesh.triangles.push_back({side, side | u | v, side | v});
    }
  }
  return mesh;
}

}  // namespace

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  const FrameContext* frame = nullptr;
  std::vector<int> object_of_geometry;           // Embree geometry id -> frame object index
  std::vector<TileCandidate> unbounded_objects;  // tested per ray, t_lower_m = 0

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void AttachMesh(const FrameObject& f, const Mesh& mesh, bool filtered) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                3 * sizeof(float), mesh.vertices_O.size()));
    for (size_t v = 0; v < mesh.vertices_O.size(); ++v) {
      const Eigen::Vector3f p_C = ToCamera(f, mesh.vertices_O[v]).cast<float>();
      vertices[3 * v] = p_C.x();
      vertices[3 * v + 1] = p_C.y();
      vertices[3 * v + 2] = p_C.z();
    }
    auto* indices = static_cast<unsigned*>(
        rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                3 * sizeof(unsigned), mesh.triangles.size()));
    for (size_t t = 0; t < mesh.triangles.size(); ++t) {
      for (int k = 0; k < 3; ++k) indices[3 * t + k] = mesh.triangles[t][k];
    }
    if (filtered) {
      rtcSetGeometryUserData(geometry, const_cast<FrameObject*>(&f));
      rtcSetGeometryIntersectFilterFunction(geometry, HoleFilter);
    }
    Attach(geometry);
  }

  void AttachCurved(const FrameObject& f) {
    RTCGeometry geometry = rtcNewGeometry(device, RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geometry, 1);
    rtcSetGeometryUserData(geometry, const_cast<FrameObject*>(&f));
    rtcSetGeometryBoundsFunction(geometry, CurvedBounds, nullptr);
    rtcSetGeometryIntersectFunction(geometry, ExactIntersect);
    Attach(geometry);
  }

  void Attach(RTCGeometry geometry) {
    rtcCommitGeometry(geometry);
    const unsigned id = rtcAttachGeometry(scene, geometry);
    rtcReleaseGeometry(geometry);
    if (object_of_geometry.size() <= id) object_of_geometry.resize(id + 1, -1);
    object_of_geometry[id] = attaching;
  }

  int attaching = -1;  // frame object index of the geometry being attached
};

bool EmbreeAvailable() { return true; }

EmbreeScene::EmbreeScene() : impl_(std::make_unique<Impl>()) {
  impl_->device = rtcNewDevice(nullptr);
  if (!impl_->device) {
    throw std::runtime_error("EmbreeScene: rtcNewDevice failed (error " +
                             std::to_string(rtcGetDeviceError(nullptr)) + ")");
  }
}

EmbreeScene::~EmbreeScene() = default;

void EmbreeScene::Build(const FrameContext& frame) {
  Impl& impl = *impl_;
  if (impl.scene) rtcReleaseScene(impl.scene);
  impl.scene = rtcNewScene(impl.device);
  rtcSetSceneBuildQuality(impl.scene, RTC_BUILD_QUALITY_LOW);
  impl.frame = &frame;
  impl.object_of_geometry.clear();
  impl.unbounded_objects.clear();
  for (int i = 0; i < static_cast<int>(frame.objects.size()); ++i) {
    const FrameObject& f = frame.objects[static_cast<size_t>(i)];
    impl.attaching = i;
    if (!f.bounded) {
      impl.unbounded_objects.push_back({i, 0.0});
    } else if (const auto* r = std::get_if<Rectangle>(f.primitive)) {
      impl.AttachMesh(f, RectangleMesh(*r), !r->polygon_holes.empty() || !r->ellipse_holes.empty());
    } else if (const auto* b = std::get_if<Box>(f.primitive)) {
      impl.AttachMesh(f, BoxMesh(*b), false);
    } else {
      impl.AttachCurved(f);
    }
  }
  rtcCommitScene(impl.scene);
}

namespace {

// The hit record of Embree's nearest geometry (RTC_INVALID_GEOMETRY_ID: none) along d_C: our
// exact test of that object, then of the unbounded objects up to its distance.
RayHit ExactHit(const FrameContext& frame, const std::vector<int>& object_of_geometry,
                const std::vector<TileCandidate>& unbounded_objects, unsigned geometry,
                const ExactHitContext& context, unsigned lane, const Eigen::Vector3d& d_C,
                double t_max) {
  RayHit best;
  if (geometry != RTC_INVALID_GEOMETRY_ID) {
    const int index = object_of_geometry[geometry];
    const FrameObject& f = frame.objects[static_cast<size_t>(index)];
    best.d_O = f.R_OC * d_C;
    if (context.geometry[lane] == geometry && context.hits[lane].t_m < t_max) {
      best.local = context.hits[lane];  // computed by our callback as Embree traversed
      best.index = index;
    } else if (IntersectPrimitive(*f.primitive, f.p_OC, best.d_O, kMinT, t_max, &best.local)) {
      best.index = index;
    } else {
      // Embree's float triangle and the double test disagree at an edge: the exact search.
      const std::pair<const TileCandidate*, const TileCandidate*> all(
          frame.all_objects.data(), frame.all_objects.data() + frame.all_objects.size());
      return TraceRay(d_C, frame.objects, all, -1, t_max);
    }
  }
  const std::pair<const TileCandidate*, const TileCandidate*> unbounded(
      unbounded_objects.data(), unbounded_objects.data() + unbounded_objects.size());
  const RayHit plane =
      TraceRay(d_C, frame.objects, unbounded, -1, best.index >= 0 ? best.local.t_m : t_max);
  return plane.index >= 0 ? plane : best;
}

}  // namespace

RayHit EmbreeScene::Nearest(const Eigen::Vector3d& d_C, double t_max) const {
  const Impl& impl = *impl_;
  RTCRayHit ray_hit;
  ray_hit.ray.org_x = ray_hit.ray.org_y = ray_hit.ray.org_z = 0.0f;
  ray_hit.ray.dir_x = static_cast<float>(d_C.x());
  ray_hit.ray.dir_y = static_cast<float>(d_C.y());
  ray_hit.ray.dir_z = static_cast<float>(d_C.z());
  ray_hit.ray.tnear = static_cast<float>(kMinT);
  // Rounded up so the float bound never drops a hit below t_max (the exact test re-checks).
  ray_hit.ray.tfar =
      std::nextafter(static_cast<float>(t_max), std::numeric_limits<float>::infinity());
  ray_hit.ray.mask = std::numeric_limits<unsigned>::max();
  ray_hit.ray.id = 0;
  ray_hit.ray.flags = 0;
  ray_hit.ray.time = 0.0f;
  ray_hit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  ray_hit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  ExactHitContext context(RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT);
  rtcIntersect1(impl.scene, &context.embree, &ray_hit);
  return ExactHit(*impl.frame, impl.object_of_geometry, impl.unbounded_objects, ray_hit.hit.geomID,
                  context, 0, d_C, t_max);
}

void EmbreeScene::NearestN(const Eigen::Vector3f* d_C, int n, RayHit* hits) const {
  const Impl& impl = *impl_;
  for (int first = 0; first < n; first += kEmbreePacket) {
    const int lanes = std::min(kEmbreePacket, n - first);
    alignas(64) int valid[kEmbreePacket];
    RTCRayHit16 packet;
    ExactHitContext context(RTC_INTERSECT_CONTEXT_FLAG_COHERENT);
    for (int i = 0; i < kEmbreePacket; ++i) {
      valid[i] = i < lanes ? -1 : 0;
      const Eigen::Vector3f& d = d_C[first + std::min(i, lanes - 1)];
      packet.ray.org_x[i] = packet.ray.org_y[i] = packet.ray.org_z[i] = 0.0f;
      packet.ray.dir_x[i] = d.x();
      packet.ray.dir_y[i] = d.y();
      packet.ray.dir_z[i] = d.z();
      packet.ray.tnear[i] = static_cast<float>(kMinT);
      packet.ray.tfar[i] = std::numeric_limits<float>::infinity();
      packet.ray.mask[i] = std::numeric_limits<unsigned>::max();
      packet.ray.id[i] = static_cast<unsigned>(i);
      packet.ray.flags[i] = 0;
      packet.ray.time[i] = 0.0f;
      packet.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
      packet.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    rtcIntersect16(valid, impl.scene, &context.embree, &packet);
    for (int i = 0; i < lanes; ++i) {
      hits[first + i] = ExactHit(*impl.frame, impl.object_of_geometry, impl.unbounded_objects,
                                 packet.hit.geomID[i], context, static_cast<unsigned>(i),
                                 d_C[first + i].cast<double>(), control::kInf);
    }
  }
}

#else  // !APERTURE_HAVE_EMBREE

struct EmbreeScene::Impl {};

bool EmbreeAvailable() { return false; }

EmbreeScene::EmbreeScene() {
  throw std::runtime_error(
      "the Embree back end is not in this build: install libembree-dev (scripts/install-deps.sh) "
      "and configure with -DAPERTURE_EMBREE=ON");
}

EmbreeScene::~EmbreeScene() = default;
void EmbreeScene::Build(const FrameContext&) {}
RayHit EmbreeScene::Nearest(const Eigen::Vector3d&, double) const { return {}; }
void EmbreeScene::NearestN(const Eigen::Vector3f*, int, RayHit*) const {}

#endif

}  // namespace aperture::sim
