/// Google Benchmark figures for the phase functions: eval and sample of every model through the
/// PhaseFunction variant (the renderer's path), and building a Lorenz-Mie phase table at
/// x = 100, 1e3 and 1e4. Not a test: nothing here gates CI on a time. Figures are in README.md.
#include "phase/phase_function.h"

#include "core/rng.h"

#include <benchmark/benchmark.h>

#include <string>
#include <vector>

namespace kasumi {
namespace {

/// Inputs are drawn once and cycled so the loop measures the model, not the random numbers.
constexpr size_t kInputs = 4096;

std::vector<float> random_cosines() {
    Pcg32 rng(1u, 2u);
    std::vector<float> mu(kInputs);
    for (float& m : mu)
        m = 2.0f * rng.next_float() - 1.0f;
    return mu;
}

std::vector<Vec2> random_uniforms() {
    Pcg32 rng(3u, 4u);
    std::vector<Vec2> u(kInputs);
    for (Vec2& v : u)
        v = rng.next_vec2();
    return u;
}

/// A 1801-node table (every 0.1°) of HG with g = 0.8, as a measured table might be.
Tabulated hg_table() {
    std::vector<double> theta_deg, value;
    for (int i = 0; i <= 1800; ++i) {
        theta_deg.push_back(0.1 * i);
        value.push_back(eval_precise(HenyeyGreenstein{0.8f}, std::cos(0.1 * i * kPiD / 180.0)));
    }
    return Tabulated{std::make_shared<const PhaseTable>(
                         PhaseTable::from_theta_deg(theta_deg, value, "bench table")),
                     "bench table"};
}

struct NamedModel {
    std::string name;
    PhaseFunction phase;
};

std::vector<NamedModel> models() {
    return {
        {"isotropic", Isotropic{}},
        {"hg/g=0.8", HenyeyGreenstein{0.8f}},
        {"rayleigh/rho=0.0279", Rayleigh{0.0279f}},
        {"double-hg/0.8,-0.3,0.7", DoubleHenyeyGreenstein{0.8f, -0.3f, 0.7f}},
        {"cornette-shanks/g=0.76", CornetteShanks{0.76f}},
        {"draine/g=0.5,alpha=0.8", Draine{0.5f, 0.8f}},
        {"jendersie-deon/d=10um", make_jendersie_deon(10.0f)},
        {"tabulated/1801-nodes", hg_table()},
        {"mie/x=100", make_mie(100.0, Complex(1.33, 0.0))},
        {"mie/x=1000", make_mie(1000.0, Complex(1.33, 0.0))},
        {"mie/x=10000", make_mie(10000.0, Complex(1.33, 0.0))},
    };
}

void bench_eval(benchmark::State& state, const PhaseFunction& phase) {
    const std::vector<float> mu = random_cosines();
    size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(eval(phase, mu[i]));
        i = (i + 1) & (kInputs - 1);
    }
    state.SetItemsProcessed(state.iterations());
}

void bench_sample(benchmark::State& state, const PhaseFunction& phase) {
    const std::vector<Vec2> u = random_uniforms();
    const Vec3 wo = glm::normalize(Vec3(0.3f, -0.5f, 0.81f));
    size_t i = 0;
    for (auto _ : state) {
        benchmark::DoNotOptimize(sample(phase, wo, u[i]));
        i = (i + 1) & (kInputs - 1);
    }
    state.SetItemsProcessed(state.iterations());
}

void bench_mie_table(benchmark::State& state) {
    const auto x = static_cast<double>(state.range(0));
    for (auto _ : state)
        benchmark::DoNotOptimize(make_mie(x, Complex(1.33, 0.0)));
    state.counters["nodes"] =
        static_cast<double>(make_mie(x, Complex(1.33, 0.0)).table->mu().size());
}

}  // namespace
}  // namespace kasumi

int main(int argc, char** argv) {
    using namespace kasumi;
    // Registered models must outlive the run: the benchmarks hold references.
    static const std::vector<NamedModel> all = models();
    for (const NamedModel& m : all) {
        benchmark::RegisterBenchmark(("eval/" + m.name).c_str(), bench_eval, m.phase);
        benchmark::RegisterBenchmark(("sample/" + m.name).c_str(), bench_sample, m.phase);
    }
    benchmark::RegisterBenchmark("mie_table/x", bench_mie_table)
        ->Arg(100)
        ->Arg(1000)
        ->Arg(10000)
        ->Unit(benchmark::kMillisecond);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv))
        return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
