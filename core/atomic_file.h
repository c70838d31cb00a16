#pragma once
/// Atomic file replacement: write under a temporary name in the destination's directory, then
/// rename over the destination, so a reader (or a crash) never sees a half-written file.
#include <cstddef>
#include <string>

namespace kasumi {

/// One pending atomic write of `path`. The constructor creates an empty, uniquely named
/// temporary `<dir>/.<name>.<pid>.<n>.tmp` beside `path` (throws ErrorKind::Output naming `path`
/// if it cannot); the caller fills `temp_path()` and calls commit(). If commit() is never
/// reached (an exception unwinds), the destructor removes the temporary.
class AtomicFile {
  public:
    explicit AtomicFile(const std::string& path);
    ~AtomicFile();
    AtomicFile(const AtomicFile&) = delete;
    AtomicFile& operator=(const AtomicFile&) = delete;

    const std::string& path() const { return m_path; }
    const std::string& temp_path() const { return m_temp_path; }

    /// Flushes the temporary to disk and renames it to path(); throws ErrorKind::Output naming
    /// path() on failure (the temporary is then removed).
    void commit();

  private:
    std::string m_path;
    std::string m_temp_path;
    bool m_committed = false;
};

/// Writes `size` bytes to `path` atomically (see AtomicFile); throws ErrorKind::Output.
void write_file_atomic(const std::string& path, const void* data, size_t size);

}  // namespace kasumi
