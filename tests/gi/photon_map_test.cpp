// The photon map's kd-tree against brute force, and the density-estimate filters' normalisation.
#include "gi/photon/photon_map.h"
#include "gi/photon/photon_estimate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <random>

namespace kasumi {
namespace {

std::vector<Photon> random_photons(size_t n, uint32_t seed) {
    std::mt19937 gen(seed);
    std::uniform_real_distribution<float> u(-1.0f, 1.0f);
    std::normal_distribution<float> g(0.0f, 0.05f);
    std::vector<Photon> photons(n);
    for (size_t i = 0; i < n; ++i) {
        // Half uniform in a box, half in tight clusters (and a few exact duplicates): the
        // medians and ties a balanced tree must handle.
        if (i % 2 == 0)
            photons[i].position = Vec3(u(gen), u(gen), 0.2f * u(gen));
        else if (i % 97 == 1)
            photons[i].position = photons[i - 1].position;
        else
            photons[i].position =
                Vec3(0.3f, -0.2f, 0.0f) * static_cast<float>(i % 3) + Vec3(g(gen), g(gen), g(gen));
        photons[i].power = Rgb(static_cast<float>(i));
    }
    return photons;
}

TEST(PhotonMap, KNearestMatchesBruteForce) {
    const std::vector<Photon> photons = random_photons(20000, 7);
    const PhotonMap map(photons);
    ASSERT_EQ(map.size(), photons.size());
    std::mt19937 gen(11);
    std::uniform_real_distribution<float> u(-1.2f, 1.2f);
    std::vector<PhotonNeighbour> found;
    for (int q = 0; q < 300; ++q) {
        const Vec3 p(u(gen), u(gen), 0.3f * u(gen));
        const int k = std::array<int, 4>{1, 7, 50, 400}[q % 4];
        const float radius = std::array<float, 3>{0.02f, 0.15f, 10.0f}[q % 3];
        std::vector<float> brute;
        for (const Photon& ph : photons) {
            const float d2 = glm::dot(ph.position - p, ph.position - p);
            if (d2 < radius * radius)
                brute.push_back(d2);
        }
        std::sort(brute.begin(), brute.end());
        if (brute.size() > static_cast<size_t>(k))
            brute.resize(static_cast<size_t>(k));
        map.nearest(p, k, radius, found);
        ASSERT_EQ(found.size(), brute.size()) << "query " << q;
        std::vector<float> tree;
        for (const PhotonNeighbour& nb : found) {
            const Photon& ph = map[nb.index];
            // The reported distance is the stored photon's.
            EXPECT_FLOAT_EQ(nb.distance2, glm::dot(ph.position - p, ph.position - p));
            tree.push_back(nb.distance2);
        }
        // The heap's front is the farthest found.
        if (!found.empty()) {
            EXPECT_EQ(found.front().distance2, *std::max_element(tree.begin(), tree.end()));
        }
        std::sort(tree.begin(), tree.end());
        for (size_t i = 0; i < tree.size(); ++i)
            ASSERT_EQ(tree[i], brute[i]) << "query " << q << " neighbour " << i;
    }
}

TEST(PhotonMap, KeepsEveryPhotonOnce) {
    const std::vector<Photon> photons = random_photons(1001, 3);
    const PhotonMap map(photons);
    std::vector<float> a, b;
    for (size_t i = 0; i < photons.size(); ++i) {
        a.push_back(photons[i].power.r);
        b.push_back(map[i].power.r);
    }
    std::sort(b.begin(), b.end());
    EXPECT_EQ(a, b);  // powers were 0..n-1 in order
}

TEST(PhotonMap, EmptyAndDegenerateQueries) {
    std::vector<PhotonNeighbour> found{{1.0f, 2}};
    PhotonMap empty;
    empty.nearest(Vec3(0.0f), 5, 1.0f, found);
    EXPECT_TRUE(found.empty());
    const PhotonMap one(std::vector<Photon>{Photon{Vec3(1.0f, 0.0f, 0.0f)}});
    one.nearest(Vec3(0.0f), 0, 10.0f, found);
    EXPECT_TRUE(found.empty());
    one.nearest(Vec3(0.0f), 3, 1.0f, found);  // at distance exactly 1: outside the open ball
    EXPECT_TRUE(found.empty());
    one.nearest(Vec3(0.0f), 3, 1.001f, found);
    EXPECT_EQ(found.size(), 1u);
}

TEST(PhotonFilter, WeightsIntegrateToOneOverTheDiscAndTheBall) {
    // Midpoint rule in the radius, 20000 shells: error O(h²) ~ 1e-8 for these polynomials.
    const float r = 0.37f;
    for (PhotonFilter f : {PhotonFilter::Box, PhotonFilter::Cone, PhotonFilter::Epanechnikov}) {
        double disc = 0.0, ball = 0.0;
        const int n = 20000;
        for (int i = 0; i < n; ++i) {
            const double d = (i + 0.5) / n * r, dr = static_cast<double>(r) / n;
            disc += filter_weight(f, 2, static_cast<float>(d), r) * 2.0 * kPiD * d * dr;
            ball += filter_weight(f, 3, static_cast<float>(d), r) * 4.0 * kPiD * d * d * dr;
        }
        EXPECT_NEAR(disc, 1.0, 1e-4) << photon_filter_name(f);
        EXPECT_NEAR(ball, 1.0, 1e-4) << photon_filter_name(f);
        EXPECT_EQ(filter_weight(f, 2, 1.01f * r, r), 0.0f);
    }
}

}  // namespace
}  // namespace kasumi
