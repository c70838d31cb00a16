#include "volume/grid/vdb_mapped_file.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

namespace kasumi::vdb_file {

void decline(std::string why) {
    throw Declined{std::move(why)};
}

MappedFile::MappedFile(const std::string& path) {
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

MappedFile::~MappedFile() {
    if (m_data)
        ::munmap(const_cast<uint8_t*>(m_data), m_size);
    if (m_fd >= 0)
        ::close(m_fd);
}

uint64_t MappedFile::size_now() const {
    struct stat st {};
    return ::fstat(m_fd, &st) == 0 ? static_cast<uint64_t>(st.st_size) : 0;
}

}  // namespace kasumi::vdb_file
