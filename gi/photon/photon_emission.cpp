#include "gi/photon/photon_emission.h"

#include "core/sampling.h"

#include <algorithm>
#include <numeric>

namespace kasumi {

namespace {

/// Solves F(x) = u for an increasing F on [lo, hi] by bisection to float precision (the CDFs
/// here are smooth but Newton would need safeguards at their flat ends).
template <class Cdf>
float invert_cdf(Cdf&& cdf, double u, double lo, double hi) {
    for (int i = 0; i < 48; ++i) {
        const double mid = 0.5 * (lo + hi);
        (cdf(mid) < u ? lo : hi) = mid;
    }
    return static_cast<float>(0.5 * (lo + hi));
}

/// A cosine-weighted direction about n (pdf cos θ / π per steradian): Lambertian emission.
Vec3 lambertian_direction(const Vec3& n, Vec2 u) {
    return Frame(n).to_world(sample_cosine_hemisphere(u));
}

Rgb flux_of(const DirectionalLight& l, const BoundingSphere& scene) {
    return l.illuminance * (kPi * scene.radius * scene.radius);
}
Rgb flux_of(const PointLight& l, const BoundingSphere&) {
    return l.intensity * (4.0f * kPi);
}
Rgb flux_of(const SpotLight& l, const BoundingSphere&) {
    return l.intensity * spot_flux_per_cd(l);
}
Rgb flux_of(const GoniometricLight& l, const BoundingSphere&) {
    return l.scale * static_cast<float>(ies_flux_lm(*l.profile));
}
Rgb flux_of(const LineLight& l, const BoundingSphere&) {
    return l.intensity_per_m * (kPi * kPi * glm::length(l.to - l.from));
}
Rgb flux_of(const PolygonLight& l, const BoundingSphere&) {
    return l.luminance * (kPi * l.area * (l.two_sided ? 2.0f : 1.0f));
}
Rgb flux_of(const SphereLight& l, const BoundingSphere&) {
    return l.luminance * (4.0f * kPi * kPi * l.radius * l.radius);
}

}  // namespace

/// One emitting thing: its flux and a sampler of rays with density ∝ emitted radiance.
class PhotonSource {
  public:
    virtual ~PhotonSource() = default;
    virtual Rgb flux() const = 0;
    virtual Ray sample(Pcg32& rng) const = 0;
};

namespace {

class DirectionalSource final : public PhotonSource {
  public:
    DirectionalSource(const DirectionalLight& l, const BoundingSphere& s)
        : m_light(l), m_scene(s) {}
    Rgb flux() const override { return flux_of(m_light, m_scene); }
    Ray sample(Pcg32& rng) const override {
        const Vec3 d = glm::normalize(m_light.direction);
        const Frame frame(d);
        const Vec2 u = rng.next_vec2();
        const float r = m_scene.radius * std::sqrt(u.x), phi = kTwoPi * u.y;
        // Start one radius before the centre: the whole bounding sphere lies ahead.
        const Vec3 origin = m_scene.center - m_scene.radius * 1.001f * d +
                            frame.to_world(Vec3(r * std::cos(phi), r * std::sin(phi), 0.0f));
        return Ray{origin, d, 0.0f, kInfinity};
    }

  private:
    DirectionalLight m_light;
    BoundingSphere m_scene;
};

class PointSource final : public PhotonSource {
  public:
    explicit PointSource(const PointLight& l) : m_light(l) {}
    Rgb flux() const override { return flux_of(m_light, {}); }
    Ray sample(Pcg32& rng) const override {
        return Ray{m_light.position, sample_uniform_sphere(rng.next_vec2()), 0.0f, kInfinity};
    }

  private:
    PointLight m_light;
};

class SpotSource final : public PhotonSource {
  public:
    explicit SpotSource(const SpotLight& l) : m_light(l) {}
    Rgb flux() const override { return flux_of(m_light, {}); }
    Ray sample(Pcg32& rng) const override {
        // Density in μ = cos θ ∝ s(μ): 1 on [cos_falloff, 1] (mass 1 - cos_falloff), the
        // smoothstep on the band (mass (cos_falloff - cos_cone) / 2).
        const double inner = 1.0 - m_light.cos_falloff;
        const double band = 0.5 * (static_cast<double>(m_light.cos_falloff) - m_light.cos_cone);
        const double u = rng.next_double() * (inner + band);
        float mu;
        if (u < inner) {
            mu = static_cast<float>(1.0 - u);
        } else {
            // t in [0, 1] with density 2 (3t² - 2t³): CDF 2t³ - t⁴.
            const double v = (u - inner) / band;
            const float t = invert_cdf([](double x) { return x * x * x * (2.0 - x); }, v, 0.0, 1.0);
            mu = m_light.cos_cone + t * (m_light.cos_falloff - m_light.cos_cone);
        }
        const Vec3 d =
            direction_about(glm::normalize(m_light.direction), mu, kTwoPi * rng.next_float());
        return Ray{m_light.position, d, 0.0f, kInfinity};
    }

  private:
    SpotLight m_light;
};

class GoniometricSource final : public PhotonSource {
  public:
    explicit GoniometricSource(const GoniometricLight& l) : m_light(l) {
        const IesProfile& p = *l.profile;
        const size_t nv = p.vertical_deg.size();
        double total = 0.0;
        for (size_t i = 0; i + 1 < p.horizontal_deg.size(); ++i) {
            for (size_t j = 0; j + 1 < nv; ++j) {
                const double g0 = p.vertical_deg[j] * (kPiD / 180.0);
                const double g1 = p.vertical_deg[j + 1] * (kPiD / 180.0);
                const double dg = g1 - g0;
                const double dc = (p.horizontal_deg[i + 1] - p.horizontal_deg[i]) * (kPiD / 180.0);
                if (!(dg > 0.0) || !(dc > 0.0))
                    continue;
                // ∫ I sin γ dγ dC of the bilinear interpolant over the cell (as ies_flux_lm).
                const double w0 = (dg * std::cos(g0) + std::sin(g0) - std::sin(g1)) / dg;
                const double w1 = (-dg * std::cos(g1) + std::sin(g1) - std::sin(g0)) / dg;
                const float c00 = p.candela[i * nv + j], c01 = p.candela[i * nv + j + 1];
                const float c10 = p.candela[(i + 1) * nv + j],
                            c11 = p.candela[(i + 1) * nv + j + 1];
                const double flux = dc * (w0 * 0.5 * (c00 + c10) + w1 * 0.5 * (c01 + c11));
                const float peak = std::max(std::max(c00, c01), std::max(c10, c11));
                if (!(flux > 0.0) || !(peak > 0.0))
                    continue;
                total += flux;
                m_cells.push_back({static_cast<uint32_t>(i), static_cast<uint32_t>(j), peak});
                m_cdf.push_back(total);
            }
        }
        for (double& c : m_cdf)
            c /= total;
    }
    Rgb flux() const override { return flux_of(m_light, {}); }
    Ray sample(Pcg32& rng) const override {
        const IesProfile& p = *m_light.profile;
        Vec3 local(0.0f, 0.0f, -1.0f);
        if (!m_cells.empty()) {
            const double u = rng.next_double();
            const size_t k = std::min<size_t>(
                static_cast<size_t>(std::lower_bound(m_cdf.begin(), m_cdf.end(), u) -
                                    m_cdf.begin()),
                m_cells.size() - 1);
            const Cell& cell = m_cells[k];
            const float g0 = p.vertical_deg[cell.v], g1 = p.vertical_deg[cell.v + 1];
            const float c0 = p.horizontal_deg[cell.h], c1 = p.horizontal_deg[cell.h + 1];
            const float cos0 = std::cos(radians(g0)), cos1 = std::cos(radians(g1));
            // Uniform in solid angle over the cell, accepted with I / I_max: the accepted
            // directions have density ∝ I within the cell (the bilinear I never exceeds the
            // largest corner). The loop is bounded; a failure (never seen) keeps the last try.
            for (int attempt = 0; attempt < 1000; ++attempt) {
                const Vec2 u2 = rng.next_vec2();
                const float cos_g = cos1 + u2.x * (cos0 - cos1);
                const float gamma = degrees(safe_acos(cos_g));
                const float c = c0 + u2.y * (c1 - c0);
                const float sin_g = safe_sqrt(1.0f - cos_g * cos_g);
                local = Vec3(sin_g * std::cos(radians(c)), sin_g * std::sin(radians(c)), -cos_g);
                if (rng.next_float() * cell.peak < ies_candela(p, gamma, c))
                    break;
            }
        }
        const Vec3 d = glm::normalize(m_light.local_to_world * local);
        return Ray{m_light.position, d, 0.0f, kInfinity};
    }

  private:
    struct Cell {
        uint32_t h = 0, v = 0;
        float peak = 0.0f;
    };
    GoniometricLight m_light;
    std::vector<Cell> m_cells;
    std::vector<double> m_cdf;
};

class LineSource final : public PhotonSource {
  public:
    explicit LineSource(const LineLight& l) : m_light(l) {}
    Rgb flux() const override { return flux_of(m_light, {}); }
    Ray sample(Pcg32& rng) const override {
        const Vec3 axis = glm::normalize(m_light.to - m_light.from);
        const Vec3 origin = m_light.from + rng.next_float() * (m_light.to - m_light.from);
        // Intensity ∝ sin α per steradian, dω = sin α dα dφ: α has density sin²α / (π/2),
        // CDF (α - sin α cos α) / π.
        const double u = rng.next_double();
        const float alpha = invert_cdf(
            [](double a) { return (a - std::sin(a) * std::cos(a)) / kPiD; }, u, 0.0, kPiD);
        const Vec3 d = direction_about(axis, std::cos(alpha), kTwoPi * rng.next_float());
        return Ray{origin, d, 0.0f, kInfinity};
    }

  private:
    LineLight m_light;
};

class PolygonSource final : public PhotonSource {
  public:
    explicit PolygonSource(const PolygonLight& l) : m_light(l) {}
    Rgb flux() const override { return flux_of(m_light, {}); }
    Ray sample(Pcg32& rng) const override {
        const PolygonLight& l = m_light;
        const float u = rng.next_float();
        size_t tri = 0;
        while (tri + 1 < l.fan_cdf.size() && u >= l.fan_cdf[tri])
            ++tri;
        const Vec2 b = rng.next_vec2();
        const float su = std::sqrt(b.x);
        const Vec3& v0 = l.vertices[0];
        const Vec3 x =
            v0 + (1.0f - su) * (l.vertices[tri + 1] - v0) + (b.y * su) * (l.vertices[tri + 2] - v0);
        Vec3 n = l.normal;
        if (l.two_sided && rng.next_float() < 0.5f)
            n = -n;
        const Vec3 d = lambertian_direction(n, rng.next_vec2());
        return Ray{x + 1e-5f * n, d, 0.0f, kInfinity};
    }

  private:
    PolygonLight m_light;
};

class SphereSource final : public PhotonSource {
  public:
    SphereSource(const Vec3& center, float radius, const Rgb& flux)
        : m_center(center), m_radius(radius), m_flux(flux) {}
    Rgb flux() const override { return m_flux; }
    Ray sample(Pcg32& rng) const override {
        const Vec3 n = sample_uniform_sphere(rng.next_vec2());
        const Vec3 d = lambertian_direction(n, rng.next_vec2());
        // Start a hair outside so an emissive sphere does not intersect itself.
        return Ray{m_center + n * (m_radius * (1.0f + 1e-5f)), d, 0.0f, kInfinity};
    }

  private:
    Vec3 m_center;
    float m_radius;
    Rgb m_flux;
};

class TriangleSource final : public PhotonSource {
  public:
    explicit TriangleSource(const EmissiveTriangle& t) : m_triangle(t) {}
    Rgb flux() const override { return emissive_flux(m_triangle); }
    Ray sample(Pcg32& rng) const override {
        const EmissiveTriangle& t = m_triangle;
        const Vec3 n = glm::normalize(glm::cross(t.v1 - t.v0, t.v2 - t.v0));
        const Vec2 b = rng.next_vec2();
        const float su = std::sqrt(b.x);
        const Vec3 x = t.v0 + (1.0f - su) * (t.v1 - t.v0) + (b.y * su) * (t.v2 - t.v0);
        const Vec3 d = lambertian_direction(n, rng.next_vec2());
        const float scale = 1.0f + max_abs_coordinate_of(x);
        return Ray{x + (4e-6f * scale) * n, d, 0.0f, kInfinity};
    }

  private:
    static float max_abs_coordinate_of(const Vec3& v) {
        return std::max(std::abs(v.x), std::max(std::abs(v.y), std::abs(v.z)));
    }
    EmissiveTriangle m_triangle;
};

std::unique_ptr<PhotonSource> make_source(const Light& light, const BoundingSphere& scene) {
    struct Make {
        const BoundingSphere& scene;
        std::unique_ptr<PhotonSource> operator()(const DirectionalLight& l) const {
            return std::make_unique<DirectionalSource>(l, scene);
        }
        std::unique_ptr<PhotonSource> operator()(const PointLight& l) const {
            return std::make_unique<PointSource>(l);
        }
        std::unique_ptr<PhotonSource> operator()(const SpotLight& l) const {
            return std::make_unique<SpotSource>(l);
        }
        std::unique_ptr<PhotonSource> operator()(const GoniometricLight& l) const {
            return std::make_unique<GoniometricSource>(l);
        }
        std::unique_ptr<PhotonSource> operator()(const LineLight& l) const {
            return std::make_unique<LineSource>(l);
        }
        std::unique_ptr<PhotonSource> operator()(const PolygonLight& l) const {
            return std::make_unique<PolygonSource>(l);
        }
        std::unique_ptr<PhotonSource> operator()(const SphereLight& l) const {
            return std::make_unique<SphereSource>(l.center, l.radius, flux_of(l, scene));
        }
    };
    return std::visit(Make{scene}, light.emitter);
}

}  // namespace

Rgb light_flux(const Light& light, const BoundingSphere& scene) {
    return std::visit([&](const auto& e) { return flux_of(e, scene); }, light.emitter);
}

Rgb emissive_flux(const EmissiveTriangle& t) {
    return t.radiance * (kPi * 0.5f * glm::length(glm::cross(t.v1 - t.v0, t.v2 - t.v0)));
}

Rgb emissive_flux(const EmissiveSphere& s) {
    return s.radiance * (4.0f * kPi * kPi * s.radius * s.radius);
}

PhotonEmitter::PhotonEmitter(const std::vector<Light>& lights, const BoundingSphere& scene,
                             const std::vector<EmissiveTriangle>& triangles,
                             const std::vector<EmissiveSphere>& spheres) {
    for (const Light& light : lights)
        m_sources.push_back(make_source(light, scene));
    for (const EmissiveTriangle& t : triangles)
        m_sources.push_back(std::make_unique<TriangleSource>(t));
    for (const EmissiveSphere& s : spheres)
        m_sources.push_back(std::make_unique<SphereSource>(s.center, s.radius, emissive_flux(s)));
    m_first.assign(m_sources.size() + 1, 0);
}

PhotonEmitter::~PhotonEmitter() = default;
PhotonEmitter::PhotonEmitter(PhotonEmitter&&) noexcept = default;

size_t PhotonEmitter::sources() const {
    return m_sources.size();
}

uint64_t PhotonEmitter::source_count(size_t s) const {
    return m_first[s + 1] - m_first[s];
}

Rgb PhotonEmitter::total_flux() const {
    Rgb total(0.0f);
    for (const auto& s : m_sources)
        total += s->flux();
    return total;
}

void PhotonEmitter::allot(uint64_t count) {
    m_count = count;
    const size_t n = m_sources.size();
    std::vector<double> weight(n, 0.0);
    double total = 0.0;
    size_t emitting = 0;
    for (size_t s = 0; s < n; ++s) {
        weight[s] = std::max(0.0f, luminance(m_sources[s]->flux()));
        total += weight[s];
        emitting += weight[s] > 0.0 ? 1 : 0;
    }
    std::vector<uint64_t> allotted(n, 0);
    if (total > 0.0 && count > 0) {
        // Every emitting source gets one photon first when there are enough (its flux must not
        // vanish from the pass), the rest in proportion to flux by largest remainders.
        const bool floor_one = count >= emitting;
        const uint64_t rest = floor_one ? count - emitting : count;
        std::vector<std::pair<double, size_t>> remainders;
        uint64_t given = 0;
        for (size_t s = 0; s < n; ++s) {
            if (!(weight[s] > 0.0))
                continue;
            const double share = static_cast<double>(rest) * weight[s] / total;
            allotted[s] = static_cast<uint64_t>(share) + (floor_one ? 1 : 0);
            given += allotted[s];
            remainders.push_back({share - std::floor(share), s});
        }
        std::sort(remainders.begin(), remainders.end(),
                  [](const auto& a, const auto& b) { return a.first > b.first; });
        for (size_t i = 0; given < count && i < remainders.size(); ++i, ++given)
            ++allotted[remainders[i].second];
    }
    m_first.assign(n + 1, 0);
    for (size_t s = 0; s < n; ++s)
        m_first[s + 1] = m_first[s] + allotted[s];
}

EmittedPhoton PhotonEmitter::emit(uint64_t index, Pcg32& rng) const {
    const size_t s = static_cast<size_t>(std::upper_bound(m_first.begin(), m_first.end(), index) -
                                         m_first.begin() - 1);
    EmittedPhoton photon;
    if (s >= m_sources.size())
        return photon;
    photon.ray = m_sources[s]->sample(rng);
    photon.power = m_sources[s]->flux() / static_cast<float>(source_count(s));
    photon.source = static_cast<uint32_t>(s);
    return photon;
}

}  // namespace kasumi
