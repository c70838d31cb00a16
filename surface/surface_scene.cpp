#include "surface/surface_scene.h"

#include "core/error.h"
#include "lights/ray_sphere.h"
#include "surface/box_faces.h"
#include "surface/sphere_light_occluders.h"

#include <embree3/rtcore.h>

#include <array>
#include <atomic>
#include <cmath>
#include <cstring>
#include <limits>
#include <mutex>
#include <string>

namespace kasumi {

namespace {

/// One shape as Embree sees it. Boxes, quads and meshes are triangles; spheres are a user
/// geometry intersected in double precision.
struct Geometry {
    bool is_sphere = false;
    std::vector<Vec3> positions;
    std::vector<Vec3> normals;      ///< per vertex, or empty
    bool authored_normals = false;  ///< the normals came from the file and define the outside
    Shading shading = Shading::Flat;
    std::vector<std::array<uint32_t, 3>> triangles;
    DVec3 center{0.0};
    double radius = 0.0;
    /// Spheres: the centre in float and the squared reach of line_may_meet_sphere's test.
    Vec3 center_float{0.0f};
    float reach_squared = 0.0f;
    /// Triangles of small geometries (boxes, quads, meshes up to kFaceTableMax triangles): the
    /// unit normal in double and the error scale hit_from would compute at every hit (a zero
    /// normal for a degenerate triangle: computed at the hit instead); empty otherwise.
    std::vector<DVec3> face_normals;
    std::vector<float> face_error_scales;
    uint32_t material = 0;
};

/// Up to this many triangles a geometry keeps its face table (28 bytes a triangle).
constexpr size_t kFaceTableMax = size_t{1} << 16;

/// The unit normal of triangle `tri` in double, zero when degenerate (exactly as hit_from
/// computed it at every hit before the table).
DVec3 face_normal(const Geometry& g, const std::array<uint32_t, 3>& tri) {
    const DVec3 v0(g.positions[tri[0]]);
    const DVec3 v1(g.positions[tri[1]]);
    const DVec3 v2(g.positions[tri[2]]);
    const DVec3 cross = glm::cross(v1 - v0, v2 - v0);
    const double area2 = glm::length(cross);
    return area2 > 0.0 ? cross / area2 : DVec3(0.0);
}

float face_error_scale(const Geometry& g, const std::array<uint32_t, 3>& tri) {
    return max_abs_coordinate(
        glm::max(glm::abs(g.positions[tri[0]]),
                 glm::max(glm::abs(g.positions[tri[1]]), glm::abs(g.positions[tri[2]]))));
}

void build_face_table(Geometry& g) {
    if (g.is_sphere || g.triangles.size() > kFaceTableMax)
        return;
    g.face_normals.reserve(g.triangles.size());
    g.face_error_scales.reserve(g.triangles.size());
    for (const auto& tri : g.triangles) {
        g.face_normals.push_back(face_normal(g, tri));
        g.face_error_scales.push_back(face_error_scale(g, tri));
    }
}

void add_quad(Geometry& g, const Vec3& v0, const Vec3& v1, const Vec3& v2, const Vec3& v3) {
    const auto base = static_cast<uint32_t>(g.positions.size());
    g.positions.insert(g.positions.end(), {v0, v1, v2, v3});
    // Both triangles keep the quad's winding, so cross(v1 - v0, v2 - v0) is the front side.
    g.triangles.push_back({base, base + 1, base + 2});
    g.triangles.push_back({base, base + 2, base + 3});
}

Geometry make_geometry(const SphereShape& s) {
    Geometry g;
    g.is_sphere = true;
    g.center = DVec3(s.center);
    g.radius = s.radius;
    g.center_float = Vec3(g.center);
    const float radius = static_cast<float>(g.radius);
    const float reach = radius + 1e-6f * (max_abs_coordinate(g.center_float) + radius);
    g.reach_squared = reach * reach;
    return g;
}

Geometry make_geometry(const QuadShape& q) {
    Geometry g;
    add_quad(g, q.vertices[0], q.vertices[1], q.vertices[2], q.vertices[3]);
    return g;
}

Geometry make_geometry(const BoxShape& b) {
    Geometry g;
    for (const std::array<Vec3, 4>& c : box_faces(b))
        add_quad(g, c[0], c[1], c[2], c[3]);
    return g;
}

Geometry make_geometry(const MeshShape& m) {
    for (const auto& triangle : m.mesh.triangles)
        for (const uint32_t index : triangle)
            KASUMI_CHECK(index < m.mesh.positions.size());
    KASUMI_CHECK(m.mesh.normals.empty() || m.mesh.normals.size() == m.mesh.positions.size());
    Geometry g;
    g.positions = m.mesh.positions;
    g.normals = m.mesh.normals;
    g.authored_normals = !g.normals.empty();
    g.triangles = m.mesh.triangles;
    return g;
}

void sphere_bounds(const RTCBoundsFunctionArguments* args) {
    const auto* g = static_cast<const Geometry*>(args->geometryUserPtr);
    RTCBounds* out = args->bounds_o;
    // Round outward so the float box contains the double sphere.
    const auto down = [](double x) {
        return std::nextafter(static_cast<float>(x), -std::numeric_limits<float>::infinity());
    };
    const auto up = [](double x) {
        return std::nextafter(static_cast<float>(x), std::numeric_limits<float>::infinity());
    };
    out->lower_x = down(g->center.x - g->radius);
    out->lower_y = down(g->center.y - g->radius);
    out->lower_z = down(g->center.z - g->radius);
    out->upper_x = up(g->center.x + g->radius);
    out->upper_y = up(g->center.y + g->radius);
    out->upper_z = up(g->center.z + g->radius);
}

/// Ray i of an Embree packet of N rays, in double precision; [t_near, t_far] is its current
/// interval.
struct PacketRay {
    DVec3 origin;
    DVec3 direction;
    double t_near = 0.0;
    double t_far = 0.0;
};

PacketRay packet_ray(RTCRayN* ray, unsigned N, unsigned i) {
    return {DVec3(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i), RTCRayN_org_z(ray, N, i)),
            DVec3(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i)),
            RTCRayN_tnear(ray, N, i), RTCRayN_tfar(ray, N, i)};
}

/// False only when the line of ray i passes clear of the sphere by far more than float
/// rounding, so the exact test (intersect_sphere, in double) would miss it too. Embree calls a
/// user geometry for every ray that reaches its BVH leaf, and a scene with one sphere has a
/// leaf for a root: without this every camera ray of a scene paid the double-precision test,
/// most of them missing the sphere by metres.
///
/// In float, from the float ray: f = c − o; the squared distance of the centre from the line is
/// (f·f d·d − (f·d)²) / d·d. Errors against the exact value (ε = 2^-24): rounding the double
/// centre to float moves the centre by at most √3 ε ‖c‖∞ and the subtraction f by √3 ε ‖f‖∞,
/// which move the distance as much (it is 1-Lipschitz in the centre); the products and the
/// cancellation f·f d·d − (f·d)² err by at most ~8 ε f·f d·d. The test keeps every ray with
/// distance² ≤ (r + m)² + 1e-5 f·f, m = 1e-6 (‖c‖∞ + r): the 1e-5 f·f term exceeds the
/// product error 100-fold and the ‖f‖ shift (2 r √3 ε ‖f‖ ≤ √3 ε (r² + f·f)) with the 2 r m
/// term, and m exceeds the centre shift 5-fold or more. So a ray dropped here misses in exact
/// arithmetic too, by far more than the double test's own rounding.
inline bool line_may_meet_sphere(const Geometry& g, RTCRayN* ray, unsigned N, unsigned i) {
    const Vec3 f = g.center_float - Vec3(RTCRayN_org_x(ray, N, i), RTCRayN_org_y(ray, N, i),
                                         RTCRayN_org_z(ray, N, i));
    const Vec3 d(RTCRayN_dir_x(ray, N, i), RTCRayN_dir_y(ray, N, i), RTCRayN_dir_z(ray, N, i));
    const float dd = glm::dot(d, d), b = glm::dot(f, d), ff = glm::dot(f, f);
    // NaN and degenerate directions compare false and are kept: the exact test decides.
    return !(ff * dd - b * b > (g.reach_squared + 1e-5f * ff) * dd);
}

void sphere_intersect(const RTCIntersectFunctionNArguments* args) {
    const auto* g = static_cast<const Geometry*>(args->geometryUserPtr);
    RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
    RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
    for (unsigned i = 0; i < args->N; ++i) {
        if (!args->valid[i] || !line_may_meet_sphere(*g, ray, args->N, i))
            continue;
        const PacketRay r = packet_ray(ray, args->N, i);
        const std::optional<double> t =
            intersect_sphere(g->center, g->radius, r.origin, r.direction, r.t_near, r.t_far);
        if (!t)
            continue;
        const DVec3 n = r.origin + *t * r.direction - g->center;
        RTCRayN_tfar(ray, args->N, i) = static_cast<float>(*t);
        RTCHitN_Ng_x(hit, args->N, i) = static_cast<float>(n.x);
        RTCHitN_Ng_y(hit, args->N, i) = static_cast<float>(n.y);
        RTCHitN_Ng_z(hit, args->N, i) = static_cast<float>(n.z);
        RTCHitN_u(hit, args->N, i) = 0.0f;
        RTCHitN_v(hit, args->N, i) = 0.0f;
        RTCHitN_primID(hit, args->N, i) = args->primID;
        RTCHitN_geomID(hit, args->N, i) = args->geomID;
        RTCHitN_instID(hit, args->N, i, 0) = args->context->instID[0];
    }
}

void sphere_occluded(const RTCOccludedFunctionNArguments* args) {
    const auto* g = static_cast<const Geometry*>(args->geometryUserPtr);
    RTCRayN* ray = args->ray;
    for (unsigned i = 0; i < args->N; ++i) {
        if (!args->valid[i] || !line_may_meet_sphere(*g, ray, args->N, i))
            continue;
        const PacketRay r = packet_ray(ray, args->N, i);
        if (intersect_sphere(g->center, g->radius, r.origin, r.direction, r.t_near, r.t_far))
            RTCRayN_tfar(ray, args->N, i) = -std::numeric_limits<float>::infinity();
    }
}

/// std::nextafter(x, +inf) for x >= 0 (or NaN) without the libm call (it was 8% of a
/// soft-shadow render's CPU time): one integer step of the bit pattern, which for IEEE 754
/// floats of one sign is the adjacent representable value (Ray Tracing Gems, ch. 6).
float next_float_up_nonnegative(float x) {
    if (x == 0.0f)
        return std::numeric_limits<float>::denorm_min();
    if (!(x < std::numeric_limits<float>::infinity()))
        return x;  // +inf and NaN stay
    uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    ++bits;
    std::memcpy(&x, &bits, sizeof x);
    return x;
}

/// std::nextafter(x, 0): the bit pattern's magnitude one step smaller (±inf become ±max).
float next_float_toward_zero(float x) {
    if (x == 0.0f || std::isnan(x))
        return x;
    uint32_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    --bits;
    std::memcpy(&x, &bits, sizeof x);
    return x;
}

/// Embree's interval is closed, [tnear, tfar]; ours is open, (t_min, t_max).
void set_interval(RTCRay& r, const Ray& ray) {
    r.org_x = ray.origin.x;
    r.org_y = ray.origin.y;
    r.org_z = ray.origin.z;
    r.dir_x = ray.direction.x;
    r.dir_y = ray.direction.y;
    r.dir_z = ray.direction.z;
    r.tnear = next_float_up_nonnegative(std::max(ray.t_min, 0.0f));
    r.tfar = next_float_toward_zero(ray.t_max);
    r.time = 0.0f;
    r.mask = ~0u;
    r.id = 0;
    r.flags = 0;
}

/// A number for the calling thread, unique in the process (ordinals are never reused).
unsigned thread_ordinal() {
    static std::atomic<unsigned> next{0};
    thread_local const unsigned ordinal = next.fetch_add(1, std::memory_order_relaxed);
    return ordinal;
}

}  // namespace

struct SurfaceScene::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::vector<Geometry> geometries;
    std::unique_ptr<SphereLightOccluders> occluders;
    uint64_t primitives = 0;
    Bounds3 bounds;
    /// Ray counts, one cache line per thread: thread k < kShards - 1 alone writes shard k, with
    /// a plain load and store (an uncontended locked add per ray cost ~4% of a soft-shadow
    /// render); threads beyond share the last shard through fetch_add. stats() sums them.
    struct alignas(64) RayCounts {
        std::atomic<uint64_t> closest{0};
        std::atomic<uint64_t> shadow{0};
    };
    static constexpr unsigned kShards = 64;
    mutable std::array<RayCounts, kShards> ray_counts;
    std::mutex error_mutex;
    std::string error;  ///< the first error Embree reported, if any

    /// Embree calls this from inside its C API, where exceptions must not pass: record the
    /// message, and throw from check() once control is back in our code.
    static void on_error(void* user, RTCError code, const char* message) {
        auto* self = static_cast<Impl*>(user);
        const std::lock_guard<std::mutex> lock(self->error_mutex);
        if (self->error.empty())
            self->error = "Embree error " + std::to_string(static_cast<int>(code)) + ": " +
                          (message ? message : "(no message)");
    }

    void check(const char* during) {
        const std::lock_guard<std::mutex> lock(error_mutex);
        if (!error.empty())
            throw Error(ErrorKind::Runtime, std::string(during) + ": " + error);
    }

    /// Adds one to the calling thread's count `member` (closest or shadow).
    void count(std::atomic<uint64_t> RayCounts::*member) const {
        const unsigned ordinal = thread_ordinal();
        if (ordinal < kShards - 1) {
            std::atomic<uint64_t>& c = ray_counts[ordinal].*member;
            c.store(c.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
        } else {
            (ray_counts[kShards - 1].*member).fetch_add(1, std::memory_order_relaxed);
        }
    }

    ~Impl() {
        if (scene)
            rtcReleaseScene(scene);
        if (device)
            rtcReleaseDevice(device);
    }
};

SurfaceScene::SurfaceScene(const std::vector<Shape>& shapes) : m_impl(std::make_unique<Impl>()) {
    Impl& impl = *m_impl;
    impl.device = rtcNewDevice(nullptr);
    if (!impl.device)
        throw Error(ErrorKind::Runtime,
                    "cannot create the Embree device (error " +
                        std::to_string(static_cast<int>(rtcGetDeviceError(nullptr))) + ")");
    rtcSetDeviceErrorFunction(impl.device, &Impl::on_error, &impl);
    if (!rtcGetDeviceProperty(impl.device, RTC_DEVICE_PROPERTY_USER_GEOMETRY_SUPPORTED) ||
        !rtcGetDeviceProperty(impl.device, RTC_DEVICE_PROPERTY_TRIANGLE_GEOMETRY_SUPPORTED))
        throw Error(ErrorKind::Runtime, "Embree lacks triangle or user geometry support");
    if (rtcGetDeviceProperty(impl.device, RTC_DEVICE_PROPERTY_BACKFACE_CULLING_ENABLED))
        throw Error(ErrorKind::Runtime,
                    "Embree was built with back-face culling; kasumi "
                    "needs hits on both sides of a surface");

    impl.occluders = std::make_unique<SphereLightOccluders>(shapes);
    impl.scene = rtcNewScene(impl.device);
    rtcSetSceneFlags(impl.scene, RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(impl.scene, RTC_BUILD_QUALITY_HIGH);

    impl.geometries.reserve(shapes.size());
    for (const Shape& shape : shapes) {
        impl.geometries.push_back(
            std::visit([](const auto& s) { return make_geometry(s); }, shape.geometry));
        Geometry& g = impl.geometries.back();
        g.material = shape.material;
        g.shading = shading_of(shape);
        if (!g.is_sphere && g.shading != Shading::Flat && g.normals.empty())
            g.normals = angle_weighted_normals(g.positions, g.triangles);
        build_face_table(g);
    }
    // The geometries' addresses are stable from here on: Embree keeps pointers to spheres.
    for (size_t id = 0; id < impl.geometries.size(); ++id) {
        Geometry& g = impl.geometries[id];
        RTCGeometry geometry = nullptr;
        if (g.is_sphere) {
            geometry = rtcNewGeometry(impl.device, RTC_GEOMETRY_TYPE_USER);
            rtcSetGeometryUserPrimitiveCount(geometry, 1);
            rtcSetGeometryUserData(geometry, &g);
            rtcSetGeometryBoundsFunction(geometry, &sphere_bounds, nullptr);
            rtcSetGeometryIntersectFunction(geometry, &sphere_intersect);
            rtcSetGeometryOccludedFunction(geometry, &sphere_occluded);
            impl.primitives += 1;
        } else {
            geometry = rtcNewGeometry(impl.device, RTC_GEOMETRY_TYPE_TRIANGLE);
            // Embree-owned buffers: Embree pads them for its vector loads.
            auto* vertices = static_cast<float*>(
                rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                        3 * sizeof(float), g.positions.size()));
            auto* indices = static_cast<uint32_t*>(
                rtcSetNewGeometryBuffer(geometry, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                        3 * sizeof(uint32_t), g.triangles.size()));
            impl.check("creating Embree buffers");
            std::memcpy(vertices, g.positions.data(), g.positions.size() * sizeof(Vec3));
            std::memcpy(indices, g.triangles.data(), g.triangles.size() * 3 * sizeof(uint32_t));
            rtcSetGeometryBuildQuality(geometry, RTC_BUILD_QUALITY_HIGH);
            impl.primitives += g.triangles.size();
        }
        rtcCommitGeometry(geometry);
        rtcAttachGeometryByID(impl.scene, geometry, static_cast<unsigned>(id));
        rtcReleaseGeometry(geometry);
        impl.check("building Embree geometry");
    }
    rtcCommitScene(impl.scene);
    impl.check("building the Embree BVH");
    if (!impl.geometries.empty()) {
        RTCBounds b;
        rtcGetSceneBounds(impl.scene, &b);
        impl.bounds.min = Vec3(b.lower_x, b.lower_y, b.lower_z);
        impl.bounds.max = Vec3(b.upper_x, b.upper_y, b.upper_z);
    }
}

SurfaceScene::~SurfaceScene() = default;

std::optional<SurfaceHit> SurfaceScene::intersect(const Ray& ray) const {
    m_impl->count(&Impl::RayCounts::closest);
    KASUMI_DCHECK(std::abs(glm::dot(ray.direction, ray.direction) - 1.0f) < 1e-4f);
    if (!(ray.t_min < ray.t_max))
        return std::nullopt;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRayHit rayhit;
    set_interval(rayhit.ray, ray);
    rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.primID = RTC_INVALID_GEOMETRY_ID;
    rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(m_impl->scene, &context, &rayhit);
    return hit_from(ray, rayhit);
}

void SurfaceScene::intersect_coherent(const Ray* rays, size_t count,
                                      std::optional<SurfaceHit>* hits) const {
    // Embree's stream interface: with the coherent flag it gathers the rays into packets and
    // traverses them together (one BVH node test for up to 8 rays), which pays for camera rays
    // of neighbouring pixels. The hits are built exactly as intersect() builds them.
    constexpr size_t kBatch = 64;
    RTCRayHit batch[kBatch];
    for (size_t start = 0; start < count; start += kBatch) {
        const size_t n = std::min(kBatch, count - start);
        for (size_t i = 0; i < n; ++i) {
            const Ray& ray = rays[start + i];
            m_impl->count(&Impl::RayCounts::closest);
            KASUMI_DCHECK(std::abs(glm::dot(ray.direction, ray.direction) - 1.0f) < 1e-4f);
            RTCRayHit& rayhit = batch[i];
            set_interval(rayhit.ray, ray);
            if (!(ray.t_min < ray.t_max)) {  // empty: inactive for Embree (tnear > tfar)
                rayhit.ray.tnear = 1.0f;
                rayhit.ray.tfar = 0.0f;
            }
            rayhit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
            rayhit.hit.primID = RTC_INVALID_GEOMETRY_ID;
            rayhit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        }
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
        rtcIntersect1M(m_impl->scene, &context, batch, static_cast<unsigned>(n), sizeof(RTCRayHit));
        for (size_t i = 0; i < n; ++i) {
            const Ray& ray = rays[start + i];
            hits[start + i] = ray.t_min < ray.t_max ? hit_from(ray, batch[i]) : std::nullopt;
        }
    }
}

std::optional<SurfaceHit> SurfaceScene::hit_from(const Ray& ray, const RTCRayHit& rayhit) const {
    if (rayhit.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return std::nullopt;

    const Geometry& g = m_impl->geometries[rayhit.hit.geomID];
    SurfaceHit hit;
    hit.t = rayhit.ray.tfar;
    hit.shape = rayhit.hit.geomID;
    hit.material = g.material;
    hit.shading = g.shading;
    const DVec3 origin(ray.origin);
    const DVec3 direction(ray.direction);
    const DVec3 p = origin + static_cast<double>(hit.t) * direction;
    if (g.is_sphere) {
        // Recompute in double from the float t, then project onto the sphere: the position is
        // then within float rounding of the surface whatever the ray's length.
        DVec3 n = p - g.center;
        const double length = glm::length(n);
        n = length > 0.0 ? n / length : DVec3(0.0, 0.0, 1.0);
        hit.position = Vec3(g.center + g.radius * n);
        hit.geometric_normal = Vec3(n);
        hit.shading_normal = hit.geometric_normal;
        // Double arithmetic leaves ~2^-50 (|c| + r) of error: a scale 2^-30 (|c| + r) makes
        // the offset 2^-47 (|c| + r), far above it, so planet-sized spheres still get offsets
        // set by |p| alone.
        hit.error_scale = static_cast<float>((glm::length(g.center) + g.radius) * 0x1p-30);
        return hit;
    }

    return triangle_hit(ray, hit.shape, rayhit.hit.primID, hit.t, rayhit.hit.u, rayhit.hit.v,
                        DVec3(rayhit.hit.Ng_x, rayhit.hit.Ng_y, rayhit.hit.Ng_z));
}

SurfaceHit SurfaceScene::hit_on_triangle(const Ray& ray, uint32_t shape, uint32_t primitive,
                                         float t, float u, float v) const {
    KASUMI_CHECK(shape < m_impl->geometries.size() && !m_impl->geometries[shape].is_sphere &&
                 primitive < m_impl->geometries[shape].triangles.size());
    return triangle_hit(ray, shape, primitive, t, u, v, DVec3(0.0, 0.0, 1.0));
}

SurfaceHit SurfaceScene::triangle_hit(const Ray& ray, uint32_t shape, uint32_t primitive, float t,
                                      float u, float v, const DVec3& fallback_normal) const {
    const Geometry& g = m_impl->geometries[shape];
    SurfaceHit hit;
    hit.t = t;
    hit.shape = shape;
    hit.material = g.material;
    hit.shading = g.shading;
    const DVec3 p = DVec3(ray.origin) + static_cast<double>(hit.t) * DVec3(ray.direction);
    hit.primitive = primitive;
    hit.u = u;
    hit.v = v;
    const auto& tri = g.triangles[primitive];
    const DVec3 v0(g.positions[tri[0]]);
    const bool tabled = !g.face_normals.empty();
    DVec3 n = tabled ? g.face_normals[primitive] : face_normal(g, tri);
    if (n == DVec3(0.0))  // degenerate: Embree's normal
        n = glm::normalize(fallback_normal);
    // Project onto the triangle's plane: removes the error t carries along the ray.
    hit.position = Vec3(p - glm::dot(p - v0, n) * n);
    hit.error_scale = tabled ? g.face_error_scales[primitive] : face_error_scale(g, tri);
    hit.shading_normal = Vec3(n);
    if (!g.normals.empty()) {
        const Vec3 interpolated = kasumi::interpolate<Vec3>(
            {g.normals[tri[0]], g.normals[tri[1]], g.normals[tri[2]]}, hit.u, hit.v);
        const float length = glm::length(interpolated);
        if (length > 0.0f && std::isfinite(length)) {
            if (g.shading != Shading::Flat)
                hit.shading_normal = interpolated / length;
            // Authored normals say which side is out (pbrt-v4's convention): the geometric
            // normal follows them, so a mesh with inconsistent winding still faces outward.
            if (g.authored_normals && glm::dot(DVec3(interpolated), n) < 0.0) {
                n = -n;
                if (g.shading == Shading::Flat)
                    hit.shading_normal = -hit.shading_normal;
            }
        }
    }
    hit.geometric_normal = Vec3(n);
    return hit;
}

std::optional<HitTriangle> SurfaceScene::triangle(const SurfaceHit& hit) const {
    KASUMI_DCHECK(hit.shape < m_impl->geometries.size());
    const Geometry& g = m_impl->geometries[hit.shape];
    if (g.is_sphere)
        return std::nullopt;
    KASUMI_DCHECK(hit.primitive < g.triangles.size());
    const auto& tri = g.triangles[hit.primitive];
    HitTriangle out;
    for (int k = 0; k < 3; ++k) {
        out.positions[k] = g.positions[tri[k]];
        out.normals[k] = g.normals.empty() ? hit.geometric_normal : g.normals[tri[k]];
    }
    return out;
}

bool SurfaceScene::occluded(const Ray& ray) const {
    m_impl->count(&Impl::RayCounts::shadow);
    KASUMI_DCHECK(std::abs(glm::dot(ray.direction, ray.direction) - 1.0f) < 1e-4f);
    if (!(ray.t_min < ray.t_max))
        return false;
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay r;
    set_interval(r, ray);
    rtcOccluded1(m_impl->scene, &context, &r);
    // Embree marks a blocked ray by setting tfar to -inf.
    return r.tfar < 0.0f;
}

Bounds3 SurfaceScene::bounds() const {
    return m_impl->bounds;
}

const SphereLightOccluders& SurfaceScene::sphere_light_occluders() const {
    return *m_impl->occluders;
}

SurfaceStats SurfaceScene::stats() const {
    SurfaceStats s;
    for (const Impl::RayCounts& c : m_impl->ray_counts) {
        s.closest_rays += c.closest.load(std::memory_order_relaxed);
        s.shadow_rays += c.shadow.load(std::memory_order_relaxed);
    }
    s.primitives = m_impl->primitives;
    return s;
}

}  // namespace kasumi
