#pragma once
/// Whole text files read into memory, for the parsers that take their input as one string.
#include <string>

namespace kasumi {

/// The bytes of the file at `path`, unchanged (binary mode). Throws an input error
/// "<path>: cannot open <what>" when the file cannot be opened.
std::string read_text_file(const std::string& path, const std::string& what);

}  // namespace kasumi
