#include "core/atomic_file.h"

#include "core/error.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>

namespace kasumi {
namespace {

std::string errno_text(int err) {
    return std::strerror(err);
}

std::string make_temp_path(const std::string& path) {
    static std::atomic<unsigned> counter{0};
    const size_t slash = path.find_last_of('/');
    const std::string dir = slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
    const std::string name = slash == std::string::npos ? path : path.substr(slash + 1);
    return dir + "." + name + "." + std::to_string(::getpid()) + "." +
           std::to_string(counter.fetch_add(1)) + ".tmp";
}

}  // namespace

AtomicFile::AtomicFile(const std::string& path) : m_path(path) {
    if (path.empty() || path.back() == '/')
        throw_output_error("'" + path + "': not a file name");
    // The rename would replace a device, FIFO or socket with a regular file (as root, `-o
    // /dev/null` would delete the device node): refuse instead. A symbolic link is replaced
    // itself, never its target, so it is allowed.
    struct stat existing;
    if (::lstat(path.c_str(), &existing) == 0 && !S_ISREG(existing.st_mode) &&
        !S_ISLNK(existing.st_mode) && !S_ISDIR(existing.st_mode)) {
        throw_output_error(path +
                           ": not a regular file (a device, FIFO or socket); outputs are "
                           "written to a temporary file renamed over the destination");
    }
    // O_EXCL: never adopt (and later rename) a file someone else is writing.
    for (int attempt = 0;; ++attempt) {
        m_temp_path = make_temp_path(path);
        const int fd = ::open(m_temp_path.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
        if (fd >= 0) {
            ::close(fd);
            return;
        }
        const int err = errno;
        if (err != EEXIST || attempt >= 100)
            throw_output_error(path +
                               ": cannot create a temporary file beside it: " + errno_text(err));
    }
}

AtomicFile::~AtomicFile() {
    if (!m_committed)
        ::unlink(m_temp_path.c_str());
}

void AtomicFile::commit() {
    // fsync before rename: after a crash the destination holds the old or the new file, never
    // a renamed but still empty one.
    const int fd = ::open(m_temp_path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0 || ::fsync(fd) != 0) {
        const int err = errno;
        if (fd >= 0)
            ::close(fd);
        throw_output_error(m_path + ": cannot flush the written file: " + errno_text(err));
    }
    ::close(fd);
    if (std::rename(m_temp_path.c_str(), m_path.c_str()) != 0)
        throw_output_error(m_path +
                           ": cannot rename the temporary file into place: " + errno_text(errno));
    m_committed = true;
}

void write_file_atomic(const std::string& path, const void* data, size_t size) {
    AtomicFile file(path);
    std::FILE* f = std::fopen(file.temp_path().c_str(), "wb");
    if (!f)
        throw_output_error(path + ": cannot open for writing: " + errno_text(errno));
    const bool written = std::fwrite(data, 1, size, f) == size;
    const int write_err = errno;
    const bool closed = std::fclose(f) == 0;
    if (!written || !closed)
        throw_output_error(path + ": write failed: " + errno_text(written ? errno : write_err));
    file.commit();
}

}  // namespace kasumi
