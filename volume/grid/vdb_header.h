#pragma once
/// A check of an OpenVDB file's header against the file's size, before OpenVDB reads it.
/// OpenVDB trusts the lengths and counts it reads: a file cut inside its header, or holding
/// garbage there, made it allocate without bound (std::bad_alloc or the OOM killer) instead of
/// reporting a broken file. Header only, so it serves the executable and the OpenVDB module alike.
///
/// The layout checked (OpenVDB io/Archive.cc `readHeader`, io/GridDescriptor.cc `read`,
/// MetaMap::readMeta; every integer little-endian, a string is an int32 length and its bytes):
///   int64 magic 0x56444220 ("VDB "), uint32 file version, [>= 211] uint32 library major and
///   minor, [>= 212] char "has grid offsets", [220, 222) char "compressed", [>= 218] 36-char
///   UUID; the file's metadata (int32 count, then per entry: name, type name, int32 size and
///   that many bytes); int32 grid count, then per grid: unique name, type name, [>= 216]
///   instance parent name, int64 grid, block and end positions (0 <= grid <= block <= end <=
///   the file's size); at each grid's position, [>= 222] uint32 compression flags and the
///   grid's metadata, which must end before the grid's block position.
/// Files older than version 222 or without grid offsets get the magic-number check only.
#include "core/error.h"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>

namespace kasumi {

namespace vdb_header_detail {

class HeaderReader {
  public:
    HeaderReader(const std::string& path, const std::string& context)
        : m_in(path, std::ios::binary), m_where(context + ": " + path) {
        if (!m_in)
            throw_input_error(m_where + ": cannot open file");
        m_in.seekg(0, std::ios::end);
        m_size = static_cast<uint64_t>(m_in.tellg());
        m_in.seekg(0);
    }
    uint64_t size() const { return m_size; }
    uint64_t position() const { return m_pos; }
    const std::string& where() const { return m_where; }

    /// Reads n bytes of `what`, or throws: the file ends before them.
    void bytes(void* out, uint64_t n, const char* what) {
        if (n > m_size - m_pos) {
            fail("truncated: " + std::string(what) + " at byte " + std::to_string(m_pos) +
                 " needs " + std::to_string(n) + " bytes, the file has " + std::to_string(m_size) +
                 " bytes");
        }
        m_in.read(static_cast<char*>(out), static_cast<std::streamsize>(n));
        if (!m_in)
            fail("cannot read " + std::string(what) + " at byte " + std::to_string(m_pos));
        m_pos += n;
    }
    template <class T>
    T value(const char* what) {
        T v{};
        bytes(&v, sizeof(T), what);
        return v;
    }
    /// An int32 count or length that must be >= 0 and leave room for `each` bytes per unit.
    uint64_t count(const char* what, uint64_t each) {
        const int32_t n = value<int32_t>(what);
        if (n < 0 || static_cast<uint64_t>(n) * each > m_size - m_pos) {
            fail(std::string(what) + " at byte " + std::to_string(m_pos - 4) + " is " +
                 std::to_string(n) + ", more than the " + std::to_string(m_size - m_pos) +
                 " bytes left in the file can hold (truncated or not a VDB file)");
        }
        return static_cast<uint64_t>(n);
    }
    void skip(uint64_t n, const char* what) {
        if (n > m_size - m_pos) {
            fail("truncated: " + std::string(what) + " at byte " + std::to_string(m_pos) +
                 " needs " + std::to_string(n) + " bytes, the file has " + std::to_string(m_size) +
                 " bytes");
        }
        m_pos += n;
        m_in.seekg(static_cast<std::streamoff>(m_pos));
    }
    std::string string(const char* what) {
        const uint64_t n = count(what, 1);
        std::string s(static_cast<size_t>(n), '\0');
        if (n > 0)
            bytes(&s[0], n, what);
        return s;
    }
    void seek(uint64_t pos) {
        m_pos = pos;
        m_in.seekg(static_cast<std::streamoff>(pos));
    }
    void metadata(const char* what) {
        const uint64_t n = count(what, 12);  // three int32 lengths per entry at least
        for (uint64_t i = 0; i < n; ++i) {
            string("a metadata name");
            string("a metadata type name");
            skip(count("a metadata value's size", 1), "a metadata value");
        }
    }
    [[noreturn]] void fail(const std::string& what) const {
        throw_input_error(m_where + ": " + what);
    }

  private:
    std::ifstream m_in;
    std::string m_where;
    uint64_t m_size = 0;
    uint64_t m_pos = 0;
};

}  // namespace vdb_header_detail

/// Throws Error (Input), "<context>: <path>: <what was expected>", when `path` is not an
/// OpenVDB file or its header is cut short or declares more than the file holds.
inline void check_vdb_header(const std::string& path, const std::string& context) {
    vdb_header_detail::HeaderReader r(path, context);
    constexpr int64_t kMagic = 0x56444220;  // "VDB " (OPENVDB_MAGIC)
    if (r.size() < 8 || r.value<int64_t>("the magic number") != kMagic)
        r.fail("not a VDB file (it does not start with OpenVDB's magic number)");
    const uint32_t version = r.value<uint32_t>("the file version");
    if (version >= 211) {
        r.value<uint32_t>("the library major version");
        r.value<uint32_t>("the library minor version");
    }
    const bool offsets = version >= 212 ? r.value<char>("the grid-offsets flag") != 0 : false;
    if (version < 222 || !offsets)
        return;  // older layouts: OpenVDB's own checks
    char uuid[36];
    r.bytes(uuid, sizeof(uuid), "the file's UUID");
    r.metadata("the file's metadata count");
    struct Grid {
        std::string name;
        uint64_t grid = 0, block = 0;
    };
    const uint64_t grids = r.count("the grid count", 36);  // 3 lengths and 3 positions at least
    Grid first[16];
    for (uint64_t i = 0; i < grids; ++i) {
        Grid g;
        g.name = r.string("a grid name");
        r.string("a grid type name");
        if (version >= 216)
            r.string("a grid's instance parent name");
        const auto grid = r.value<int64_t>("a grid position");
        const auto block = r.value<int64_t>("a grid's block position");
        const auto end = r.value<int64_t>("a grid's end position");
        const std::string which = "grid \"" + g.name + "\"";
        if (grid < 0 || block < grid || end < block) {
            r.fail(which + " has positions " + std::to_string(grid) + ", " + std::to_string(block) +
                   ", " + std::to_string(end) + ": expected 0 <= grid <= block <= end");
        }
        if (static_cast<uint64_t>(end) > r.size()) {
            r.fail("truncated: " + which + " ends at byte " + std::to_string(end) +
                   ", the file has " + std::to_string(r.size()) + " bytes");
        }
        g.grid = static_cast<uint64_t>(grid);
        g.block = static_cast<uint64_t>(block);
        if (i < 16)
            first[i] = g;
    }
    // Each grid's own metadata (read when the grid is), within its grid..block stretch.
    for (uint64_t i = 0; i < grids && i < 16; ++i) {
        r.seek(first[i].grid);
        r.value<uint32_t>("a grid's compression flags");
        r.metadata("a grid's metadata count");
        if (r.position() > first[i].block) {
            r.fail("grid \"" + first[i].name + "\"'s metadata runs to byte " +
                   std::to_string(r.position()) + ", past its data at byte " +
                   std::to_string(first[i].block));
        }
    }
}

}  // namespace kasumi
