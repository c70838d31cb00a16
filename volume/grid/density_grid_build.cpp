#include "volume/grid/density_grid_build.h"

#include "core/error.h"
#include "core/zeroed_allocator.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cfloat>
#include <cstdint>

#include <sys/mman.h>

#ifdef __SSE2__
#include <emmintrin.h>
#include <xmmintrin.h>
#endif
#if defined(__x86_64__)
#include <immintrin.h>
#endif

namespace kasumi {

namespace {

constexpr int kBrick = DensityGrid::kBrick;
constexpr int kStored = DensityGrid::kStored;
static_assert(VoxelBlock::kEdge == kBrick, "a block spans at most 2 bricks per axis");

int floor_div(int a, int b) {
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

/// Where a block's voxels go. Brick B holds the voxels whose local index l (index - grid origin)
/// lies in [8B, 8B + 8]: its own 8 plus the apron, the first voxel of brick B + 1 (DensityGrid::set
/// does the same). For the 8 voxels l0 .. l0 + 7 of a block that means bricks base and base + 1
/// per axis, base = floor((l0 - 1) / 8): 8 bricks k = ox + 2 oy + 4 oz, and into brick k go the
/// block's voxels i with lo <= i <= hi per axis, at position i + shift.
struct BlockBricks {
    IVec3 base;
    IVec3 lo[8], hi[8], shift[8];
    bool any[8];  ///< whether brick k receives any voxel of the block at all

    explicit BlockBricks(IVec3 local0) {
        for (int a = 0; a < 3; ++a)
            base[a] = floor_div(local0[a] - 1, kBrick);
        for (int k = 0; k < 8; ++k) {
            const IVec3 o(k & 1, (k >> 1) & 1, k >> 2);
            shift[k] = local0 - kBrick * (base + o);
            lo[k] = glm::max(IVec3(0), -shift[k]);
            hi[k] = glm::min(IVec3(VoxelBlock::kEdge - 1), IVec3(kBrick) - shift[k]);
            any[k] = lo[k].x <= hi[k].x && lo[k].y <= hi[k].y && lo[k].z <= hi[k].z;
        }
    }
    /// The block's voxel bits (offset x << 6 | y << 3 | z, word x) that go to brick k, for the
    /// given word: bytes y in [lo.y, hi.y], bits z in [lo.z, hi.z].
    uint64_t yz_mask(int k) const {
        const uint64_t z_bits = ((uint64_t(2) << hi[k].z) - 1) & ~((uint64_t(1) << lo[k].z) - 1);
        uint64_t m = 0;
        for (int y = lo[k].y; y <= hi[k].y; ++y)
            m |= z_bits << (8 * y);
        return m;
    }
};

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define KASUMI_GRID_AVX2 1
/// classify_word eight at a time: the same comparisons (ordered >= 0 and <= FLT_MAX: false for
/// NaN; unordered != 0: true for NaN), half the instructions of the SSE2 loop.
__attribute__((target("avx2"))) void classify_word_avx2(const float* v, uint64_t& valid,
                                                        uint64_t& nonzero) {
    const __m256 zero = _mm256_setzero_ps(), largest = _mm256_set1_ps(FLT_MAX);
    uint64_t ok_bits = 0, nz_bits = 0;
    for (int i = 0; i < 64; i += 8) {
        const __m256 x = _mm256_loadu_ps(v + i);
        const __m256 ok = _mm256_and_ps(_mm256_cmp_ps(x, zero, _CMP_GE_OQ),
                                        _mm256_cmp_ps(x, largest, _CMP_LE_OQ));
        ok_bits |= static_cast<uint64_t>(_mm256_movemask_ps(ok)) << i;
        nz_bits |= static_cast<uint64_t>(_mm256_movemask_ps(_mm256_cmp_ps(x, zero, _CMP_NEQ_UQ)))
                   << i;
    }
    valid = ok_bits;
    nonzero = nz_bits;
}
#endif

/// Bits of the 64 values at v (one block word): `valid`, the finite values >= 0 (-0 included),
/// and `nonzero`, those != 0; eight at a time on a CPU with AVX2, four where SSE2 is available
/// (the same comparisons).
void classify_word(const float* v, uint64_t& valid, uint64_t& nonzero) {
#if defined(KASUMI_GRID_AVX2)
    static const bool avx2 = __builtin_cpu_supports("avx2");
    if (avx2) {
        classify_word_avx2(v, valid, nonzero);
        return;
    }
#endif
    valid = 0;
    nonzero = 0;
#ifdef __SSE2__
    const __m128 zero = _mm_setzero_ps(), largest = _mm_set1_ps(FLT_MAX);
    for (int i = 0; i < 64; i += 4) {
        const __m128 x = _mm_loadu_ps(v + i);
        const __m128 ok = _mm_and_ps(_mm_cmpge_ps(x, zero), _mm_cmple_ps(x, largest));
        valid |= static_cast<uint64_t>(_mm_movemask_ps(ok)) << i;
        nonzero |= static_cast<uint64_t>(_mm_movemask_ps(_mm_cmpneq_ps(x, zero))) << i;
    }
#else
    for (int i = 0; i < 64; ++i) {
        if (v[i] >= 0.0f && v[i] <= FLT_MAX)
            valid |= uint64_t(1) << i;
        if (v[i] != 0.0f)
            nonzero |= uint64_t(1) << i;
    }
#endif
}

/// t[x + 8 (y + 8 z)] = the block's value at offset(x, y, z) where its bit in `bits` (word x,
/// bit y << 3 | z) is set, else +0: the block transposed to the bricks' order (x fastest).
void transpose_block(const float* values, const uint64_t bits[VoxelBlock::kEdge],
                     float t[VoxelBlock::kVoxels]) {
#ifdef __SSE2__
    // A block with a full word is mostly dense: 4x4 transposes of masked rows, ~800
    // instructions a block; a sparse one copies its set bits one by one (~11 each).
    bool dense = false;
    for (int x = 0; x < VoxelBlock::kEdge; ++x)
        dense = dense || bits[x] == ~uint64_t(0);
    if (dense) {
        for (int y = 0; y < 8; ++y)
            for (int x0 = 0; x0 < 8; x0 += 4)
                for (int z0 = 0; z0 < 8; z0 += 4) {
                    __m128 r[4];
                    for (int i = 0; i < 4; ++i) {
                        const unsigned m =
                            static_cast<unsigned>(bits[x0 + i] >> (8 * y + z0)) & 0xFu;
                        const __m128i lanes = _mm_set_epi32(
                            -static_cast<int>((m >> 3) & 1u), -static_cast<int>((m >> 2) & 1u),
                            -static_cast<int>((m >> 1) & 1u), -static_cast<int>(m & 1u));
                        r[i] = _mm_and_ps(_mm_loadu_ps(values + ((x0 + i) << 6) + 8 * y + z0),
                                          _mm_castsi128_ps(lanes));
                    }
                    _MM_TRANSPOSE4_PS(r[0], r[1], r[2], r[3]);
                    for (int j = 0; j < 4; ++j)
                        _mm_storeu_ps(t + x0 + 8 * (y + 8 * (z0 + j)), r[j]);
                }
        return;
    }
#endif
    for (int i = 0; i < VoxelBlock::kVoxels; ++i)
        t[i] = 0.0f;
    for (int x = 0; x < VoxelBlock::kEdge; ++x) {
        for (uint64_t word = bits[x]; word != 0; word &= word - 1) {
            const int yz = __builtin_ctzll(word);
            t[x + 8 * ((yz >> 3) + 8 * (yz & 7))] = values[(x << 6) | yz];
        }
    }
}

}  // namespace

DensityGridBuild DensityGridBuilder::build(IVec3 index_min, IVec3 index_max,
                                           const std::vector<VoxelBlock>& blocks) {
    DensityGridBuild result;
    auto grid = std::make_shared<DensityGrid>(index_min, index_max);
    const size_t count = blocks.size();

    // Pass 1 (parallel): the bricks each block's non-zero voxels touch, and the first invalid
    // voxel of each block.
    std::vector<uint8_t> touched(count, 0);
    std::vector<int> invalid_at(count, -1);
    // Per block, its non-zero active voxels (word x, bit y << 3 | z): pass 2 writes only these.
    using BlockBits = std::array<uint64_t, VoxelBlock::kEdge>;
    std::vector<BlockBits, ZeroedAllocator<BlockBits>> nonzero_bits(count);  // every one written
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t b = r.begin(); b != r.end(); ++b) {
                              const VoxelBlock& block = blocks[b];
                              // The non-zero active voxels; the first active one (in offset order)
                              // that is NaN, infinite or negative is the block's invalid voxel.
                              uint64_t nonzero[VoxelBlock::kEdge] = {};
                              for (int w = 0; w < VoxelBlock::kEdge; ++w) {
                                  const uint64_t active = block.active[w];
                                  if (active == 0)
                                      continue;
                                  uint64_t valid = 0, nz = 0;
                                  classify_word(block.values + 64 * w, valid, nz);
                                  if (const uint64_t bad = active & ~valid; bad != 0) {
                                      invalid_at[b] = w * 64 + __builtin_ctzll(bad);
                                      break;
                                  }
                                  nonzero[w] = active & nz;
                              }
                              for (int w = 0; w < VoxelBlock::kEdge; ++w)
                                  nonzero_bits[b][static_cast<size_t>(w)] = nonzero[w];
                              const BlockBricks bricks(block.origin - grid->m_origin);
                              uint8_t mask = 0;
                              for (int k = 0; k < 8; ++k) {
                                  if (!bricks.any[k])
                                      continue;
                                  const uint64_t yz = bricks.yz_mask(k);
                                  for (int x = bricks.lo[k].x; x <= bricks.hi[k].x; ++x) {
                                      if (nonzero[x] & yz) {
                                          mask |= static_cast<uint8_t>(1 << k);
                                          break;
                                      }
                                  }
                              }
                              touched[b] = mask;
                          }
                      });
    for (size_t b = 0; b < count; ++b) {
        if (invalid_at[b] >= 0) {
            const int n = invalid_at[b];
            result.has_invalid = true;
            result.invalid.index = blocks[b].origin + IVec3(n >> 6, (n >> 3) & 7, n & 7);
            result.invalid.value = blocks[b].values[n];
            return result;
        }
    }

    // Allocate every touched brick once, numbered in slot order (neighbouring bricks along x,
    // then y, then z stay close in memory).
    std::vector<int32_t>& index = grid->m_brick_index;
    for (size_t b = 0; b < count; ++b) {
        if (touched[b] == 0)
            continue;
        const IVec3 base = BlockBricks(blocks[b].origin - grid->m_origin).base;
        for (int k = 0; k < 8; ++k) {
            if (touched[b] & (1 << k))
                index[grid->brick_slot(base + IVec3(k & 1, (k >> 1) & 1, k >> 2))] = 0;
        }
    }
    int32_t allocated = 0;
    for (int32_t& slot : index) {
        if (slot == 0)
            slot = allocated++;
    }
    grid->m_allocated = static_cast<size_t>(allocated);
    const size_t floats = grid->m_allocated * DensityGrid::kBrickVoxels;
    grid->m_voxels.reserve(floats);
    advise_huge_pages(grid->m_voxels.data(), floats * sizeof(float));
    grid->m_voxels.resize(floats);  // zeros from calloc, not written (ZeroedAllocator)

    // Pass 2 (parallel): copy each block's voxels into its bricks and their aprons. Every
    // (brick, position) belongs to exactly one voxel, so blocks write disjoint floats.
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, count), [&](const tbb::blocked_range<size_t>& r) {
            for (size_t b = r.begin(); b != r.end(); ++b) {
                if (touched[b] == 0)
                    continue;
                const VoxelBlock& block = blocks[b];
                // The block transposed to the bricks' order (x fastest), inactive and zero
                // voxels as +0: each brick then takes runs of consecutive floats along x. Only
                // the non-zero active voxels pass 1 found are copied; the rest are +0.
                float t[VoxelBlock::kVoxels];
                transpose_block(block.values, nonzero_bits[b].data(), t);
                const BlockBricks bricks(block.origin - grid->m_origin);
                for (int k = 0; k < 8; ++k) {
                    if (!(touched[b] & (1 << k)))
                        continue;
                    const size_t slot =
                        grid->brick_slot(bricks.base + IVec3(k & 1, (k >> 1) & 1, k >> 2));
                    float* dst = &grid->m_voxels[static_cast<size_t>(index[slot]) *
                                                 DensityGrid::kBrickVoxels];
                    const IVec3 lo = bricks.lo[k], hi = bricks.hi[k], sh = bricks.shift[k];
                    const int run = hi.x - lo.x + 1;
                    for (int z = lo.z; z <= hi.z; ++z)
                        for (int y = lo.y; y <= hi.y; ++y) {
                            const float* src = t + lo.x + 8 * (y + 8 * z);
                            float* out =
                                dst + (lo.x + sh.x) + kStored * ((y + sh.y) + kStored * (z + sh.z));
                            for (int i = 0; i < run; ++i)
                                out[i] = src[i];
                        }
                }
            }
        });
    grid->finalize();
    result.grid = std::move(grid);
    return result;
}

}  // namespace kasumi
