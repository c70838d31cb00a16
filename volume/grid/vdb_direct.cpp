#include "volume/grid/vdb_direct.h"

#include "core/error.h"
#include "core/zeroed_allocator.h"
#include "volume/grid/density_grid_build.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <zlib.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <functional>
#include <limits>
#include <memory>
#include <mutex>
#include <vector>

#include <dlfcn.h>
#include <fcntl.h>
#include <setjmp.h>
#include <signal.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "VDB files are little-endian");

namespace kasumi {

namespace {

/// Thrown inside this file only: the file is not one this reader handles (or is broken).
struct Declined {
    std::string why;
};
[[noreturn]] void decline(std::string why) {
    throw Declined{std::move(why)};
}

// io/Compression.h
constexpr uint32_t kCompressZip = 0x1;
constexpr uint32_t kCompressActiveMask = 0x2;
constexpr uint32_t kCompressBlosc = 0x4;
constexpr int8_t kNoMaskAndAllValues = 6;  // the only mask-compression code storing every value

// What a grid may cover. Both readers store every active voxel of a tile and a brick index over
// the active box, so a few bytes of a hostile file (one mask bit is a tile of 128³ voxels, two
// leaves far apart span 2^32 voxels per axis) would ask either for terabytes: such grids are
// input errors here rather than a decline (OpenVDB's path would allocate until it fails).
constexpr uint64_t kMaxTileVoxels = uint64_t(1) << 27;  // 512³ voxels of tiles: 0.8 GB of bricks
constexpr int64_t kMaxEdgeVoxels = int64_t(1) << 24;    // per axis of the active box
constexpr uint64_t kMaxBrickSlots = uint64_t(1) << 24;  // bricks of 8³ cells in the box: 0.2 GB

/// The file, mapped read-only.
class MappedFile {
  public:
    explicit MappedFile(const std::string& path) {
        m_fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
        if (m_fd < 0)
            decline("cannot open");
        struct stat st {};
        if (::fstat(m_fd, &st) != 0 || !S_ISREG(st.st_mode) || st.st_size <= 0)
            decline("not a regular, non-empty file");
        m_size = static_cast<size_t>(st.st_size);
        void* p = ::mmap(nullptr, m_size, PROT_READ, MAP_PRIVATE | MAP_POPULATE, m_fd, 0);
        if (p == MAP_FAILED)
            decline("cannot map");
        m_data = static_cast<const uint8_t*>(p);
    }
    ~MappedFile() {
        if (m_data)
            ::munmap(const_cast<uint8_t*>(m_data), m_size);
        if (m_fd >= 0)
            ::close(m_fd);
    }
    MappedFile(const MappedFile&) = delete;
    MappedFile& operator=(const MappedFile&) = delete;
    const uint8_t* data() const { return m_data; }
    size_t size() const { return m_size; }
    /// The file's size now (another process may have cut it since it was mapped).
    uint64_t size_now() const {
        struct stat st {};
        return ::fstat(m_fd, &st) == 0 ? static_cast<uint64_t>(st.st_size) : 0;
    }

  private:
    int m_fd = -1;
    const uint8_t* m_data = nullptr;
    size_t m_size = 0;
};

/// A read of the mapped file that survives the file being cut while it is read. Pages of a
/// mapping past the file's new end raise SIGBUS on access (even with MAP_POPULATE: truncation
/// unmaps them), so another process rewriting the .vdb killed the renderer. While a thread runs
/// `body` under a guard, a SIGBUS at an address of the mapping jumps back here instead; a
/// SIGBUS anywhere else goes to the handler that was installed before ours (by default: the
/// crash it always was). What `body` was doing is abandoned: a zip or blosc call cut short
/// leaks its small work buffers, once, on a run that then stops with an input error.
class SigbusGuard {
  public:
    SigbusGuard(const uint8_t* data, size_t size) : m_begin(data), m_end(data + size) { install(); }
    /// Runs `body`; false if it touched a page of the mapping that the file no longer has.
    /// Objects that `body` creates and a jump skips are not destroyed: keep what owns memory
    /// outside it.
    template <class Body>
    bool run(Body&& body) const {
        Active active{this, t_active, {}};
        const Restore restore{active.outer};  // also on an exception and after a jump
        t_active = &active;
        // sigsetjmp saves the signal mask (1): the handler runs with SIGBUS blocked, and a
        // jump out of it must not leave it blocked for the next fault.
        if (sigsetjmp(active.env, 1) != 0)
            return false;
        body();
        return true;
    }

  private:
    struct Active {
        const SigbusGuard* guard;
        Active* outer;
        sigjmp_buf env;
    };
    struct Restore {
        Active* outer;
        ~Restore() { t_active = outer; }
    };
    static inline thread_local Active* t_active = nullptr;
    static inline struct sigaction s_previous {};

    static void install() {
        static std::once_flag once;
        std::call_once(once, [] {
            struct sigaction action {};
            action.sa_sigaction = &SigbusGuard::handle;
            action.sa_flags = SA_SIGINFO;
            sigemptyset(&action.sa_mask);
            ::sigaction(SIGBUS, &action, &s_previous);
        });
    }
    static void handle(int signal, siginfo_t* info, void* context) {
        const Active* active = t_active;
        const auto* address = static_cast<const uint8_t*>(info->si_addr);
        if (active && address >= active->guard->m_begin && address < active->guard->m_end)
            siglongjmp(const_cast<Active*>(active)->env, 1);
        // Not ours: the previous handler, or the default action once this returns and the
        // faulting access runs again.
        if (s_previous.sa_flags & SA_SIGINFO) {
            if (s_previous.sa_sigaction) {
                s_previous.sa_sigaction(signal, info, context);
                return;
            }
        } else if (s_previous.sa_handler != SIG_DFL && s_previous.sa_handler != SIG_IGN) {
            s_previous.sa_handler(signal);
            return;
        }
        ::signal(SIGBUS, SIG_DFL);
    }

    const uint8_t* m_begin;
    const uint8_t* m_end;
};

std::function<void(const std::string&, const char*)>& read_hook() {
    static std::function<void(const std::string&, const char*)> hook;
    return hook;
}

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

uint32_t count_on(const uint64_t* words, int n_words) {
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

struct Tree {
    std::string where;  ///< "context: path grid "name"", for input errors
    uint32_t compression = 0;
    std::vector<VoxelBlock> leaves;  ///< in file order (their values are read later)
    std::vector<VoxelBlock> tiles;   ///< active tiles cut into 8³ blocks of one value
    std::deque<std::vector<float>> tile_values;
    uint64_t active_voxels = 0;
    uint64_t active_tiles = 0;
    IVec3 box_min{std::numeric_limits<int>::max()};
    IVec3 box_max{std::numeric_limits<int>::min()};

    void expand(IVec3 lo, IVec3 hi) {
        box_min = glm::min(box_min, lo);
        box_max = glm::max(box_max, hi);
    }
};

/// A leaf's active-voxel box from its mask (offset = x << 6 | y << 3 | z: word x, byte y, bit z).
void expand_by_leaf(Tree& tree, const VoxelBlock& leaf) {
    int x0 = -1, x1 = -1;
    uint64_t any = 0;
    for (int x = 0; x < 8; ++x) {
        if (leaf.active[x] != 0) {
            x0 = x0 < 0 ? x : x0;
            x1 = x;
            any |= leaf.active[x];
        }
    }
    if (x0 < 0)
        return;
    int y0 = 8, y1 = -1;
    uint8_t zs = 0;
    for (int y = 0; y < 8; ++y) {
        const uint8_t byte = static_cast<uint8_t>(any >> (8 * y));
        if (byte != 0) {
            y0 = std::min(y0, y);
            y1 = y;
            zs |= byte;
        }
    }
    const int z0 = __builtin_ctz(zs), z1 = 31 - __builtin_clz(zs);
    tree.expand(leaf.origin + IVec3(x0, y0, z0), leaf.origin + IVec3(x1, y1, z1));
}

/// InternalNode<ChildT, Log2>::readTopology (file format >= 222), children read recursively.
template <int Log2>
void read_internal(Cursor& in, Tree& tree, IVec3 origin, std::vector<float>& values) {
    constexpr uint32_t kCount = 1u << (3 * Log2);
    constexpr int kWords = kCount / 64;
    constexpr int kChildTotal = Log2 == 5 ? 7 : 3;  // log2 of a child's edge in voxels
    uint64_t child_mask[kWords], value_mask[kWords];
    std::memcpy(child_mask, in.take(sizeof(child_mask)), sizeof(child_mask));
    std::memcpy(value_mask, in.take(sizeof(value_mask)), sizeof(value_mask));
    values.resize(2 * kCount);
    read_values(in, tree.compression, values.data(), kCount, value_mask, values.data() + kCount);
    auto local = [](uint32_t i) {
        return IVec3(static_cast<int>(i >> (2 * Log2)),
                     static_cast<int>((i >> Log2) & ((1u << Log2) - 1)),
                     static_cast<int>(i & ((1u << Log2) - 1)));
    };
    // Active tiles: cut into 8³ blocks of one value, as vdb_read.cpp does.
    for (int w = 0; w < kWords; ++w) {
        for (uint64_t word = value_mask[w] & ~child_mask[w]; word != 0; word &= word - 1) {
            const uint32_t i = static_cast<uint32_t>(w * 64 + __builtin_ctzll(word));
            const IVec3 lo = origin + (local(i) << kChildTotal);
            const int edge = 1 << kChildTotal;
            if (tree.active_voxels + uint64_t(edge) * edge * edge > kMaxTileVoxels)
                throw_input_error(tree.where + ": active tiles cover more than 2^27 voxels");
            tree.tile_values.emplace_back(VoxelBlock::kVoxels, values[i]);
            ++tree.active_tiles;
            tree.active_voxels += uint64_t(edge) * edge * edge;
            tree.expand(lo, lo + IVec3(edge - 1));
            VoxelBlock block;
            block.values = tree.tile_values.back().data();
            block.active.fill(~uint64_t(0));
            for (int z = 0; z < edge; z += VoxelBlock::kEdge)
                for (int y = 0; y < edge; y += VoxelBlock::kEdge)
                    for (int x = 0; x < edge; x += VoxelBlock::kEdge) {
                        block.origin = lo + IVec3(x, y, z);
                        tree.tiles.push_back(block);
                    }
        }
    }
    for (int w = 0; w < kWords; ++w) {
        for (uint64_t word = child_mask[w]; word != 0; word &= word - 1) {
            const uint32_t i = static_cast<uint32_t>(w * 64 + __builtin_ctzll(word));
            const IVec3 child = origin + (local(i) << kChildTotal);
            if constexpr (Log2 == 5) {
                read_internal<4>(in, tree, child, values);
            } else {
                VoxelBlock leaf;  // LeafNode::readTopology: its value mask
                leaf.origin = child;
                std::memcpy(leaf.active.data(), in.take(sizeof(leaf.active)), sizeof(leaf.active));
                tree.leaves.push_back(leaf);
            }
        }
    }
}

/// Math/Maps.h: the map's type name, then its doubles; the matrix maps index to world for row
/// vectors (world = index * M), stored as index_to_world[i][j] = M(i, j) like vdb_read.cpp.
glm::dmat4 read_transform(Cursor& in) {
    const std::string type = in.string();
    auto vec3 = [&in] {
        double v[3];
        std::memcpy(v, in.take(sizeof(v)), sizeof(v));
        return glm::dvec3(v[0], v[1], v[2]);
    };
    glm::dmat4 m(1.0);
    if (type == "AffineMap") {
        double a[16];  // Mat4d, row-major
        std::memcpy(a, in.take(sizeof(a)), sizeof(a));
        for (int i = 0; i < 4; ++i)
            for (int j = 0; j < 4; ++j)
                m[i][j] = a[4 * i + j];
    } else if (type == "ScaleMap" || type == "UniformScaleMap") {
        const glm::dvec3 s = vec3();
        in.take(4 * 3 * sizeof(double));  // voxel size, inverse scale, its square, 1 / (2 scale)
        m[0][0] = s.x;
        m[1][1] = s.y;
        m[2][2] = s.z;
    } else if (type == "ScaleTranslateMap" || type == "UniformScaleTranslateMap") {
        const glm::dvec3 t = vec3();
        const glm::dvec3 s = vec3();
        in.take(4 * 3 * sizeof(double));
        m[0][0] = s.x;
        m[1][1] = s.y;
        m[2][2] = s.z;
        m[3] = glm::dvec4(t, 1.0);
    } else if (type == "TranslationMap") {
        m[3] = glm::dvec4(vec3(), 1.0);
    } else {
        decline("map " + type);
    }
    return m;
}

struct Descriptor {
    std::string name, type;
    bool half = false, instance = false;
    uint64_t grid = 0, block = 0, end = 0;
};

/// The transform must map index space to world space and back (OpenVDB's maps are affine).
void check_transform(const glm::dmat4& m, const std::string& where) {
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j)
            if (!std::isfinite(m[i][j]))
                throw_input_error(where + ": the transform holds a non-finite number");
    if (m[0][3] != 0.0 || m[1][3] != 0.0 || m[2][3] != 0.0 || m[3][3] != 1.0)
        throw_input_error(where + ": the transform is not affine");
    const double det = glm::determinant(glm::dmat3(m));
    const glm::dmat4 inverse = glm::inverse(m);
    bool finite = std::isfinite(det) && det != 0.0;
    for (int i = 0; i < 4 && finite; ++i)
        for (int j = 0; j < 4; ++j)
            finite = finite && std::isfinite(inverse[i][j]);
    if (!finite)
        throw_input_error(where + ": the transform is not invertible");
}

/// What a read builds, kept outside the guarded reads (SigbusGuard::run): a jump out of them
/// skips the destructors of what they created.
struct ReadState {
    std::vector<Descriptor> grids;
    Tree tree;
    std::vector<float> scratch;
    std::vector<size_t> values_at;
    std::vector<float, ZeroedAllocator<float>> values;
    std::string shifted_where;
    LoadedGrid loaded;
};

/// The file's header and descriptors, the chosen grid's topology and the positions of its
/// leaves' values; returns false when the grid is empty (nothing more to read).
bool read_layout(const MappedFile& file, const std::string& path, const std::string& wanted,
                 const std::string& context, ReadState& state) {
    Cursor in(file.data(), file.size());
    if (in.get<int64_t>() != 0x56444220)  // "VDB "
        decline("not a VDB file");
    const uint32_t version = in.get<uint32_t>();
    if (version < 222 || version > 224)  // node-mask compression .. OpenVDB 11's format
        decline("file format " + std::to_string(version));
    in.take(8);  // library major and minor version
    if (in.get<uint8_t>() == 0)
        decline("no grid offsets");
    in.take(36);  // UUID
    in.skip_metadata();
    const int32_t count = in.get<int32_t>();
    if (count < 0)
        decline("a negative grid count");
    std::vector<Descriptor>& grids = state.grids;
    grids.resize(static_cast<size_t>(std::min(count, 1 << 16)));
    if (static_cast<int32_t>(grids.size()) != count)
        decline("too many grids");
    static const std::string kHalf = "_HalfFloat", kDensity = "density";
    for (Descriptor& d : grids) {
        d.name = in.string();
        d.type = in.string();
        if (d.type.size() > kHalf.size() &&
            d.type.compare(d.type.size() - kHalf.size(), kHalf.size(), kHalf) == 0) {
            d.half = true;
            d.type.resize(d.type.size() - kHalf.size());
        }
        d.instance = !in.string().empty();
        const auto grid = in.get<int64_t>(), block = in.get<int64_t>(), end = in.get<int64_t>();
        if (grid < 0 || block < grid || end < block || static_cast<uint64_t>(end) > file.size())
            decline("grid positions outside the file");
        d.grid = static_cast<uint64_t>(grid);
        d.block = static_cast<uint64_t>(block);
        d.end = static_cast<uint64_t>(end);
        if (d.name.find('\x1e') != std::string::npos)  // a suffixed duplicate name
            decline("several grids of one name");
    }
    // The grid vdb_read.cpp picks: the one named; else "density"; else the first float grid in
    // name order (OpenVDB's File::beginName iterates a map sorted by name).
    const Descriptor* d = nullptr;
    const std::string& name = wanted.empty() ? kDensity : wanted;
    for (const Descriptor& g : grids)
        if (g.name == name)
            d = &g;
    if (!d && wanted.empty()) {
        for (const Descriptor& g : grids)
            if (g.type == "Tree_float_5_4_3" && (!d || g.name < d->name))
                d = &g;
    }
    if (!d)
        decline("no such grid");
    if (d->type != "Tree_float_5_4_3" || d->half || d->instance)
        decline("grid type " + d->type + (d->half ? " (half)" : "") +
                (d->instance ? " (an instance)" : ""));

    LoadedGrid& loaded = state.loaded;
    Tree& tree = state.tree;
    loaded.grid_name = d->name;
    in.seek(d->grid);
    tree.where = (context.empty() ? path : context + ": " + path) + " grid \"" + d->name + "\"";
    tree.compression = in.get<uint32_t>();
    if (tree.compression & ~(kCompressZip | kCompressActiveMask | kCompressBlosc))
        decline("unknown compression flags");
    in.set_where(&tree.where);
    in.skip_metadata();
    loaded.index_to_world = read_transform(in);
    check_transform(loaded.index_to_world, tree.where);
    if (in.get<int32_t>() != 1)
        decline("a buffer count other than 1");
    const float background = in.get<float>();
    if (background != 0.0f)
        decline("a non-zero background");
    const uint32_t root_tiles = in.get<uint32_t>(), root_children = in.get<uint32_t>();
    for (uint32_t i = 0; i < root_tiles; ++i) {
        in.take(3 * sizeof(int32_t) + sizeof(float));
        if (in.get<uint8_t>() != 0)  // 4096³ voxels
            throw_input_error(tree.where + ": active tiles cover more than 2^27 voxels");
    }
    if (in.pos() > d->block)
        decline("the topology starts past the grid's data");
    tree.leaves.reserve((d->block - in.pos()) /
                        sizeof(VoxelBlock::active));  // a bound: 64-byte masks
    for (uint32_t i = 0; i < root_children; ++i) {
        int32_t o[3];
        std::memcpy(o, in.take(sizeof(o)), sizeof(o));
        if ((o[0] | o[1] | o[2]) & 4095)  // RootNode keys: origins of 4096³ children
            decline("a root child off the 4096-voxel lattice");
        read_internal<5>(in, tree, IVec3(o[0], o[1], o[2]), state.scratch);
    }
    if (read_hook())
        read_hook()(path, "topology");

    // Leaf values (LeafNode::readBuffers): found in order, then decompressed in parallel. The
    // value mask stored again here is skipped, as OpenVDB does on a seekable stream. OpenVDB
    // reads them from wherever the topology ended, not from the descriptor's block position:
    // node masks that claim leaves the file does not hold (a flipped bit) shift every leaf
    // after them, and the sizes read there are garbage. A chunk past the end of the file is an
    // input error then (Cursor::chunk: OpenVDB would allocate it), the rest is declined below.
    const size_t topology_end = in.pos();
    const size_t leaves = tree.leaves.size();
    std::string& shifted = state.shifted_where;
    shifted = tree.where + ": the node masks claim " + std::to_string(leaves) +
              " leaves, whose topology ends at byte " + std::to_string(topology_end) +
              ", not where the grid's data start (byte " + std::to_string(d->block) + ")";
    if (topology_end != d->block)
        in.set_where(&shifted);
    state.values_at.resize(leaves);
    for (size_t i = 0; i < leaves; ++i) {
        in.take(sizeof(VoxelBlock::active));
        state.values_at[i] = in.pos();
        skip_values(in, tree.compression, VoxelBlock::kVoxels, tree.leaves[i].active.data());
        expand_by_leaf(tree, tree.leaves[i]);
        tree.active_voxels += count_on(tree.leaves[i].active.data(), 8);
    }
    if (topology_end != d->block)
        decline("the topology does not end where the grid's data start");
    if (in.pos() != d->end)
        decline("the leaves do not end where the grid does");
    loaded.active_voxels = tree.active_voxels;
    loaded.active_tiles = tree.active_tiles;
    return tree.active_voxels != 0;
}

/// The leaves' values, decompressed in parallel into state.values, each worker under the
/// guard; false if the file was cut meanwhile.
bool read_leaf_values(const MappedFile& file, const SigbusGuard& guard, ReadState& state) {
    const Tree& tree = state.tree;
    const size_t leaves = tree.leaves.size();
    const size_t floats = leaves * VoxelBlock::kVoxels;
    // Zeroed pages (every float is written below anyway), 2 MiB-aligned as transparent huge
    // pages from the start: with new float[] and advice on its aligned middle only, the rest
    // faulted in 4 KiB at a time (~550 faults of the 256³ render's ~1300).
    state.values.resize(floats);
    std::atomic<bool> broken{false}, cut{false};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, leaves),
                      [&](const tbb::blocked_range<size_t>& r) {
                          float buffer[VoxelBlock::kVoxels];
                          const bool whole = guard.run([&] {
                              try {
                                  for (size_t i = r.begin(); i != r.end(); ++i) {
                                      Cursor c(file.data(), file.size(), state.values_at[i]);
                                      c.set_where(&tree.where);
                                      float* dest = state.values.data() + i * VoxelBlock::kVoxels;
                                      read_values(c, tree.compression, dest, VoxelBlock::kVoxels,
                                                  tree.leaves[i].active.data(), buffer);
                                  }
                              } catch (const Declined&) {
                                  broken = true;
                              }
                          });
                          if (!whole)
                              cut = true;
                      });
    if (broken && !cut)
        decline("a broken leaf");
    return !cut;
}

[[noreturn]] void file_cut(const MappedFile& file, const std::string& path,
                           const std::string& context) {
    throw_input_error((context.empty() ? path : context + ": " + path) +
                      ": the file was cut from " + std::to_string(file.size()) + " to " +
                      std::to_string(file.size_now()) +
                      " bytes while it was read (is another process writing it?)");
}

LoadedGrid read_grid(const std::string& path, const std::string& wanted,
                     const std::string& context) {
    const MappedFile file(path);
    const SigbusGuard guard(file.data(), file.size());
    ReadState state;
    bool any = false;
    if (!guard.run([&] { any = read_layout(file, path, wanted, context, state); }))
        file_cut(file, path, context);
    if (!any) {
        state.loaded.grid = std::make_shared<DensityGrid>();
        return std::move(state.loaded);
    }
    Tree& tree = state.tree;
    const glm::i64vec3 extent =
        glm::i64vec3(tree.box_max) - glm::i64vec3(tree.box_min) + glm::i64vec3(1);
    const glm::i64vec3 bricks =
        (extent + glm::i64vec3(2 + DensityGrid::kBrick - 1)) / glm::i64vec3(DensityGrid::kBrick);
    if (glm::any(glm::greaterThan(extent, glm::i64vec3(kMaxEdgeVoxels))) ||
        static_cast<uint64_t>(bricks.x * bricks.y) * static_cast<uint64_t>(bricks.z) >
            kMaxBrickSlots)
        throw_input_error(tree.where + ": the active voxels span " + std::to_string(extent.x) +
                          " x " + std::to_string(extent.y) + " x " + std::to_string(extent.z) +
                          " voxels, more than a grid may hold (2^24 per axis, 2^33 in all)");
    if (read_hook())
        read_hook()(path, "values");
    if (!read_leaf_values(file, guard, state))
        file_cut(file, path, context);
    const size_t leaves = tree.leaves.size();
    std::vector<VoxelBlock> blocks = std::move(tree.leaves);
    for (size_t i = 0; i < leaves; ++i)
        blocks[i].values = state.values.data() + i * VoxelBlock::kVoxels;
    blocks.insert(blocks.end(), tree.tiles.begin(), tree.tiles.end());
    DensityGridBuild built = DensityGridBuilder::build(tree.box_min, tree.box_max, blocks);
    if (built.has_invalid)
        decline("an invalid voxel");  // OpenVDB's path names it
    state.loaded.grid = std::move(built.grid);
    return std::move(state.loaded);
}

}  // namespace

std::optional<LoadedGrid> read_density_grid_direct(const std::string& path,
                                                   const std::string& grid_name,
                                                   std::string* why_not,
                                                   const std::string& context) {
    try {
        return read_grid(path, grid_name, context);
    } catch (const Declined& e) {
        if (why_not)
            *why_not = e.why;
        return std::nullopt;
    }
}

void set_direct_read_hook(std::function<void(const std::string& path, const char* stage)> hook) {
    read_hook() = std::move(hook);
}

}  // namespace kasumi
