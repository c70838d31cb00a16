// Hostile and damaged .vdb files against the direct reader (volume/grid/vdb_direct.h): small grids
// written by OpenVDB with each compression (blosc, none; with and without the active mask;
// OpenVDB writes the "zip" fixtures of a fog volume without zip), one with active tiles, then
// deterministic mutations of their bytes: the file cut at many lengths, single bytes set to 0x00,
// 0xFF or flipped in their top bit, and int32/int64 windows overwritten with huge, negative and
// extreme counts at every offset. Each mutant must be read or declined (std::nullopt), or refused
// with kasumi::Error (Input) for what no reader could load; nothing else may escape, a grid read
// from a mutant must be finite and its transform invertible. The allocation bound is enforced by
// the address-space limit below in Release (a request beyond it throws std::bad_alloc, which fails
// the test); under ASan (the asan preset runs this file: label unit) by ASan, which aborts on a
// request over its maximum (ASAN_OPTIONS=max_allocation_size_mb=1024 tightens it). Deterministic
// (no random draws in the fixed set), so no false failures. $KASUMI_VDB_FUZZ_SEEDS=N adds N random
// multi-byte mutants per fixture (for long local runs under ASan; not used by ctest).
#include "volume/grid/vdb_direct.h"

#include "core/error.h"
#include "core/rng.h"
#include "vdb_test_grids.h"
#include "volume/grid/vdb_io.h"

#include <gtest/gtest.h>

#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>

#if !defined(__SANITIZE_ADDRESS__)
namespace {
// 8 GiB of address space: TBB's threads and the fixtures need well under 1 GiB.
[[maybe_unused]] const bool g_limited = [] {
    rlimit r{};
    r.rlim_cur = r.rlim_max = rlim_t(8) << 30;
    return ::setrlimit(RLIMIT_AS, &r) == 0;
}();
}  // namespace
#endif

namespace kasumi {
namespace {

using Bytes = std::vector<uint8_t>;

Bytes read_bytes(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return Bytes(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

void write_bytes(const std::string& path, const Bytes& bytes) {
    std::ofstream out(path, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(bytes.data()),
              static_cast<std::streamsize>(bytes.size()));
}

/// A small cloud: sparse and dense leaves, inactive junk values. Negative coordinates make four
/// root children, each with its internal nodes' 36864 values (147 KB stored uncompressed).
DenseVoxels small_cloud(int compression, IVec3 origin) {
    DenseVoxels v;
    v.origin = origin;
    v.dims = IVec3(20, 13, 11);
    v.compression = compression;
    const size_t n = static_cast<size_t>(v.dims.x) * v.dims.y * v.dims.z;
    v.values.assign(n, 0.0f);
    v.inactive.assign(n, 0);
    Pcg32 rng(11, 2);
    for (size_t i = 0; i < n; ++i) {
        const float u = rng.next_float();
        if (u < 0.5f)
            v.values[i] = 0.1f + u;
        else if (u < 0.6f) {
            v.values[i] = u < 0.55f ? -1.0f : 3.0f;
            v.inactive[i] = 1;
        }
    }
    return v;
}

struct Fixture {
    std::string name;
    Bytes bytes;
};

const std::vector<Fixture>& fixtures() {
    static const std::vector<Fixture> all = [] {
        std::vector<Fixture> f;
        const struct {
            const char* name;
            int compression;
            IVec3 origin;
        } kinds[] = {{"blosc_mask", -1, IVec3(-9, -5, 3)},
                     {"zip_mask", 3, IVec3(-9, -5, 3)},
                     {"zip", 1, IVec3(1, 2, 3)},
                     {"none", 0, IVec3(1, 2, 3)},
                     {"mask", 2, IVec3(1, 2, 3)}};
        for (const auto& k : kinds) {
            const std::string path = test::temp_grid_path(std::string("fuzz_src_") + k.name);
            write_fog_volume(path, "density", small_cloud(k.compression, k.origin), 0.5,
                             Vec3(1, 2, 3));
            f.push_back({k.name, read_bytes(path)});
        }
        // Active tiles of a 4-level internal node: a constant 128³ box plus a leaf.
        DenseVoxels t;
        t.dims = IVec3(129, 128, 128);
        t.values.assign(static_cast<size_t>(t.dims.x) * t.dims.y * t.dims.z, 0.0f);
        for (int z = 0; z < 128; ++z)
            for (int y = 0; y < 128; ++y)
                for (int x = 0; x < 129; ++x)
                    t.values[static_cast<size_t>(x) + 129 * (y + size_t(128) * z)] =
                        x < 128 ? 0.25f : (y == 3 && z == 5 ? 0.5f : 0.0f);
        const std::string path = test::temp_grid_path("fuzz_src_tiles");
        write_fog_volume(path, "density", t, 1.0, Vec3(0.0f), /*constant_tiles=*/true);
        f.push_back({"tiles", read_bytes(path)});
        return f;
    }();
    return all;
}

/// Makes the file at `path` hold `bytes`, given that it holds `*held`: a mutant of the same
/// length rewrites only the bytes between its first and last change (most of the test's time
/// under ASan went to rewriting whole files).
void update_bytes(const std::string& path, const Bytes& bytes, Bytes* held) {
    if (held->size() != bytes.size()) {
        write_bytes(path, bytes);
    } else {
        const auto first = std::mismatch(bytes.begin(), bytes.end(), held->begin()).first;
        if (first != bytes.end()) {
            const auto last = std::mismatch(bytes.rbegin(), bytes.rend(), held->rbegin()).first;
            const auto begin = static_cast<std::streamoff>(first - bytes.begin());
            const auto end = static_cast<std::streamoff>(bytes.rend() - last);
            std::fstream out(path, std::ios::binary | std::ios::in | std::ios::out);
            out.seekp(begin);
            out.write(reinterpret_cast<const char*>(bytes.data()) + begin, end - begin);
        }
    }
    *held = bytes;
}

/// Reads one mutant; returns a failure description, or "" when it behaved.
std::string try_mutant(const Bytes& bytes, const std::string& what) {
    static const std::string path = test::temp_grid_path("fuzz_mutant");
    static Bytes held;
    update_bytes(path, bytes, &held);
    try {
        std::string why;
        const std::optional<LoadedGrid> g = read_density_grid_direct(path, "", &why, "fuzz");
        if (!g)
            return why.empty() ? what + ": declined without a reason" : "";
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                if (!std::isfinite(g->index_to_world[i][j]))
                    return what + ": non-finite transform";
        if (!g->grid)
            return what + ": no grid";
        if (!g->grid->empty() &&
            !(std::isfinite(g->grid->max_density()) && g->grid->max_density() >= 0.0f))
            return what + ": max density " + std::to_string(g->grid->max_density());
        return "";
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::Input)
            return what + ": Error of kind " + std::to_string(static_cast<int>(e.kind()));
        if (std::string(e.what()).find("fuzz: " + path) != 0)
            return what + ": message does not name the file: " + e.what();
        return "";
    } catch (const std::exception& e) {
        return what + ": threw " + e.what();
    }
}

/// Every offset up to 128 (header, UUID, descriptor), then `spread` more evenly over the rest;
/// every offset with $KASUMI_VDB_FUZZ_DENSE=1 (about 10 minutes in Release: the long run).
std::vector<size_t> offsets(size_t size, size_t spread) {
    const char* dense = std::getenv("KASUMI_VDB_FUZZ_DENSE");
    const size_t head = dense && std::strcmp(dense, "1") == 0 ? size : std::min<size_t>(size, 128);
    std::vector<size_t> o;
    for (size_t i = 0; i < head; ++i)
        o.push_back(i);
    if (head < size) {
        const size_t stride = std::max<size_t>(1, (size - head) / spread);
        for (size_t i = head + stride / 2; i < size; i += stride)
            o.push_back(i);
    }
    return o;
}

void put32(Bytes& b, size_t at, uint32_t v) {
    std::memcpy(b.data() + at, &v, std::min<size_t>(4, b.size() - at));
}
void put64(Bytes& b, size_t at, uint64_t v) {
    std::memcpy(b.data() + at, &v, std::min<size_t>(8, b.size() - at));
}

int check_all(const Fixture& f, const std::vector<std::pair<std::string, Bytes>>& mutants) {
    int failures = 0;
    for (const auto& [what, bytes] : mutants) {
        const std::string failure = try_mutant(bytes, f.name + " " + what);
        if (!failure.empty() && ++failures <= 10)
            ADD_FAILURE() << failure;
    }
    return failures;
}

TEST(VdbDirectFuzz, FixturesReadUnmutated) {
    for (const Fixture& f : fixtures()) {
        const std::string path = test::temp_grid_path("fuzz_unmutated");
        write_bytes(path, f.bytes);
        std::string why;
        const std::optional<LoadedGrid> g = read_density_grid_direct(path, "", &why);
        ASSERT_TRUE(g) << f.name << ": " << why;  // else the mutants would test the decline only
        EXPECT_GT(g->active_voxels, 0u) << f.name;
    }
}

TEST(VdbDirectFuzz, TruncatedAnywhere) {
    for (const Fixture& f : fixtures()) {
        std::vector<std::pair<std::string, Bytes>> mutants;
        for (size_t cut : offsets(f.bytes.size(), 64))
            mutants.emplace_back("cut at " + std::to_string(cut),
                                 Bytes(f.bytes.begin(), f.bytes.begin() + cut));
        EXPECT_EQ(check_all(f, mutants), 0) << f.name;
    }
}

TEST(VdbDirectFuzz, SingleBytes) {
    for (const Fixture& f : fixtures()) {
        std::vector<std::pair<std::string, Bytes>> mutants;
        for (size_t at : offsets(f.bytes.size(), 64)) {
            for (int op = 0; op < 3; ++op) {
                Bytes b = f.bytes;
                b[at] = op == 0 ? 0x00 : op == 1 ? 0xff : static_cast<uint8_t>(b[at] ^ 0x80);
                if (b[at] != f.bytes[at])
                    mutants.emplace_back("byte " + std::to_string(at) + " op " + std::to_string(op),
                                         std::move(b));
            }
        }
        EXPECT_EQ(check_all(f, mutants), 0) << f.name;
    }
}

TEST(VdbDirectFuzz, HugeCounts) {
    const uint32_t words32[] = {0x7fffffffu, 0x80000000u};
    const uint64_t words64[] = {0x8000000000000000ull, 0x0000010000000000ull};
    for (const Fixture& f : fixtures()) {
        std::vector<std::pair<std::string, Bytes>> mutants;
        // Counts, lengths and positions are 4- or 8-byte fields at any offset (strings and
        // masks shift them off alignment).
        for (size_t at : offsets(f.bytes.size(), 32)) {
            for (uint32_t w : words32) {
                Bytes b = f.bytes;
                put32(b, at, w);
                mutants.emplace_back("int32 " + std::to_string(w) + " at " + std::to_string(at),
                                     std::move(b));
            }
            for (uint64_t w : words64) {
                Bytes b = f.bytes;
                put64(b, at, w);
                mutants.emplace_back("int64 " + std::to_string(w) + " at " + std::to_string(at),
                                     std::move(b));
            }
        }
        EXPECT_EQ(check_all(f, mutants), 0) << f.name;
    }
}

TEST(VdbDirectFuzz, NodeMasksClaimingALeafTheFileLacksAreAnInputError) {
    // One active voxel, blosc (OpenVDB writes fog volumes without zip): a root child, a 5-level and
    // a 4-level internal node, one leaf. A bit set in the 4-level node's child mask claims a second
    // leaf: OpenVDB's reader then takes the leaf's stored mask as that leaf's topology and reads
    // every value chunk 64 bytes late, its sizes garbage that it allocates (out of memory, exit 1,
    // through the CLI). The direct reader reads on as OpenVDB would and refuses the first chunk
    // past the file's end.
    DenseVoxels v;
    v.dims = IVec3(1);
    v.values = {0.5f};
    v.compression = 4;
    const std::string path = test::temp_grid_path("fuzz_one_leaf");
    write_fog_volume(path, "density", v, 1.0, Vec3(0.0f));
    Bytes b = read_bytes(path);
    // The root: background 0, no tiles, one child at (0, 0, 0), then the 5-level node's child
    // mask holding child 0 only.
    const uint8_t root[25] = {0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0,
                              0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1};
    const auto at = std::search(b.begin(), b.end(), std::begin(root), std::end(root));
    ASSERT_NE(at, b.end());
    const size_t node5 = static_cast<size_t>(at - b.begin()) + 24;
    const size_t values5 = node5 + 2 * 4096;  // child and value masks of 32768 bits
    ASSERT_LT(values5 + 9, b.size());
    // Mask-compression code 0 or 6: no inactive values, no selection mask; then the chunk.
    ASSERT_TRUE(b[values5] == 0 || b[values5] == 6) << int(b[values5]);
    int64_t packed = 0;
    std::memcpy(&packed, &b[values5 + 1], sizeof(packed));
    ASSERT_GT(packed, 0);
    const size_t node4 = values5 + 9 + static_cast<size_t>(packed);
    ASSERT_LT(node4, b.size());
    ASSERT_EQ(b[node4], 1);  // the 4-level node's child mask: leaf 0
    b[node4] = 3;
    write_bytes(path, b);
    try {
        std::string why;
        read_density_grid_direct(path, "", &why, "fuzz");
        ADD_FAILURE() << "read or declined (" << why << "): OpenVDB's path would allocate";
    } catch (const Error& e) {
        EXPECT_EQ(e.kind(), ErrorKind::Input);
        EXPECT_NE(std::string(e.what()).find("fuzz: " + path +
                                             " grid \"density\": the node "
                                             "masks claim 2 leaves, whose topology ends at byte"),
                  std::string::npos)
            << e.what();
    }
}

TEST(VdbDirectFuzz, RandomMutantsFromEnvironment) {
    const char* env = std::getenv("KASUMI_VDB_FUZZ_SEEDS");
    const long seeds = env ? std::strtol(env, nullptr, 10) : 0;
    if (seeds <= 0)
        GTEST_SKIP() << "set KASUMI_VDB_FUZZ_SEEDS=N for N random mutants per fixture";
    for (const Fixture& f : fixtures()) {
        std::vector<std::pair<std::string, Bytes>> mutants;
        for (long s = 0; s < seeds; ++s) {
            Pcg32 rng(static_cast<uint64_t>(s), 9);
            Bytes b = f.bytes;
            const int edits = 1 + static_cast<int>(rng.next_u32() % 4);
            for (int e = 0; e < edits && !b.empty(); ++e) {
                const size_t at = rng.next_u32() % b.size();
                switch (rng.next_u32() % 5) {
                    case 0:
                        b[at] = static_cast<uint8_t>(rng.next_u32());
                        break;
                    case 1:
                        b[at] ^= static_cast<uint8_t>(1u << (rng.next_u32() % 8));
                        break;
                    case 2:
                        put32(b, at, rng.next_u32());
                        break;
                    case 3:
                        put32(b, at, 0x7fffffffu >> (rng.next_u32() % 24));
                        break;
                    default:
                        b.resize(at);
                        break;
                }
            }
            mutants.emplace_back("seed " + std::to_string(s), std::move(b));
            if (mutants.size() == 1000 || s + 1 == seeds) {
                EXPECT_EQ(check_all(f, mutants), 0) << f.name;
                mutants.clear();
            }
        }
    }
}

}  // namespace
}  // namespace kasumi
