#include "core/exr_io.h"

#include "core/atomic_file.h"
#include "core/error.h"
#include "core/exr_half.h"
#include "core/exr_module.h"
#include "core/module_loader.h"

#include <openexr.h>
#include <zlib.h>
#if defined(__x86_64__)
#include <immintrin.h>
#endif
#if defined(__GLIBC__)
#include <malloc.h>
#endif

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstring>
#include <exception>
#include <memory>
#include <mutex>
#include <set>
#include <stdexcept>
#include <thread>

#ifndef KASUMI_EXR_MODULE_BUILD_PATH
#define KASUMI_EXR_MODULE_BUILD_PATH ""
#endif

namespace kasumi {
namespace {

/// The first non-finite value of `n` floats, or n. One branch-free pass the compiler vectorises
/// (an exponent of all ones is an infinity or a NaN); the index is searched only when one is seen.
size_t first_non_finite(const float* data, size_t n) {
    uint32_t all_ones = 0;
    for (size_t i = 0; i < n; ++i) {
        uint32_t bits;
        std::memcpy(&bits, &data[i], sizeof bits);
        all_ones |= static_cast<uint32_t>((bits & 0x7f800000u) == 0x7f800000u);
    }
    if (all_ones == 0)
        return n;
    for (size_t i = 0; i < n; ++i)
        if (!std::isfinite(data[i]))
            return i;
    return n;
}

/// What the header says of the HALF channels, before any is converted: the largest |v| and how
/// many values exceed the half range (the conversion itself runs block by block while the file
/// is written, after the header). Finite values only (checked first).
void scan_half_range(const float* data, size_t n, ExrWriteReport& report) {
    float max_abs = report.half_max_abs;
    uint64_t saturated = 0;
    for (size_t i = 0; i < n; ++i) {
        const float magnitude = std::fabs(data[i]);
        max_abs = std::max(max_abs, magnitude);
        saturated += magnitude > kHalfMax ? 1u : 0u;
    }
    report.half_max_abs = max_abs;
    report.half_saturated += saturated;
}

void check_writable(const Image& header, const std::vector<ExrChannelView>& channels) {
    if (header.width <= 0 || header.height <= 0)
        throw Error(ErrorKind::Runtime, "write_exr: empty image " + std::to_string(header.width) +
                                            "x" + std::to_string(header.height));
    if (channels.empty())
        throw Error(ErrorKind::Runtime, "write_exr: image has no channels");
    const size_t pixels = static_cast<size_t>(header.width) * static_cast<size_t>(header.height);
    std::set<std::string> names;
    for (const ExrChannelView& channel : channels) {
        if (channel.name.empty() || !names.insert(channel.name).second)
            throw Error(ErrorKind::Runtime,
                        "write_exr: empty or repeated channel name '" + channel.name + "'");
        // The renderer guarantees finite pixels; this is the last guard before the file.
        const size_t i = first_non_finite(channel.data, pixels);
        if (i < pixels) {
            const float v = channel.data[i];
            const size_t x = i % static_cast<size_t>(header.width);
            const size_t y = i / static_cast<size_t>(header.width);
            throw Error(ErrorKind::Runtime, "write_exr: channel '" + channel.name + "' pixel (" +
                                                std::to_string(x) + ", " + std::to_string(y) +
                                                ") is " + (std::isnan(v) ? "NaN" : "infinite") +
                                                ": refusing to write a non-finite value");
        }
    }
    for (const auto& kv : header.metadata) {
        if (kv.first.empty())
            throw Error(ErrorKind::Runtime, "write_exr: metadata with an empty key");
    }
}

/// HALF channels: what the header reports of them (scanned before the file is opened; the
/// values are converted while each block is packed).
struct HalfPlanes {
    std::vector<size_t> channels;  ///< indices of the HALF channels
    ExrWriteReport report;
    bool any() const { return !channels.empty(); }
};

HalfPlanes scan_half_channels(const Image& header, const std::vector<ExrChannelView>& channels) {
    const size_t pixels = static_cast<size_t>(header.width) * static_cast<size_t>(header.height);
    HalfPlanes planes;
    for (size_t c = 0; c < channels.size(); ++c) {
        if (channels[c].type != ExrPixelType::Half)
            continue;
        planes.channels.push_back(c);
        scan_half_range(channels[c].data, pixels, planes.report);
    }
    return planes;
}

/// ZIP (OpenEXR's ZIP_COMPRESSION) is written here through OpenEXR's core C library, which
/// takes each chunk as we compressed it: Imf::OutputFile splits and predicts the bytes one at a
/// time, copies every scanline through its frame buffer and hands each block to its thread pool
/// (43.5M instructions for a 128x128 render with its AOVs, 19% of the process at 1 spp, of
/// which 40% before zlib). The file is the same format, every byte of pixels the same.
constexpr int kZipBlockRows = 16;  ///< scanlines per ZIP chunk (the format's)

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__,
              "ZIP chunks are packed from the planes' bytes: EXR values are little-endian");

/// OpenEXR's ZIP pre-pass over one chunk of `n` bytes (n even: 2- and 4-byte values): the even
/// bytes, then the odd ones (the low and high bytes of the values apart), each then replaced by
/// its difference from the one before plus 128, modulo 256 (smooth data becomes runs of 128).
/// In one pass over `raw` (OpenEXR splits into a buffer, then differences it byte by byte).
void zip_predict(const uint8_t* raw, size_t n, uint8_t* out) {
    if (n == 0)
        return;
    const size_t half = n / 2;
    out[0] = raw[0];
    for (size_t i = 1; i < half; ++i)
        out[i] = static_cast<uint8_t>(raw[2 * i] - raw[2 * i - 2] + 128u);
    out[half] = static_cast<uint8_t>(raw[1] - raw[n - 2] + 128u);
    for (size_t i = 1; i < half; ++i)
        out[half + i] = static_cast<uint8_t>(raw[2 * i + 1] - raw[2 * i - 1] + 128u);
}

/// zlib's checksum of `n` bytes (RFC 1950: s1 = 1 + the sum of the bytes, s2 = the sum of the
/// successive s1, both modulo 65521; s2 << 16 | s1).
uint32_t adler32_of(const uint8_t* data, size_t n);

#if defined(__x86_64__) && (defined(__GNUC__) || defined(__clang__))
#define KASUMI_EXR_AVX2_ADLER 1
/// The same 32 bytes at a time (zlib 1.2.13 adds them one by one, 18% of its deflate's
/// instructions on a render's ZIP chunks). Over a chunk of bytes b_0 .. b_31: s1 gains their
/// sum, s2 gains 32 s1 plus sum (32 - i) b_i; over up to 173 chunks (5536 bytes, zlib's NMAX
/// bound: nothing overflows 32 bits before the modulo) s2 gains 32 times the running s1 before
/// each chunk.
/// The sum of the 8 32-bit lanes of `v`.
__attribute__((target("avx2"))) uint64_t sum_lanes(__m256i v) {
    const __m128i h = _mm_add_epi32(_mm256_castsi256_si128(v), _mm256_extracti128_si256(v, 1));
    const __m128i q = _mm_add_epi32(h, _mm_shuffle_epi32(h, 0x4e));
    return static_cast<uint32_t>(_mm_cvtsi128_si32(_mm_add_epi32(q, _mm_shuffle_epi32(q, 0xb1))));
}

__attribute__((target("avx2"))) uint32_t adler32_avx2(const uint8_t* data, size_t n) {
    constexpr uint32_t kBase = 65521;
    constexpr size_t kChunksPerRound = 173;
    uint64_t s1 = 1, s2 = 0;
    const __m256i weights =
        _mm256_setr_epi8(32, 31, 30, 29, 28, 27, 26, 25, 24, 23, 22, 21, 20, 19, 18, 17, 16, 15, 14,
                         13, 12, 11, 10, 9, 8, 7, 6, 5, 4, 3, 2, 1);
    const __m256i ones = _mm256_set1_epi16(1), zero = _mm256_setzero_si256();
    while (n >= 32) {
        const size_t chunks = std::min(n / 32, kChunksPerRound);
        __m256i byte_sums = zero, prefix = zero, weighted = zero;
        for (size_t c = 0; c < chunks; ++c, data += 32) {
            const __m256i v = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(data));
            prefix = _mm256_add_epi32(prefix, byte_sums);
            byte_sums = _mm256_add_epi32(byte_sums, _mm256_sad_epu8(v, zero));
            weighted = _mm256_add_epi32(weighted,
                                        _mm256_madd_epi16(_mm256_maddubs_epi16(v, weights), ones));
        }
        s2 = (s2 + 32 * chunks * s1 + 32 * sum_lanes(prefix) + sum_lanes(weighted)) % kBase;
        s1 = (s1 + sum_lanes(byte_sums)) % kBase;
        n -= 32 * chunks;
    }
    for (size_t i = 0; i < n; ++i) {
        s1 += data[i];
        s2 += s1;
    }
    return static_cast<uint32_t>((s2 % kBase) << 16 | (s1 % kBase));
}
#endif

uint32_t adler32_of(const uint8_t* data, size_t n) {
#if defined(KASUMI_EXR_AVX2_ADLER)
    static const bool avx2 = __builtin_cpu_supports("avx2");
    if (avx2)
        return adler32_avx2(data, n);
#endif
    return static_cast<uint32_t>(
        adler32_z(adler32_z(0, nullptr, 0), data, static_cast<z_size_t>(n)));
}

/// A channel in the file's order (by name), with what its values are written as.
struct ZipChannel {
    const float* data = nullptr;
    ExrPixelType type = ExrPixelType::Float;
};

/// Encodes ZIP chunks: rows [y0, y0 + rows) packed as OpenEXR lays them out (row after row, in
/// each row every channel's `width` values, channels in name order), predicted and deflated
/// (zlib level 1: on a 1280x720 render with its AOVs, 8% less write time than the default level
/// for a 3% larger file, float noise compresses little at any level). The zlib stream is the
/// one compress2 makes at that level, the bytes OpenEXR writes: its 2-byte header, the raw
/// deflate stream, the Adler-32 of the input (computed here, adler32_of). The chunk is the
/// packed bytes themselves when deflate does not make them smaller (the format's rule: a chunk
/// as large as its raw data is raw). Half channels are converted here, counted in `report`.
/// One deflate state and one set of buffers, never cleared, serve every chunk (compress2
/// allocates and clears ~270 KB of state per call; a vector sized for deflate's bound would be
/// cleared per chunk, 1.4 MB of a 1280-pixel block with every AOV).
class ZipEncoder {
  public:
    ZipEncoder() {
        // Raw deflate (negative window bits: no zlib header or checksum), level 1, zlib's
        // default window (15 bits), memory level (8) and strategy, as compress2 uses them.
        if (deflateInit2(&m_stream, 1, Z_DEFLATED, -15, 8, Z_DEFAULT_STRATEGY) != Z_OK)
            throw std::runtime_error("zlib deflateInit2 failed");
    }
    ~ZipEncoder() { deflateEnd(&m_stream); }
    ZipEncoder(const ZipEncoder&) = delete;
    ZipEncoder& operator=(const ZipEncoder&) = delete;

    /// The chunk's bytes, valid until the next call.
    struct Chunk {
        const uint8_t* data;
        size_t size;
    };

    Chunk encode(const std::vector<ZipChannel>& channels, size_t width, int y0, int rows,
                 ExrWriteReport& report) {
        size_t row_bytes = 0;
        for (const ZipChannel& channel : channels)
            row_bytes += width * (channel.type == ExrPixelType::Half ? 2u : 4u);
        const size_t n = row_bytes * static_cast<size_t>(rows);
        constexpr size_t kHeader = 2, kChecksum = 4;
        const size_t bound = kHeader + deflateBound(&m_stream, static_cast<uLong>(n)) + kChecksum;
        if (n > m_capacity || bound > m_out_capacity) {  // every byte written before it is read
            m_packed.reset(new uint8_t[n]);
            m_predicted.reset(new uint8_t[n]);
            m_out.reset(new uint8_t[bound]);
            m_capacity = n;
            m_out_capacity = bound;
        }
        uint8_t* to = m_packed.get();
        for (int y = y0; y < y0 + rows; ++y) {
            const size_t first = static_cast<size_t>(y) * width;
            for (const ZipChannel& channel : channels) {
                if (channel.type == ExrPixelType::Half) {
                    // Even offsets only (every value before is 2 or 4 bytes): aligned halves.
                    convert_to_half(channel.data + first, width, reinterpret_cast<Imath::half*>(to),
                                    report);
                    to += width * 2;
                } else {
                    std::memcpy(to, channel.data + first, width * 4);
                    to += width * 4;
                }
            }
        }
        zip_predict(m_packed.get(), n, m_predicted.get());
        uint8_t* out = m_out.get();
        out[0] = 0x78;  // deflate, 32 KB window
        out[1] = 0x01;  // level 1 ("fastest"), no dictionary; header % 31 == 0
        m_stream.next_in = m_predicted.get();
        m_stream.avail_in = static_cast<uInt>(n);
        m_stream.next_out = out + kHeader;
        m_stream.avail_out = static_cast<uInt>(bound - kHeader - kChecksum);
        const int result = deflate(&m_stream, Z_FINISH);
        const size_t size = kHeader + m_stream.total_out + kChecksum;
        deflateReset(&m_stream);
        if (result == Z_STREAM_END && size < n) {
            const uint32_t checksum = adler32_of(m_predicted.get(), n);
            for (size_t i = 0; i < kChecksum; ++i)  // big-endian
                out[size - kChecksum + i] = static_cast<uint8_t>(checksum >> (24 - 8 * i));
            return {out, size};
        }
        return {m_packed.get(), n};
    }

  private:
    z_stream m_stream{};
    std::unique_ptr<uint8_t[]> m_packed, m_predicted, m_out;
    size_t m_capacity = 0, m_out_capacity = 0;
};

/// The message of the last failed OpenEXR core call on this thread (its error callback; the
/// default one prints to stderr).
thread_local std::string exr_core_message;

void remember_exr_core_error(exr_const_context_t, exr_result_t code, const char* message) {
    exr_core_message = std::string(exr_get_error_code_as_string(code)) +
                       (message ? ": " + std::string(message) : "");
}

void check_exr_core(exr_result_t result) {
    if (result != EXR_ERR_SUCCESS) {
        const std::string message =
            exr_core_message.empty() ? exr_get_default_error_message(result) : exr_core_message;
        exr_core_message.clear();
        throw std::runtime_error(message);
    }
}

/// An OpenEXR core write context, finished (offset table written, file closed) on every path.
class ExrCoreWriter {
  public:
    explicit ExrCoreWriter(const std::string& path) {
        exr_context_initializer_t init = EXR_DEFAULT_CONTEXT_INITIALIZER;
        init.error_handler_fn = &remember_exr_core_error;
        check_exr_core(exr_start_write(&m_context, path.c_str(), EXR_WRITE_FILE_DIRECTLY, &init));
    }
    ~ExrCoreWriter() { finish(); }
    ExrCoreWriter(const ExrCoreWriter&) = delete;
    ExrCoreWriter& operator=(const ExrCoreWriter&) = delete;

    exr_context_t context() const { return m_context; }
    exr_result_t finish() { return m_context ? exr_finish(&m_context) : EXR_ERR_SUCCESS; }

  private:
    exr_context_t m_context = nullptr;
};

/// How many threads compress `blocks` chunks of `bytes` raw bytes in all, for a write asked to
/// use `threads` (0: every hardware thread): at least 1 MiB of raw data each (a thread's start
/// costs more than it saves on less).
int zip_threads(int threads, size_t bytes, int blocks) {
    const int hardware = std::max(1, static_cast<int>(std::thread::hardware_concurrency()));
    const int asked = threads <= 0 ? hardware : std::min(threads, hardware);
    const int by_size = static_cast<int>(std::max<size_t>(1, bytes >> 20));
    return std::max(1, std::min({asked, by_size, blocks}));
}

/// Keeps zlib's deflate state in the process: zlib allocates ~270 KB of it for every write (it
/// was every compressed block with Imf) and frees it after; glibc's default trim threshold (128 KB)
/// then returns the top of the arena to the kernel each time (madvise, and in a VM a TLB shootdown
/// on every core): 4% of the CPU of a 640x480 soft-shadow render. Keep up to 64 MB of freed memory
/// instead.
void keep_freed_memory() {
#if defined(__GLIBC__)
    static std::once_flag once;
    std::call_once(once, [] { mallopt(M_TRIM_THRESHOLD, 64 << 20); });
#endif
}

/// Writes the ZIP-compressed EXR of `channels` (checked, HALF ones scanned into `half`) to
/// `path`, with the header make_header gives Imf::OutputFile (its attributes, and the part's
/// `type` the core library adds); the HALF channels' flushes are counted in `half.report`.
void write_zip_exr(const Image& image, const std::vector<ExrChannelView>& channels,
                   const std::string& path, int threads, HalfPlanes& half) {
    keep_freed_memory();
    ExrCoreWriter writer(path);
    exr_context_t context = writer.context();
    int part = 0;
    check_exr_core(exr_add_part(context, nullptr, EXR_STORAGE_SCANLINE, &part));
    check_exr_core(exr_initialize_required_attr_simple(context, part, image.width, image.height,
                                                       EXR_COMPRESSION_ZIP));
    const std::vector<std::pair<std::string, std::string>> attributes =
        exr_string_attributes(image, half.any(), half.report);
    bool long_names = false;  // beyond 31 bytes: the file's "long names" flag, as Imf sets it
    for (const auto& kv : attributes)
        long_names = long_names || kv.first.size() > 31;
    for (const ExrChannelView& channel : channels)
        long_names = long_names || channel.name.size() > 31;
    if (long_names)
        check_exr_core(exr_set_longname_support(context, 1));
    for (const ExrChannelView& channel : channels)
        check_exr_core(
            exr_add_channel(context, part, channel.name.c_str(),
                            channel.type == ExrPixelType::Half ? EXR_PIXEL_HALF : EXR_PIXEL_FLOAT,
                            EXR_PERCEPTUALLY_LOGARITHMIC, 1, 1));
    const Chromaticities& c = image.chromaticities;
    const exr_attr_chromaticities_t chromaticities = {c.red_x,  c.red_y,  c.green_x, c.green_y,
                                                      c.blue_x, c.blue_y, c.white_x, c.white_y};
    check_exr_core(exr_attr_set_chromaticities(context, part, "chromaticities", &chromaticities));
    for (const auto& kv : attributes)
        check_exr_core(exr_attr_set_string(context, part, kv.first.c_str(), kv.second.c_str()));
    check_exr_core(exr_write_header(context));

    // The channels in the file's order (the list the core library sorted by name).
    const exr_attr_chlist_t* list = nullptr;
    check_exr_core(exr_get_channels(context, part, &list));
    std::vector<ZipChannel> ordered;
    for (int i = 0; i < list->num_channels; ++i)
        for (const ExrChannelView& channel : channels)
            if (channel.name == list->entries[i].name.str)
                ordered.push_back({channel.data, channel.type});
    if (ordered.size() != channels.size())
        throw std::runtime_error("channel list mismatch");

    const size_t width = static_cast<size_t>(image.width);
    const int blocks = (image.height + kZipBlockRows - 1) / kZipBlockRows;
    size_t row_bytes = 0;
    for (const ZipChannel& channel : ordered)
        row_bytes += width * (channel.type == ExrPixelType::Half ? 2u : 4u);
    const int workers = zip_threads(threads, row_bytes * static_cast<size_t>(image.height), blocks);
    const auto rows_of = [&](int block) {
        return std::min(kZipBlockRows, image.height - block * kZipBlockRows);
    };
    if (workers == 1) {
        ZipEncoder encoder;
        for (int b = 0; b < blocks; ++b) {
            const ZipEncoder::Chunk chunk =
                encoder.encode(ordered, width, b * kZipBlockRows, rows_of(b), half.report);
            check_exr_core(
                exr_write_scanline_chunk(context, part, b * kZipBlockRows, chunk.data, chunk.size));
        }
    } else {
        // Every chunk compressed first (each thread takes the next block), then written in order.
        std::vector<std::vector<uint8_t>> chunks(static_cast<size_t>(blocks));
        std::vector<ExrWriteReport> reports(static_cast<size_t>(workers));
        std::atomic<int> next{0};
        // A worker's failure (zlib's state or a buffer not allocated) is kept and rethrown
        // here after the join: an exception leaving a std::thread would end the process.
        std::vector<std::exception_ptr> failures(static_cast<size_t>(workers));
        const auto work = [&](int worker) {
            try {
                ZipEncoder encoder;
                for (int b = next++; b < blocks; b = next++) {
                    const ZipEncoder::Chunk chunk =
                        encoder.encode(ordered, width, b * kZipBlockRows, rows_of(b),
                                       reports[static_cast<size_t>(worker)]);
                    chunks[static_cast<size_t>(b)].assign(chunk.data, chunk.data + chunk.size);
                }
            } catch (...) {
                failures[static_cast<size_t>(worker)] = std::current_exception();
                next = blocks;  // the others stop at their next block
            }
        };
        std::vector<std::thread> helpers;
        for (int w = 1; w < workers; ++w)
            helpers.emplace_back(work, w);
        work(0);
        for (std::thread& helper : helpers)
            helper.join();
        for (const std::exception_ptr& failure : failures)
            if (failure)
                std::rethrow_exception(failure);
        for (const ExrWriteReport& report : reports)
            half.report.half_flushed_to_zero += report.half_flushed_to_zero;
        for (int b = 0; b < blocks; ++b)
            check_exr_core(exr_write_scanline_chunk(context, part, b * kZipBlockRows,
                                                    chunks[static_cast<size_t>(b)].data(),
                                                    chunks[static_cast<size_t>(b)].size()));
    }
    check_exr_core(writer.finish());
}

const ExrModuleApi& exr_module() {
    static const ModuleSpec spec{"OpenEXR module",
                                 "to read EXR files and to write them with piz, rle or none",
                                 kExrModuleFile,
                                 "KASUMI_EXR_MODULE",
                                 KASUMI_EXR_MODULE_BUILD_PATH,
                                 kExrModuleEntry,
                                 kExrModuleAbi};
    return module_api<ExrModuleApi>(spec);
}

}  // namespace

bool parse_exr_compression(const std::string& text, ExrCompression& compression) {
    if (text == "zip")
        compression = ExrCompression::Zip;
    else if (text == "piz")
        compression = ExrCompression::Piz;
    else if (text == "rle")
        compression = ExrCompression::Rle;
    else if (text == "none")
        compression = ExrCompression::None;
    else
        return false;
    return true;
}

bool parse_exr_pixel_type(const std::string& text, ExrPixelType& type) {
    if (text == "float")
        type = ExrPixelType::Float;
    else if (text == "half")
        type = ExrPixelType::Half;
    else
        return false;
    return true;
}

const char* exr_pixel_type_name(ExrPixelType type) {
    return type == ExrPixelType::Half ? "half" : "float";
}

ExrWriteReport write_exr(const Image& image, const std::string& path, ExrCompression compression,
                         ExrPixelType beauty) {
    const size_t pixels = static_cast<size_t>(std::max(image.width, 0)) *
                          static_cast<size_t>(std::max(image.height, 0));
    std::vector<ExrChannelView> channels;
    channels.reserve(image.channels.size());
    for (const ImageChannel& channel : image.channels) {
        if (channel.data.size() != pixels)
            throw Error(ErrorKind::Runtime, "write_exr: channel '" + channel.name + "' has " +
                                                std::to_string(channel.data.size()) +
                                                " values for " + std::to_string(pixels) +
                                                " pixels");
        const bool is_beauty = channel.name == "R" || channel.name == "G" || channel.name == "B" ||
                               channel.name == "A";
        channels.push_back(
            {channel.name, channel.data.data(), is_beauty ? beauty : ExrPixelType::Float});
    }
    return write_exr(image, channels, path, compression);
}

ExrWriteReport write_exr(const Image& header_image, const std::vector<ExrChannelView>& channels,
                         const std::string& path, ExrCompression compression, int threads) {
    check_writable(header_image, channels);
    HalfPlanes half = scan_half_channels(header_image, channels);
    AtomicFile file(path);
    try {
        if (compression == ExrCompression::Zip)
            write_zip_exr(header_image, channels, file.temp_path(), threads, half);
        else
            exr_module().write(header_image, channels, file.temp_path(), compression, threads,
                               half.report);
    } catch (const Error&) {
        throw;
    } catch (const std::exception& e) {
        throw_output_error(path + ": cannot write EXR: " + e.what());
    }
    file.commit();
    return half.report;
}

Image read_exr(const std::string& path) {
    return exr_module().read(path);
}

}  // namespace kasumi
