// Raw trilinear density lookups on one grid, three ways (and our stochastic one-voxel lookup):
// OpenVDB (tools::BoxSampler through a ValueAccessor), NanoVDB (SampleFromVoxels order 1 through a
// ReadAccessor) and our DensityGrid (bricks with aprons, volume/grid/density_grid.h), plus the
// all-in MediumSet::coefficients that the trackers call (world-to-index transform and the
// coefficient scaling on top). The only file outside volume/vdb_*.cpp that includes OpenVDB
// headers.
//
// The grid: $KASUMI_BENCH_VDB (default data/clouds/cumulus_256.vdb, relative to the working
// directory; make it with `kasumi make-cloud --res 256 --seed 7 -o data/clouds/cumulus_256.vdb`).
// Points, all inside the active voxels' bounding box, fixed seed, the same for every method:
//   - "rays": 4096 random rays across the box sampled every 0.5 voxel (coherent, like a march
//     or a tracker walk);
//   - "random": uniform points in the box (incoherent: the worst case for accessor caches).
// Items/s is lookups per second on one core; ns per lookup = 1e9 / items_per_second.
#include "volume/grid/vdb_io.h"
#include "volume/medium_set.h"

#include <benchmark/benchmark.h>
#include <nanovdb/util/OpenToNanoVDB.h>
#include <nanovdb/util/SampleFromVoxels.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <random>
#include <string>
#include <vector>

namespace {

struct Fixture {
    openvdb::FloatGrid::Ptr vdb;
    nanovdb::GridHandle<nanovdb::HostBuffer> nano;
    kasumi::LoadedGrid ours;
    kasumi::MediumSet media;
    kasumi::Mat4 world_to_index{1.0f};
    std::vector<openvdb::Vec3d> ray_points, random_points;  // index space
    std::vector<kasumi::Vec3> ray_points_f, random_points_f;
    std::vector<kasumi::Vec3> ray_points_world, random_points_world;
};

std::string grid_path() {
    const char* env = std::getenv("KASUMI_BENCH_VDB");
    return env != nullptr ? env : "data/clouds/cumulus_256.vdb";
}

Fixture& fixture() {
    static Fixture* f = [] {
        auto* fx = new Fixture;
        openvdb::initialize();
        const std::string path = grid_path();
        openvdb::io::File file(path);
        file.open();
        fx->vdb = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("density"));
        file.close();
        fx->nano = nanovdb::openToNanoVDB(*fx->vdb);
        fx->ours = kasumi::load_density_grid(path, "density", path);
        kasumi::VdbMedium m;
        m.grid = fx->ours.grid;
        m.world_to_index = kasumi::Mat4(glm::inverse(fx->ours.index_to_world));
        m.sigma_a_per_density = kasumi::Rgb(0.01f);
        m.sigma_s_per_density = kasumi::Rgb(1.0f);
        fx->world_to_index = m.world_to_index;
        std::vector<kasumi::Medium> media;
        media.push_back({"cloud", m});
        fx->media = kasumi::MediumSet(std::move(media));

        const openvdb::CoordBBox box = fx->vdb->evalActiveVoxelBoundingBox();
        const openvdb::Vec3d lo = box.min().asVec3d(), hi = box.max().asVec3d();
        std::mt19937_64 rng(7);
        std::uniform_real_distribution<double> u(0.0, 1.0);
        auto in_box = [&] {
            return openvdb::Vec3d(lo.x() + u(rng) * (hi.x() - lo.x()),
                                  lo.y() + u(rng) * (hi.y() - lo.y()),
                                  lo.z() + u(rng) * (hi.z() - lo.z()));
        };
        for (int r = 0; r < 4096; ++r) {
            const openvdb::Vec3d a = in_box(), b = in_box();
            const double len = (b - a).length();
            for (double t = 0.0; t < len; t += 0.5)
                fx->ray_points.push_back(a + (b - a) * (t / len));
        }
        for (size_t i = 0; i < fx->ray_points.size(); ++i)
            fx->random_points.push_back(in_box());
        const glm::dmat4& to_world = fx->ours.index_to_world;
        for (const auto* src : {&fx->ray_points, &fx->random_points}) {
            auto& dst_f = src == &fx->ray_points ? fx->ray_points_f : fx->random_points_f;
            auto& dst_w = src == &fx->ray_points ? fx->ray_points_world : fx->random_points_world;
            for (const openvdb::Vec3d& p : *src) {
                dst_f.emplace_back(p.x(), p.y(), p.z());
                dst_w.emplace_back(to_world * glm::dvec4(p.x(), p.y(), p.z(), 1.0));
            }
        }
        std::fprintf(stderr, "grid %s: %zu active voxels, %zu points per pass\n", path.c_str(),
                     static_cast<size_t>(fx->vdb->activeVoxelCount()), fx->ray_points.size());
        return fx;
    }();
    return *f;
}

const std::vector<openvdb::Vec3d>& points_d(int which) {
    return which == 0 ? fixture().ray_points : fixture().random_points;
}
const std::vector<kasumi::Vec3>& points_f(int which) {
    return which == 0 ? fixture().ray_points_f : fixture().random_points_f;
}

void label(benchmark::State& state) {
    state.SetLabel(state.range(0) == 0 ? "rays" : "random");
}

void BM_OpenVdbBoxSampler(benchmark::State& state) {
    const auto& pts = points_d(static_cast<int>(state.range(0)));
    openvdb::FloatGrid::ConstAccessor acc = fixture().vdb->getConstAccessor();
    for (auto _ : state) {
        float sum = 0.0f;
        for (const openvdb::Vec3d& p : pts) {
            float v;
            openvdb::tools::BoxSampler::sample(acc, p, v);
            sum += v;
        }
        benchmark::DoNotOptimize(sum);
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * pts.size()));
    label(state);
}

void BM_NanoVdbTrilinear(benchmark::State& state) {
    const auto& pts = points_d(static_cast<int>(state.range(0)));
    const nanovdb::NanoGrid<float>* grid = fixture().nano.grid<float>();
    auto acc = grid->getAccessor();
    auto sampler = nanovdb::createSampler<1>(acc);
    for (auto _ : state) {
        float sum = 0.0f;
        for (const openvdb::Vec3d& p : pts)
            sum += sampler(nanovdb::Vec3f(static_cast<float>(p.x()), static_cast<float>(p.y()),
                                          static_cast<float>(p.z())));
        benchmark::DoNotOptimize(sum);
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * pts.size()));
    label(state);
}

void BM_KasumiDensityGrid(benchmark::State& state) {
    const auto& pts = points_f(static_cast<int>(state.range(0)));
    const kasumi::DensityGrid& grid = *fixture().ours.grid;
    for (auto _ : state) {
        float sum = 0.0f;
        for (const kasumi::Vec3& p : pts)
            sum += grid.density(p);
        benchmark::DoNotOptimize(sum);
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * pts.size()));
    label(state);
}

// Stochastic (one-voxel) trilinear lookups (DensityGrid::density_stochastic, render.volume.
// density_filter "stochastic"): each with its random bits made as RayMediaQuery makes them (two
// SplitMix64 finalisers of a seed, the point's bits and the lookup's ordinal), so the time is
// what a tracker's lookup costs with the option on.
void BM_KasumiDensityStochastic(benchmark::State& state) {
    const auto& pts = points_f(static_cast<int>(state.range(0)));
    const kasumi::DensityGrid& grid = *fixture().ours.grid;
    const uint64_t seed = kasumi::mix64(7);
    for (auto _ : state) {
        float sum = 0.0f;
        uint32_t ordinal = 0;
        for (const kasumi::Vec3& p : pts) {
            uint32_t tb = 0;
            std::memcpy(&tb, &p.x, sizeof(float));
            const uint64_t bits =
                kasumi::mix64(seed ^ kasumi::mix64((static_cast<uint64_t>(tb) << 32) | ordinal++));
            sum += grid.density_stochastic(p, bits);
        }
        benchmark::DoNotOptimize(sum);
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * pts.size()));
    label(state);
}

void BM_KasumiCoefficients(benchmark::State& state) {
    const auto& pts =
        state.range(0) == 0 ? fixture().ray_points_world : fixture().random_points_world;
    const kasumi::MediumSet& media = fixture().media;
    for (auto _ : state) {
        float sum = 0.0f;
        for (const kasumi::Vec3& p : pts)
            sum += media.coefficients(p, 1u).sigma_t.r;
        benchmark::DoNotOptimize(sum);
    }
    state.SetItemsProcessed(static_cast<int64_t>(state.iterations() * pts.size()));
    label(state);
}

BENCHMARK(BM_OpenVdbBoxSampler)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_NanoVdbTrilinear)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KasumiDensityGrid)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KasumiDensityStochastic)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_KasumiCoefficients)->Arg(0)->Arg(1)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
