#include "core/content_hash.h"

#include "core/error.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <vector>

namespace kasumi {

namespace {

std::string hash_text(uint64_t hash) {
    char text[32];
    std::snprintf(text, sizeof text, "fnv1a64:%016llx", static_cast<unsigned long long>(hash));
    return text;
}

}  // namespace

uint64_t fnv1a64(const void* data, size_t size, uint64_t hash) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) {
        hash ^= bytes[i];
        hash *= 1099511628211ull;
    }
    return hash;
}

std::string file_content_hash(const std::string& path) {
    std::FILE* file = std::fopen(path.c_str(), "rb");
    if (file == nullptr)
        throw_input_error(path + ": cannot read: " + std::strerror(errno));
    std::vector<unsigned char> buffer(1 << 20);
    uint64_t hash = kFnv1a64Basis;
    size_t n = 0;
    while ((n = std::fread(buffer.data(), 1, buffer.size(), file)) > 0)
        hash = fnv1a64(buffer.data(), n, hash);
    const bool failed = std::ferror(file) != 0;
    std::fclose(file);
    if (failed)
        throw_input_error(path + ": read error");
    return hash_text(hash);
}

std::string text_content_hash(const std::string& text) {
    return hash_text(fnv1a64(text.data(), text.size()));
}

}  // namespace kasumi
