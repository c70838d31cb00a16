#pragma once
/// The byte layer of the direct .vdb reader (vdb_direct.h): a bounds-checked cursor over the
/// mapped file and the value codecs of OpenVDB's io/Compression (node-mask compression, blosc,
/// zip, raw). Internal to volume/grid.
#include "core/error.h"
#include "volume/grid/vdb_mapped_file.h"

#include <cstdint>
#include <cstring>
#include <limits>
#include <string>

namespace kasumi::vdb_file {

// io/Compression.h
constexpr uint32_t kCompressZip = 0x1;
constexpr uint32_t kCompressActiveMask = 0x2;
constexpr uint32_t kCompressBlosc = 0x4;
constexpr int8_t kNoMaskAndAllValues = 6;  // the only mask-compression code storing every value

/// A bounds-checked cursor over [0, size) of the mapped file.
class Cursor {
  public:
    Cursor(const uint8_t* data, size_t size, size_t pos = 0) : m_data(data), m_size(size) {
        seek(pos);
    }
    size_t pos() const { return m_pos; }
    void seek(size_t pos) {
        if (pos > m_size)
            decline("a position past the end of the file");
        m_pos = pos;
    }
    const uint8_t* take(uint64_t n) {
        if (n > m_size - m_pos)
            decline("truncated");
        const uint8_t* p = m_data + m_pos;
        m_pos += static_cast<size_t>(n);
        return p;
    }
    template <class T>
    T get() {
        T v;
        std::memcpy(&v, take(sizeof(T)), sizeof(T));
        return v;
    }
    /// Once the grid's layout is known: the "context: path grid" that input errors start with.
    void set_where(const std::string* where) { m_where = where; }
    /// The bytes of a blosc, zip or raw chunk of `n` bytes, where `expected_raw` are expected
    /// when stored raw (n <= 0). A chunk past the end of the file or a raw chunk of the wrong
    /// size is an input error once the layout is known: OpenVDB's reader (io/Compression.cc)
    /// allocates n bytes before reading them, and reads -n raw bytes into the leaf's buffer.
    const uint8_t* chunk(int64_t n, uint64_t expected_raw) {
        if (n == std::numeric_limits<int64_t>::min() ||
            (n <= 0 && static_cast<uint64_t>(-n) != expected_raw))
            broken("a raw chunk of " +
                   (n == std::numeric_limits<int64_t>::min() ? std::string("2^63")
                                                             : std::to_string(-n)) +
                   " bytes at byte " + std::to_string(m_pos) + ", expected " +
                   std::to_string(expected_raw));
        const uint64_t bytes = n <= 0 ? expected_raw : static_cast<uint64_t>(n);
        if (bytes > m_size - m_pos)
            broken("truncated: a chunk of " + std::to_string(bytes) + " bytes at byte " +
                   std::to_string(m_pos) + ", the file has " + std::to_string(m_size));
        return take(bytes);
    }
    std::string string() {
        const int32_t n = get<int32_t>();
        if (n < 0)
            decline("a negative string length");
        const uint8_t* p = take(static_cast<uint64_t>(n));
        return std::string(reinterpret_cast<const char*>(p), static_cast<size_t>(n));
    }
    /// MetaMap::readMeta: int32 count, then name, type name, int32 size and the value's bytes.
    void skip_metadata() {
        const int32_t n = get<int32_t>();
        if (n < 0)
            decline("a negative metadata count");
        for (int32_t i = 0; i < n; ++i) {
            string();
            string();
            const int32_t size = get<int32_t>();
            if (size < 0)
                decline("a negative metadata size");
            take(static_cast<uint64_t>(size));
        }
    }

  private:
    [[noreturn]] void broken(const std::string& why) const {
        if (m_where)
            throw_input_error(*m_where + ": " + why);
        decline(why);
    }
    const uint8_t* m_data;
    size_t m_size;
    size_t m_pos = 0;
    const std::string* m_where = nullptr;
};

/// io::readData for floats: `count` values into `out` (io/Compression.cc bloscFromStream,
/// unzipFromStream). Blosc wins when both flags are set, as in OpenVDB. Declines a chunk it
/// cannot decode.
void read_data(Cursor& in, uint32_t compression, float* out, uint32_t count);

/// The number of set bits in `n_words` 64-bit words.
uint32_t count_on(const uint64_t* words, int n_words);

/// io::readCompressedValues for floats and a node of `count` values with value mask `mask`:
/// fills the active values of `dest` (the inactive ones are left 0; a fog volume's are 0 or
/// ignored). `scratch` holds at least `count` floats.
void read_values(Cursor& in, uint32_t compression, float* dest, uint32_t count,
                 const uint64_t* mask, float* scratch);

/// Skips what read_values reads, returning nothing; the position is kept for a later read.
/// An unknown mask-compression code is skipped as OpenVDB reads it (io::readCompressedValues:
/// no inactive values, no selection mask), so that the chunk sizes OpenVDB would read after it
/// are checked here; read_values declines it.
void skip_values(Cursor& in, uint32_t compression, uint32_t count, const uint64_t* mask);

}  // namespace kasumi::vdb_file
