// expect_error.hpp - what every failure test checks about a vkfuse::Error.
#pragma once
#include <gtest/gtest.h>

#include <string>

#include "vkfuse/core/error.hpp"
#include "vkfuse/core/io.hpp"

namespace vkfuse::test {

// call must throw an Error of kind whose message is one line starting with
// "<subject>: " and containing fragment.
template <class F>
void expect_error(F&& call, const std::string& subject, ErrorKind kind, const std::string& fragment) {
    try {
        call();
        ADD_FAILURE() << "no Error for " << subject;
    } catch (const Error& e) {
        std::string what = e.what();
        EXPECT_EQ(e.kind(), kind) << what;
        EXPECT_EQ(what.rfind(subject + ": ", 0), 0u) << what;
        EXPECT_NE(what.find(fragment), std::string::npos) << what;
        EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
}

inline void expect_read_error(const std::string& path, ErrorKind kind, const std::string& fragment) {
    expect_error([&] { io::read_image(path); }, path, kind, fragment);
}

}  // namespace vkfuse::test
