// Exact answers for the Fresnel equations and the reflection and refraction directions.
#include "surface/fresnel.h"
#include "surface/material.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace kasumi {
namespace {

/// Uniform random unit vector (fixed seed: deterministic).
Vec3 random_direction(std::mt19937& rng) {
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    for (;;) {
        const Vec3 v(u(rng), u(rng), u(rng));
        const float l2 = glm::dot(v, v);
        if (l2 > 1e-4f && l2 <= 1.0f)
            return v / std::sqrt(l2);
    }
}

TEST(Fresnel, NormalIncidenceIsSquaredRatio) {
    for (const float eta : {1.0f, 1.33f, 1.5f, 2.42f, 0.5f}) {
        const float expected = ((eta - 1.0f) / (eta + 1.0f)) * ((eta - 1.0f) / (eta + 1.0f));
        EXPECT_NEAR(fresnel_dielectric(1.0f, eta), expected, 1e-7f) << eta;
        // From inside (cos < 0) the interface is seen with 1 / eta: the same value.
        EXPECT_NEAR(fresnel_dielectric(-1.0f, eta), expected, 1e-7f) << eta;
    }
    EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f), 0.04f, 1e-7f);
}

TEST(Fresnel, BrewsterAngleHasNoParallelReflection) {
    for (const float eta : {1.33f, 1.5f, 1.0f / 1.5f}) {
        const double theta_b = std::atan(static_cast<double>(eta));  // tan θB = η
        const auto r = fresnel_amplitudes(static_cast<float>(std::cos(theta_b)), eta);
        EXPECT_NEAR(r.rp, 0.0f, 1e-6f) << eta;
        // Then F = rs² / 2, and rs = -cos(2θB) at Brewster's angle... checked via the definition:
        EXPECT_NEAR(fresnel_dielectric(static_cast<float>(std::cos(theta_b)), eta),
                    0.5f * r.rs * r.rs, 1e-7f);
        // rs at Brewster: (cos θi - η cos θt) / (cos θi + η cos θt) with θt = π/2 - θB.
        const double rs = (std::cos(theta_b) - eta * std::sin(theta_b)) /
                          (std::cos(theta_b) + eta * std::sin(theta_b));
        EXPECT_NEAR(r.rs, rs, 1e-6);
    }
}

TEST(Fresnel, TotalInternalReflectionBeyondCriticalAngle) {
    const float ior = 1.5f;
    const double critical = std::asin(1.0 / ior);  // 41.8°, seen from inside the glass
    for (const double extra : {1e-4, 0.01, 0.3, 0.7}) {
        const double theta = critical + extra;
        if (theta >= kPiD / 2)
            continue;
        const float cos_i = static_cast<float>(std::cos(theta));
        EXPECT_EQ(fresnel_dielectric(-cos_i, ior), 1.0f) << theta;
        EXPECT_EQ(fresnel_dielectric(cos_i, 1.0f / ior), 1.0f) << theta;
        const Vec3 wi(static_cast<float>(std::sin(theta)), 0.0f, cos_i);
        EXPECT_FALSE(refract(wi, Vec3(0, 0, 1), 1.0f / ior).has_value()) << theta;
    }
    // Just inside the critical angle F is below 1 and rises to it continuously.
    const float below = fresnel_dielectric(-static_cast<float>(std::cos(critical - 1e-3)), ior);
    EXPECT_LT(below, 1.0f);
    EXPECT_GT(below, 0.7f);
    // Grazing incidence from outside reflects everything.
    EXPECT_NEAR(fresnel_dielectric(0.0f, ior), 1.0f, 1e-6f);
}

TEST(Fresnel, ReflectionLawOnRandomDirections) {
    std::mt19937 rng(7);
    for (int i = 0; i < 1000; ++i) {
        const Vec3 n = random_direction(rng);
        Vec3 wi = random_direction(rng);
        if (glm::dot(n, wi) < 0.0f)
            wi = -wi;
        const Vec3 wr = reflect(wi, n);
        EXPECT_NEAR(glm::length(wr), 1.0f, 1e-5f);
        EXPECT_NEAR(glm::dot(wr, n), glm::dot(wi, n), 1e-5f);       // equal angles
        EXPECT_NEAR(glm::dot(glm::cross(wi, n), wr), 0.0f, 1e-5f);  // coplanar
        EXPECT_NEAR(glm::length(wr + wi - 2.0f * glm::dot(wi, n) * n), 0.0f, 1e-5f);
    }
}

TEST(Fresnel, SnellsLawOnRandomDirections) {
    std::mt19937 rng(11);
    int refracted = 0;
    for (int i = 0; i < 1000; ++i) {
        const Vec3 n = random_direction(rng);
        Vec3 wi = random_direction(rng);
        if (glm::dot(n, wi) < 0.0f)
            wi = -wi;
        const float eta = (i % 2) ? 1.5f : 1.0f / 1.5f;
        const std::optional<Vec3> wt = refract(wi, n, eta);
        const float cos_i = glm::dot(n, wi);
        const float sin_i = std::sqrt(std::max(0.0f, 1.0f - cos_i * cos_i));
        if (!wt) {
            EXPECT_GT(sin_i / eta, 1.0f - 1e-5f);  // only under total internal reflection
            continue;
        }
        ++refracted;
        EXPECT_NEAR(glm::length(*wt), 1.0f, 1e-5f);
        EXPECT_LT(glm::dot(*wt, n), 0.0f);  // crosses to the other side
        const float cos_t = -glm::dot(*wt, n);
        const float sin_t = std::sqrt(std::max(0.0f, 1.0f - cos_t * cos_t));
        EXPECT_NEAR(sin_i, eta * sin_t, 2e-4f);  // Snell: η_i sin θi = η_t sin θt
        EXPECT_NEAR(glm::dot(glm::cross(wi, n), *wt), 0.0f, 1e-5f);  // coplanar
    }
    // Half the cases leave glass (η = 1/1.5): total internal reflection for cos θi < 0.745.
    EXPECT_GT(refracted, 550);
}

TEST(Fresnel, EnergyIsConservedAtTheInterface) {
    // T from the transmission amplitude coefficients (Born & Wolf §1.5.2, eq. 20):
    // ts = 2 cos θi / (cos θi + η cos θt), tp = 2 cos θi / (η cos θi + cos θt), and the power
    // transmittance T = η cos θt / cos θi (ts² + tp²) / 2. R + T = 1 is then a check of F.
    for (const double eta : {1.5, 1.33, 1.0 / 1.5, 2.4}) {
        for (int k = 0; k <= 20; ++k) {
            const double cos_i = std::max(1e-3, k / 20.0);
            const double sin_t2 = (1.0 - cos_i * cos_i) / (eta * eta);
            if (sin_t2 >= 1.0)
                continue;
            const double cos_t = std::sqrt(1.0 - sin_t2);
            const double ts = 2.0 * cos_i / (cos_i + eta * cos_t);
            const double tp = 2.0 * cos_i / (eta * cos_i + cos_t);
            const double t = eta * cos_t / cos_i * 0.5 * (ts * ts + tp * tp);
            const double r = fresnel_dielectric(static_cast<float>(cos_i), static_cast<float>(eta));
            EXPECT_NEAR(r + t, 1.0, 1e-6) << eta << " " << cos_i;
        }
    }
}

TEST(Fresnel, SchlickMatchesAtNormalAndGrazingIncidence) {
    EXPECT_FLOAT_EQ(fresnel_schlick(1.0f, 0.04f), 0.04f);
    EXPECT_FLOAT_EQ(fresnel_schlick(0.0f, 0.04f), 1.0f);
    // For glass Schlick stays within 0.036 absolute of the exact curve (its largest error,
    // computed in double, is 0.0357 near cos θ = 0.13).
    for (int k = 0; k <= 50; ++k) {
        const float c = k / 50.0f;
        EXPECT_NEAR(fresnel_schlick(c, 0.04f), fresnel_dielectric(c, 1.5f), 0.036f) << c;
    }
}

TEST(Fresnel, PhongSpecularReflectanceModes) {
    PhongMaterial m;
    m.ks = Rgb(0.04f, 0.2f, 1.0f);
    EXPECT_EQ(specular_reflectance(m, 0.3f), m.ks);
    m.ks_fresnel = SpecularFresnel::Exact;
    const Rgb normal = specular_reflectance(m, 1.0f);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(normal[c], m.ks[c], 1e-6f);
    EXPECT_NEAR(specular_reflectance(m, 0.0f).g, 1.0f, 1e-5f);
    EXPECT_NEAR(specular_reflectance(m, 0.5f).r, fresnel_dielectric(0.5f, 1.5f), 1e-6f);
    m.ks_fresnel = SpecularFresnel::Schlick;
    EXPECT_NEAR(specular_reflectance(m, 1.0f).g, 0.2f, 1e-7f);
    EXPECT_NEAR(specular_reflectance(m, 0.0f).r, 1.0f, 1e-7f);
}

}  // namespace
}  // namespace kasumi
