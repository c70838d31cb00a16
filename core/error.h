#pragma once
/// The project's one error type. Library code throws it for input and I/O errors at load or
/// write time; hot loops never throw. Only apps/ catches it and maps its kind to an exit code.
#include <stdexcept>
#include <string>

namespace kasumi {

/// What went wrong, which decides the CLI exit code (see README "Exit codes").
enum class ErrorKind {
    Runtime = 1,     ///< an internal failure
    Usage = 2,       ///< bad command-line arguments
    Input = 3,       ///< invalid scene or input file
    Output = 4,      ///< cannot write output
    Validation = 5,  ///< a validation check failed
};

class Error : public std::runtime_error {
  public:
    Error(ErrorKind kind, const std::string& message) : std::runtime_error(message), m_kind(kind) {}
    ErrorKind kind() const { return m_kind; }
    int exit_code() const { return static_cast<int>(m_kind); }

  private:
    ErrorKind m_kind;
};

[[noreturn]] inline void throw_input_error(const std::string& message) {
    throw Error(ErrorKind::Input, message);
}
[[noreturn]] inline void throw_output_error(const std::string& message) {
    throw Error(ErrorKind::Output, message);
}

[[noreturn]] void check_failed(const char* condition, const char* file, int line);

}  // namespace kasumi

/// An invariant that is always checked (not for hot loops: use KASUMI_DCHECK there).
#define KASUMI_CHECK(cond)                                     \
    do {                                                       \
        if (!(cond))                                           \
            ::kasumi::check_failed(#cond, __FILE__, __LINE__); \
    } while (false)

#ifdef NDEBUG
#define KASUMI_DCHECK(cond) \
    do {                    \
    } while (false)
#else
#define KASUMI_DCHECK(cond) KASUMI_CHECK(cond)
#endif
