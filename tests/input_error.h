#pragma once
// Shared by the test folders: the message of the input error a call throws, or the kind of
// any kasumi::Error it throws.
#include "core/error.h"

#include <gtest/gtest.h>

#include <string>

namespace kasumi {

/// The message of the input error (exit code 3) `f` throws, or "" when it throws none.
template <typename F>
std::string input_error(F f) {
    try {
        f();
    } catch (const Error& e) {
        EXPECT_EQ(e.exit_code(), 3);
        return e.what();
    }
    return "";
}

/// The kind of the kasumi::Error `f` throws (its message into `message` if given); a test
/// failure and ErrorKind::Runtime when it throws none.
template <typename F>
ErrorKind error_kind_of(F&& f, std::string* message = nullptr) {
    try {
        f();
    } catch (const Error& e) {
        if (message)
            *message = e.what();
        return e.kind();
    }
    ADD_FAILURE() << "no kasumi::Error thrown";
    return ErrorKind::Runtime;
}

}  // namespace kasumi
