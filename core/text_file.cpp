#include "core/text_file.h"

#include "core/error.h"

#include <fstream>
#include <sstream>

namespace kasumi {

std::string read_text_file(const std::string& path, const std::string& what) {
    std::ifstream in(path, std::ios::binary);
    if (!in)
        throw_input_error(path + ": cannot open " + what);
    std::ostringstream text;
    text << in.rdbuf();
    return text.str();
}

}  // namespace kasumi
