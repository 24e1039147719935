// ros2msg schemas from the .msg files embedded at build time (src/CMakeLists.txt).
#include "sensor/ros2_schema.hpp"

#include <map>
#include <set>
#include <sstream>
#include <vector>

#include "vkfuse/core/error.hpp"

namespace vkfuse::sensor {
namespace {

// "package/Type" -> the .msg text.
const std::map<std::string_view, std::string_view>& msg_texts() {
    static const std::map<std::string_view, std::string_view> texts = {
#include "ros2_msg_texts.inc"
    };
    return texts;
}

const std::set<std::string_view> kPrimitives = {"bool",  "byte",   "char",   "int8",    "uint8",   "int16",
                                                "uint16", "int32", "uint32", "int64",   "uint64",  "float32",
                                                "float64", "string", "wstring"};

// "pkg/msg/T" and "pkg/T" -> "pkg/T".
std::string short_name(std::string_view type) {
    std::string name(type);
    if (const auto at = name.find("/msg/"); at != std::string::npos) name.erase(at, 4);
    return name;
}

// The message types a .msg text's fields use, as "package/Type", in order.
std::vector<std::string> uses(std::string_view package, std::string_view text) {
    std::vector<std::string> out;
    std::istringstream lines{std::string(text)};
    for (std::string line; std::getline(lines, line);) {
        line = line.substr(0, line.find('#'));
        std::istringstream words(line);
        std::string type, name;
        if (!(words >> type >> name) || name.find('=') != std::string::npos) continue;  // blank, or a constant
        type = type.substr(0, type.find('['));
        if (const auto bound = type.find("<="); bound != std::string::npos) type.erase(bound);
        if (kPrimitives.count(type)) continue;
        out.push_back(type.find('/') == std::string::npos ? std::string(package) + "/" + type : short_name(type));
    }
    return out;
}

std::string_view text_of(const std::string& name) {
    const auto it = msg_texts().find(name);
    if (it == msg_texts().end())
        throw Error(ErrorKind::InvalidArgument, "no ROS 2 message definition for " + name + " in vkfuse");
    return it->second;
}

}  // namespace

std::string ros2msg_schema(std::string_view type) {
    const std::string root = short_name(type);
    std::string schema(text_of(root));
    std::set<std::string> seen{root};
    std::vector<std::string> pending = uses(root.substr(0, root.find('/')), text_of(root));
    // Depth first, in the order fields name them, each type once.
    for (std::size_t i = 0; i < pending.size(); ++i) {
        const std::string name = pending[i];
        if (!seen.insert(name).second) continue;
        const std::string_view text = text_of(name);
        if (!schema.empty() && schema.back() != '\n') schema += '\n';
        schema += std::string(80, '=') + "\nMSG: " + name + "\n" + std::string(text);
        const std::vector<std::string> more = uses(name.substr(0, name.find('/')), text);
        pending.insert(pending.begin() + std::ptrdiff_t(i) + 1, more.begin(), more.end());
    }
    return schema;
}

}  // namespace vkfuse::sensor
