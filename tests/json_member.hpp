// json_member.hpp - a JSON object's member, or a test failure naming it.
#pragma once
#include <stdexcept>
#include <string>

#include "io/json_value.hpp"

namespace vkfuse::test {

inline const json::Value& member(const json::Value& v, const char* key) {
    const json::Value* m = v.find(key);
    if (!m) throw std::runtime_error(std::string("no member ") + key);
    return *m;
}

}  // namespace vkfuse::test
