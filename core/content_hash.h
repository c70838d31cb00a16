#pragma once
/// Content hashes of files: 64-bit FNV-1a (Fowler, Noll & Vo; offset basis 14695981039346656037,
/// prime 1099511628211). Not cryptographic: it detects accidental change (a flipped bit, a
/// truncated or replaced file), which is what a sequence manifest checks.
#include <cstddef>
#include <cstdint>
#include <string>

namespace kasumi {

/// FNV-1a 64 of `size` bytes, continuing from `hash` (start with kFnv1a64Basis).
inline constexpr uint64_t kFnv1a64Basis = 14695981039346656037ull;
uint64_t fnv1a64(const void* data, size_t size, uint64_t hash = kFnv1a64Basis);

/// "fnv1a64:" and 16 lower-case hex digits of the hash of `path`'s bytes. Throws
/// ErrorKind::Input naming `path` if it cannot be read.
std::string file_content_hash(const std::string& path);

/// The same text for the hash of a string (a document's JSON text).
std::string text_content_hash(const std::string& text);

}  // namespace kasumi
