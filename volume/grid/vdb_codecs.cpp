#include "volume/grid/vdb_codecs.h"

#include <zlib.h>

#include <algorithm>
#include <mutex>

#include <dlfcn.h>

namespace kasumi::vdb_file {

namespace {

/// libblosc, loaded on first use like OpenVDB itself (it is OpenVDB's own dependency, so it is
/// installed wherever the module works); null when missing.
struct Blosc {
    int (*decompress_ctx)(const void* src, void* dest, size_t destsize, int threads) = nullptr;
    int (*cbuffer_validate)(const void* src, size_t cbytes, size_t* nbytes) = nullptr;
};
const Blosc* blosc() {
    static Blosc api;
    static bool ok = false;
    static std::once_flag once;
    std::call_once(once, [] {
        void* lib = ::dlopen("libblosc.so.1", RTLD_NOW | RTLD_LOCAL);
        if (!lib)
            return;
        api.decompress_ctx =
            reinterpret_cast<decltype(api.decompress_ctx)>(::dlsym(lib, "blosc_decompress_ctx"));
        api.cbuffer_validate = reinterpret_cast<decltype(api.cbuffer_validate)>(
            ::dlsym(lib, "blosc_cbuffer_validate"));
        ok = api.decompress_ctx && api.cbuffer_validate;
    });
    return ok ? &api : nullptr;
}

}  // namespace

/// io::readData for floats: `count` values into `out` (io/Compression.cc bloscFromStream,
/// unzipFromStream). Blosc wins when both flags are set, as in OpenVDB.
void read_data(Cursor& in, uint32_t compression, float* out, uint32_t count) {
    const uint64_t bytes = uint64_t(count) * sizeof(float);
    if (compression & (kCompressBlosc | kCompressZip)) {
        const int64_t n = in.get<int64_t>();
        const uint8_t* src = in.chunk(n, bytes);
        if (n <= 0) {  // stored raw
            std::memcpy(out, src, bytes);
            return;
        }
        if (compression & kCompressBlosc) {
            const Blosc* b = blosc();
            if (!b)
                decline("libblosc.so.1 is not available");
            size_t nbytes = 0;
            if (b->cbuffer_validate(src, static_cast<size_t>(n), &nbytes) != 0 || nbytes != bytes)
                decline("a blosc chunk of the wrong size");
            if (bytes > 0 && b->decompress_ctx(src, out, bytes, 1) != static_cast<int>(bytes))
                decline("a broken blosc chunk");
        } else {
            uLongf len = static_cast<uLongf>(bytes);
            if (::uncompress(reinterpret_cast<Bytef*>(out), &len, src, static_cast<uLong>(n)) !=
                    Z_OK ||
                len != bytes)
                decline("a broken zip chunk");
        }
    } else {
        std::memcpy(out, in.take(bytes), bytes);
    }
}

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define KASUMI_VDB_POPCNT 1
/// count_on with the POPCNT instruction: the build targets baseline x86-64, where
/// __builtin_popcountll is a call into libgcc (~21 instructions a word; 0.7M instructions
/// reading the WDAS cloud).
__attribute__((target("popcnt"))) uint32_t count_on_popcnt(const uint64_t* words, int n_words) {
    uint32_t c = 0;
    for (int w = 0; w < n_words; ++w)
        c += static_cast<uint32_t>(__builtin_popcountll(words[w]));
    return c;
}
#endif

uint32_t count_on(const uint64_t* words, int n_words) {
#if defined(KASUMI_VDB_POPCNT)
    static const bool popcnt = __builtin_cpu_supports("popcnt");
    if (popcnt)
        return count_on_popcnt(words, n_words);
#endif
    uint32_t c = 0;
    for (int w = 0; w < n_words; ++w)
        c += static_cast<uint32_t>(__builtin_popcountll(words[w]));
    return c;
}

/// io::readCompressedValues for floats and a node of `count` values with value mask `mask`:
/// fills the active values of `dest` (the inactive ones are left 0; a fog volume's are 0 or
/// ignored). `scratch` holds at least `count` floats.
void read_values(Cursor& in, uint32_t compression, float* dest, uint32_t count,
                 const uint64_t* mask, float* scratch) {
    const int8_t code = in.get<int8_t>();
    if (code < 0 || code > kNoMaskAndAllValues)
        decline("an unknown mask-compression code");
    if (code == 2 || code == 4 || code == 5)  // one inactive value, or two
        in.take(code == 5 ? 8 : 4);
    if (code >= 3 && code <= 5)  // the selection mask between two inactive values
        in.take(count / 8);
    const int words = static_cast<int>(count / 64);
    const bool compact = (compression & kCompressActiveMask) && code != kNoMaskAndAllValues;
    const uint32_t stored = compact ? count_on(mask, words) : count;
    if (stored == count) {
        read_data(in, compression, dest, count);
        return;
    }
    read_data(in, compression, scratch, stored);
    std::fill(dest, dest + count, 0.0f);
    uint32_t k = 0;
    for (int w = 0; w < words; ++w) {
        for (uint64_t word = mask[w]; word != 0; word &= word - 1)
            dest[w * 64 + __builtin_ctzll(word)] = scratch[k++];
    }
}

/// Skips what read_values reads, returning nothing; the position is kept for a later read.
/// An unknown mask-compression code is skipped as OpenVDB reads it (io::readCompressedValues:
/// no inactive values, no selection mask), so that the chunk sizes OpenVDB would read after it
/// are checked here; read_values declines it.
void skip_values(Cursor& in, uint32_t compression, uint32_t count, const uint64_t* mask) {
    const int8_t code = in.get<int8_t>();
    if (code == 2 || code == 4 || code == 5)
        in.take(code == 5 ? 8 : 4);
    if (code >= 3 && code <= 5)
        in.take(count / 8);
    const bool compact = (compression & kCompressActiveMask) && code != kNoMaskAndAllValues;
    const uint64_t stored = compact ? count_on(mask, static_cast<int>(count / 64)) : count;
    if (compression & (kCompressBlosc | kCompressZip)) {
        in.chunk(in.get<int64_t>(), stored * sizeof(float));
    } else {
        in.take(stored * sizeof(float));
    }
}

}  // namespace kasumi::vdb_file
