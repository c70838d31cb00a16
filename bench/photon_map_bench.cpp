// Our photon kd-tree (gi/photon/photon_map.h) against nanoflann (Debian libnanoflann-dev) on the
// photon maps of the shipped photon scenes, at equal results.
//
// The maps: each scene's own render.photons settings and seed through build_photon_maps, as a
// render makes them (or read back from --photons FILE, written by --write-photons FILE, so that
// callgrind need not trace photons). The queries, the same for both trees, fixed seed: for the
// surface maps (global, caustic) the positions of randomly chosen photons, where a render's
// estimates sit (surfaces); for the volume map those positions moved uniformly within
// ±max_radius_m/2 per axis (march nodes lie anywhere in the fog). Each query asks for the
// scene's k nearest within its max_radius_m, as kernel_estimate does. nanoflann answers through
// a result set bounded by the radius like ours (k-nearest with a shrinking radius), so both
// return the same neighbours; the program checks it (sorted squared distances equal bit for bit,
// photon positions equal except between neighbours at exactly the k-th distance) and compares
// the box-filter estimate Σ power / (π r²) too.
//
// Timings: CPU time of this thread (the machine is shared), `--runs` alternating runs (ours
// first in even runs, nanoflann first in odd ones), median reported. `--only ours|nanoflann`
// with `--phase build|query` runs one part between CALLGRIND_START/STOP_INSTRUMENTATION for
// instruction counts (valgrind --tool=callgrind --instr-atstart=no), the load-free yardstick.
//
// usage: photon_map_bench [--runs N] [--queries N] [--leaf N] [--photons FILE]
//                         [--write-photons FILE] [--map SUBSTRING]
//                         [--only ours|nanoflann --phase build|query]
//                         [SCENE.json ...]   (default: data/scenes/caustic_glass.json and
//                                             data/scenes/caustic_fog.json)
#include "gi/photon/photon_map.h"
#include "gi/photon/photon_tracer.h"
#include "render/scene_runtime.h"
#include "scene/scene_loader.h"

#include <valgrind/callgrind.h>
#include <nanoflann.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <random>
#include <string>
#include <vector>

using namespace kasumi;

namespace {

struct MapCase {
    std::string name;  ///< scene/map
    std::vector<Photon> photons;
    int dims = 2;  ///< 2: surface map (queries at photons), 3: volume map (jittered queries)
    int k = 80;
    float max_radius = 0.25f;
};

double thread_cpu_seconds() {
    timespec t{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// nanoflann's dataset adaptor over the photons as given (nanoflann keeps an index array and
/// leaves the points in place).
struct PhotonCloud {
    const std::vector<Photon>* photons = nullptr;
    size_t kdtree_get_point_count() const { return photons->size(); }
    float kdtree_get_pt(size_t i, size_t dim) const { return (*photons)[i].position[int(dim)]; }
    template <class Box>
    bool kdtree_get_bbox(Box&) const {
        return false;
    }
};

using NanoTree =
    nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<float, PhotonCloud>,
                                        PhotonCloud, 3, uint32_t>;

/// The k nearest within a radius, as PhotonMap::nearest: a max-heap on distance², the search
/// radius the radius until k are found, then the k-th distance.
class BoundedKnn {
  public:
    using DistanceType = float;
    using IndexType = uint32_t;
    BoundedKnn(size_t k, float radius2, std::vector<PhotonNeighbour>& out)
        : m_k(k), m_radius2(radius2), m_out(out) {
        m_out.clear();
    }
    size_t size() const { return m_out.size(); }
    bool full() const { return m_out.size() == m_k; }
    bool addPoint(float d2, uint32_t index) {
        // nanoflann reads worstDist() once per leaf: later points of the leaf may be farther.
        if (!(d2 < m_radius2))
            return true;
        const auto farther = [](const PhotonNeighbour& a, const PhotonNeighbour& b) {
            return a.distance2 < b.distance2;
        };
        if (m_out.size() < m_k) {
            m_out.push_back({d2, index});
            std::push_heap(m_out.begin(), m_out.end(), farther);
        } else {
            std::pop_heap(m_out.begin(), m_out.end(), farther);
            m_out.back() = {d2, index};
            std::push_heap(m_out.begin(), m_out.end(), farther);
        }
        if (m_out.size() == m_k)
            m_radius2 = m_out.front().distance2;
        return true;
    }
    float worstDist() const { return m_radius2; }

  private:
    size_t m_k;
    float m_radius2;
    std::vector<PhotonNeighbour>& m_out;
};

std::vector<Vec3> make_queries(const MapCase& c, size_t count) {
    std::mt19937_64 rng(12345);
    std::uniform_int_distribution<size_t> pick(0, c.photons.size() - 1);
    std::uniform_real_distribution<float> jitter(-0.5f * c.max_radius, 0.5f * c.max_radius);
    std::vector<Vec3> out;
    out.reserve(count);
    for (size_t i = 0; i < count; ++i) {
        Vec3 p = c.photons[pick(rng)].position;
        if (c.dims == 3)
            p += Vec3(jitter(rng), jitter(rng), jitter(rng));
        out.push_back(p);
    }
    return out;
}

/// Σ power / (π r²) (box filter) over the neighbours in ascending distance order.
Rgb box_estimate(const std::vector<Photon>& photons, std::vector<PhotonNeighbour> found, int k,
                 float max_radius) {
    std::sort(found.begin(), found.end(), [](const PhotonNeighbour& a, const PhotonNeighbour& b) {
        return a.distance2 < b.distance2;
    });
    const float r =
        int(found.size()) >= k && !found.empty() ? std::sqrt(found.back().distance2) : max_radius;
    Rgb sum(0.0f);
    for (const PhotonNeighbour& nb : found)
        sum += photons[nb.index].power;
    return r > 0.0f ? sum / (kPi * r * r) : Rgb(0.0f);
}

struct Agreement {
    size_t queries = 0, same_sets = 0, tie_swaps = 0, distance_mismatch = 0;
    double max_rel_estimate = 0.0;
};

/// Runs both trees on every query and compares their answers.
Agreement compare(const MapCase& c, const PhotonMap& ours, const NanoTree& nano,
                  const std::vector<Vec3>& queries) {
    Agreement a;
    std::vector<PhotonNeighbour> x, y;
    for (const Vec3& q : queries) {
        ours.nearest(q, c.k, c.max_radius, x);
        BoundedKnn result(size_t(c.k), c.max_radius * c.max_radius, y);
        nano.findNeighbors(result, &q.x, nanoflann::SearchParams(32, 0.0f, false));
        ++a.queries;
        std::vector<float> dx, dy;
        for (const auto& n : x)
            dx.push_back(n.distance2);
        for (const auto& n : y)
            dy.push_back(n.distance2);
        std::sort(dx.begin(), dx.end());
        std::sort(dy.begin(), dy.end());
        if (dx != dy) {
            ++a.distance_mismatch;
            continue;
        }
        // Same photons? Compare positions in (distance², x, y, z) order.
        auto key = [](const Photon& p, float d2) {
            return std::array<float, 4>{d2, p.position.x, p.position.y, p.position.z};
        };
        std::vector<std::array<float, 4>> px, py;
        for (const auto& n : x)
            px.push_back(key(ours[n.index], n.distance2));
        for (const auto& n : y)
            py.push_back(key(c.photons[n.index], n.distance2));
        std::sort(px.begin(), px.end());
        std::sort(py.begin(), py.end());
        if (px == py)
            ++a.same_sets;
        else
            ++a.tie_swaps;  // equal distances, other photons: only at the k-th distance
        const Rgb ex = box_estimate(ours.photons(), x, c.k, c.max_radius);
        const Rgb ey = box_estimate(c.photons, y, c.k, c.max_radius);
        const double lx = ex.r + ex.g + ex.b, ly = ey.r + ey.g + ey.b;
        if (lx > 0.0)
            a.max_rel_estimate = std::max(a.max_rel_estimate, std::abs(lx - ly) / lx);
    }
    return a;
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
}

/// Sum of found counts: keeps the query loops from being optimised away.
size_t g_sink = 0;

double query_ours(const MapCase& c, const PhotonMap& map, const std::vector<Vec3>& queries) {
    std::vector<PhotonNeighbour> out;
    const double t0 = thread_cpu_seconds();
    for (const Vec3& q : queries) {
        map.nearest(q, c.k, c.max_radius, out);
        g_sink += out.size();
    }
    return thread_cpu_seconds() - t0;
}

double query_nano(const MapCase& c, const NanoTree& tree, const std::vector<Vec3>& queries) {
    std::vector<PhotonNeighbour> out;
    out.reserve(size_t(c.k));
    const double t0 = thread_cpu_seconds();
    for (const Vec3& q : queries) {
        BoundedKnn result(size_t(c.k), c.max_radius * c.max_radius, out);
        tree.findNeighbors(result, &q.x, nanoflann::SearchParams(32, 0.0f, false));
        g_sink += out.size();
    }
    return thread_cpu_seconds() - t0;
}

void write_cases(const std::string& path, const std::vector<MapCase>& cases) {
    std::ofstream f(path, std::ios::binary);
    const uint64_t n = cases.size();
    f.write(reinterpret_cast<const char*>(&n), sizeof n);
    for (const MapCase& c : cases) {
        const uint64_t len = c.name.size(), count = c.photons.size();
        f.write(reinterpret_cast<const char*>(&len), sizeof len);
        f.write(c.name.data(), std::streamsize(len));
        f.write(reinterpret_cast<const char*>(&c.dims), sizeof c.dims);
        f.write(reinterpret_cast<const char*>(&c.k), sizeof c.k);
        f.write(reinterpret_cast<const char*>(&c.max_radius), sizeof c.max_radius);
        f.write(reinterpret_cast<const char*>(&count), sizeof count);
        f.write(reinterpret_cast<const char*>(c.photons.data()),
                std::streamsize(count * sizeof(Photon)));
    }
}

std::vector<MapCase> read_cases(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    uint64_t n = 0;
    f.read(reinterpret_cast<char*>(&n), sizeof n);
    std::vector<MapCase> cases(n);
    for (MapCase& c : cases) {
        uint64_t len = 0, count = 0;
        f.read(reinterpret_cast<char*>(&len), sizeof len);
        c.name.resize(len);
        f.read(c.name.data(), std::streamsize(len));
        f.read(reinterpret_cast<char*>(&c.dims), sizeof c.dims);
        f.read(reinterpret_cast<char*>(&c.k), sizeof c.k);
        f.read(reinterpret_cast<char*>(&c.max_radius), sizeof c.max_radius);
        f.read(reinterpret_cast<char*>(&count), sizeof count);
        c.photons.resize(count);
        f.read(reinterpret_cast<char*>(c.photons.data()), std::streamsize(count * sizeof(Photon)));
    }
    if (!f) {
        std::fprintf(stderr, "photon_map_bench: cannot read %s\n", path.c_str());
        std::exit(1);
    }
    return cases;
}

std::vector<MapCase> trace_cases(const std::vector<std::string>& scenes) {
    std::vector<MapCase> cases;
    for (const std::string& path : scenes) {
        const SceneRuntime runtime(load_scene(path));
        const RenderSettings& render = runtime.desc().render;
        const PhotonMaps maps = build_photon_maps(runtime, render.photons, render.seed, 0);
        const std::string stem = path.substr(path.find_last_of('/') + 1);
        const std::pair<const char*, const PhotonMap*> named[] = {
            {"global", &maps.global}, {"caustic", &maps.caustic}, {"volume", &maps.volume}};
        for (const auto& [name, map] : named) {
            if (map->empty())
                continue;
            MapCase c;
            c.name = stem + "/" + name;
            c.photons = map->photons();
            c.dims = std::strcmp(name, "volume") == 0 ? 3 : 2;
            c.k = render.photons.k;
            c.max_radius = render.photons.max_radius_m;
            cases.push_back(std::move(c));
        }
    }
    return cases;
}

}  // namespace

int main(int argc, char** argv) {
    int runs = 9, leaf = 10;
    size_t queries = 100000;
    std::string photons_in, photons_out, only, phase, map_filter;
    std::vector<std::string> scenes;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&] { return i + 1 < argc ? std::string(argv[++i]) : std::string(); };
        if (a == "--runs")
            runs = std::stoi(value());
        else if (a == "--queries")
            queries = std::stoul(value());
        else if (a == "--leaf")
            leaf = std::stoi(value());
        else if (a == "--photons")
            photons_in = value();
        else if (a == "--write-photons")
            photons_out = value();
        else if (a == "--only")
            only = value();
        else if (a == "--phase")
            phase = value();
        else if (a == "--map")
            map_filter = value();
        else
            scenes.push_back(a);
    }
    if (scenes.empty())
        scenes = {"data/scenes/caustic_glass.json", "data/scenes/caustic_fog.json"};
    std::vector<MapCase> cases = photons_in.empty() ? trace_cases(scenes) : read_cases(photons_in);
    if (!photons_out.empty())
        write_cases(photons_out, cases);
    cases.erase(std::remove_if(
                    cases.begin(), cases.end(),
                    [&](const MapCase& c) { return c.name.find(map_filter) == std::string::npos; }),
                cases.end());

    if (!only.empty()) {  // one part under callgrind
        for (const MapCase& c : cases) {
            const std::vector<Vec3> qs = make_queries(c, queries);
            const PhotonCloud cloud{&c.photons};
            const nanoflann::KDTreeSingleIndexAdaptorParams params(
                size_t(leaf), nanoflann::KDTreeSingleIndexAdaptorFlags::SkipInitialBuildIndex);
            NanoTree nano(3, cloud, params);
            if (phase == "build")
                CALLGRIND_START_INSTRUMENTATION;
            const PhotonMap ours = only == "ours" ? PhotonMap(c.photons) : PhotonMap();
            if (only == "nanoflann")
                nano.buildIndex();
            if (phase == "build")
                CALLGRIND_STOP_INSTRUMENTATION;
            if (phase == "query") {
                CALLGRIND_START_INSTRUMENTATION;
                if (only == "ours")
                    query_ours(c, ours, qs);
                else
                    query_nano(c, nano, qs);
                CALLGRIND_STOP_INSTRUMENTATION;
            }
        }
        std::printf("%zu\n", g_sink);
        return 0;
    }

    std::printf("%-22s %9s %4s %6s | %-29s | %-29s | %s\n", "map", "photons", "k", "r_m",
                "build ms: ours  nanoflann", "query us: ours  nanoflann", "agreement");
    for (const MapCase& c : cases) {
        const std::vector<Vec3> qs = make_queries(c, queries);
        const PhotonCloud cloud{&c.photons};
        const nanoflann::KDTreeSingleIndexAdaptorParams params{static_cast<size_t>(leaf)};
        std::vector<double> build_ours, build_nano, query_o, query_n;
        for (int run = 0; run < runs; ++run) {
            for (int side = 0; side < 2; ++side) {
                if ((side == 0) == (run % 2 == 0)) {
                    const double t0 = thread_cpu_seconds();
                    const PhotonMap map(c.photons);
                    build_ours.push_back(thread_cpu_seconds() - t0);
                    query_o.push_back(query_ours(c, map, qs));
                } else {
                    const double t0 = thread_cpu_seconds();
                    const NanoTree tree(3, cloud, params);
                    build_nano.push_back(thread_cpu_seconds() - t0);
                    query_n.push_back(query_nano(c, tree, qs));
                }
            }
        }
        const PhotonMap map(c.photons);
        const NanoTree tree(3, cloud, params);
        const Agreement a = compare(c, map, tree, qs);
        const double per_query = 1e6 / double(qs.size());
        std::printf(
            "%-22s %9zu %4d %6.3f | %12.2f %12.2f    | %12.3f %12.3f    | %zu/%zu same "
            "sets, %zu tie swaps, %zu distance mismatches, estimate rel. diff %.1e\n",
            c.name.c_str(), c.photons.size(), c.k, double(c.max_radius), 1e3 * median(build_ours),
            1e3 * median(build_nano), per_query * median(query_o), per_query * median(query_n),
            a.same_sets, a.queries, a.tie_swaps, a.distance_mismatch, a.max_rel_estimate);
    }
    std::fprintf(stderr, "(%zu)\n", g_sink);
    return 0;
}
