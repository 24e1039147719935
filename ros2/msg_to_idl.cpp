// msg_to_idl: the .msg files of a ROS 2 interface package as the DDS IDL that
// ROS 2 puts on the wire, for Cyclone DDS's idlc. Run by the build, so the
// messages are declared once (ros2/vkfuse_msgs/msg) and their DDS form
// derives from them.
//
//   msg_to_idl OUT.idl PACKAGE A.msg [B.msg ...]
//
// ROS 2 (rmw_cyclonedds_cpp, rmw_fastrtps) names message pkg/msg/T the DDS
// type pkg::msg::dds_::T_, sends plain CDR (XCDR1) of final structs, and maps
// the field types as rosidl_adapter does: byte -> octet, char -> uint8,
// float32/64 -> float/double, T[] and T[<=N] -> sequence<T> / sequence<T, N>,
// T[N] -> an array, string<=N -> string<N>. Constants become
// `module T_Constants { const ... }`. Other packages' types come from
// "<pkg>.idl" (ros2/idl), included; this package's structs are written in
// dependency order. Anything else in a .msg is refused with its file and line.
#include <algorithm>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

struct Field {
    std::string type;  // IDL element type
    std::string name;
    std::string array;  // "", "[]", "[<=N]" or "[N]"
};
struct Constant {
    std::string type, name, value;
};
struct Message {
    std::string name;
    std::vector<Field> fields;
    std::vector<Constant> constants;
    std::set<std::string> uses;  // this package's messages it holds
};

const std::map<std::string, std::string> kPrimitives = {
    {"bool", "boolean"}, {"byte", "octet"},    {"char", "uint8"},     {"int8", "int8"},
    {"uint8", "uint8"},  {"int16", "short"},   {"uint16", "unsigned short"},
    {"int32", "long"},   {"uint32", "unsigned long"}, {"int64", "long long"},
    {"uint64", "unsigned long long"}, {"float32", "float"}, {"float64", "double"}, {"string", "string"}};

[[noreturn]] void fail(const std::string& where, const std::string& what) {
    throw std::runtime_error(where + ": " + what);
}

// IDL 4.2's keywords (7.2.4), which idlc refuses as names whatever their case.
const std::set<std::string> kIdlKeywords = {
    "abstract", "any", "alias", "attribute", "bitfield", "bitmask", "bitset", "boolean", "case", "char", "component",
    "connector", "const", "consumes", "context", "custom", "default", "double", "exception", "emits", "enum",
    "eventtype", "factory", "false", "finder", "fixed", "float", "getraises", "getter", "home", "import", "in",
    "inout", "interface", "local", "long", "manages", "map", "mirrorport", "module", "multiple", "native", "object",
    "octet", "oneway", "out", "primarykey", "private", "port", "porttype", "provides", "public", "publishes",
    "raises", "readonly", "setraises", "setter", "sequence", "short", "string", "struct", "supports", "switch",
    "true", "truncatable", "typedef", "typeid", "typename", "typeprefix", "unsigned", "union", "uses", "valuebase",
    "valuetype", "void", "wchar", "wstring", "int8", "uint8", "int16", "int32", "int64", "uint16", "uint32", "uint64"};

bool is_idl_keyword(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return kIdlKeywords.count(s) > 0;
}

bool is_name(const std::string& s) {
    return !s.empty() && std::isalpha(static_cast<unsigned char>(s[0])) &&
           std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
}

// The IDL type of a .msg element type (without its array suffix); a type of
// this package is noted in `uses`, another package's in `packages`.
std::string idl_type(const std::string& type, const std::string& package, Message& m, std::set<std::string>& packages,
                     const std::string& where) {
    if (auto p = kPrimitives.find(type); p != kPrimitives.end()) return p->second;
    if (type.rfind("string<=", 0) == 0) {
        const std::string bound = type.substr(8);
        if (bound.empty() || !std::all_of(bound.begin(), bound.end(), ::isdigit)) fail(where, "bad string bound " + type);
        return "string<" + bound + ">";
    }
    std::string pkg = package, name = type;
    if (const auto slash = type.find('/'); slash != std::string::npos) {
        pkg = type.substr(0, slash);
        name = type.substr(slash + 1);
    } else if (type == "Header") {
        pkg = "std_msgs";  // the one type .msg files may name without its package
    }
    if (!is_name(pkg) || !is_name(name)) fail(where, "unknown type " + type);
    if (pkg == package)
        m.uses.insert(name);
    else
        packages.insert(pkg);
    return pkg + "::msg::dds_::" + name + "_";
}

Message parse(const std::string& path, const std::string& package, std::set<std::string>& packages) {
    std::ifstream in(path);
    if (!in) fail(path, "cannot read");
    Message m;
    const auto slash = path.find_last_of('/');
    m.name = path.substr(slash == std::string::npos ? 0 : slash + 1);
    if (m.name.size() < 5 || m.name.substr(m.name.size() - 4) != ".msg") fail(path, "not a .msg file");
    m.name.resize(m.name.size() - 4);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        const std::string where = path + ":" + std::to_string(n);
        if (const auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
        std::istringstream words(line);
        std::string type, rest;
        if (!(words >> type)) continue;
        std::getline(words, rest);
        rest.erase(0, rest.find_first_not_of(" \t"));
        rest.erase(rest.find_last_not_of(" \t\r") + 1);
        std::string array;
        if (const auto bracket = type.find('['); bracket != std::string::npos) {
            array = type.substr(bracket);
            type.resize(bracket);
            if (array.back() != ']') fail(where, "bad array " + array);
        }
        if (const auto eq = rest.find('='); eq != std::string::npos) {  // a constant: TYPE NAME=VALUE
            std::string name = rest.substr(0, eq), value = rest.substr(eq + 1);
            name.erase(name.find_last_not_of(" \t") + 1);
            value.erase(0, value.find_first_not_of(" \t"));
            if (!array.empty() || !is_name(name) || value.empty() || !kPrimitives.count(type) || type == "string")
                fail(where, "unsupported constant '" + line + "'");
            m.constants.push_back({kPrimitives.at(type), name, value});
            continue;
        }
        std::istringstream names(rest);
        std::string name, extra;
        names >> name;
        if (!is_name(name)) fail(where, "bad field name in '" + line + "'");
        if (is_idl_keyword(name)) fail(where, "field name " + name + " is an IDL keyword");
        if (names >> extra) fail(where, "default values are not supported: '" + line + "'");
        m.fields.push_back({idl_type(type, package, m, packages, where), name, array});
    }
    return m;
}

std::string member(const Field& f, const std::string& where) {
    if (f.array.empty()) return f.type + " " + f.name + ";";
    if (f.array == "[]") return "sequence<" + f.type + "> " + f.name + ";";
    const bool bounded = f.array.rfind("[<=", 0) == 0;
    const std::string n = f.array.substr(bounded ? 3 : 1, f.array.size() - (bounded ? 4 : 2));
    if (n.empty() || !std::all_of(n.begin(), n.end(), ::isdigit)) fail(where, "bad array " + f.array);
    return bounded ? "sequence<" + f.type + ", " + n + "> " + f.name + ";" : f.type + " " + f.name + "[" + n + "];";
}

// This package's messages, each after those it holds.
std::vector<const Message*> in_dependency_order(const std::vector<Message>& messages) {
    std::map<std::string, const Message*> by_name;
    for (const Message& m : messages) by_name[m.name] = &m;
    std::vector<const Message*> order;
    std::set<std::string> done, visiting;
    auto visit = [&](auto&& self, const Message& m) -> void {
        if (done.count(m.name)) return;
        if (!visiting.insert(m.name).second) fail(m.name + ".msg", "holds itself through its fields");
        for (const std::string& used : m.uses) {
            const auto it = by_name.find(used);
            if (it == by_name.end()) fail(m.name + ".msg", "uses " + used + ", which is not among the package's messages");
            self(self, *it->second);
        }
        visiting.erase(m.name);
        done.insert(m.name);
        order.push_back(&m);
    };
    for (const Message& m : messages) visit(visit, m);
    return order;
}

}  // namespace

int main(int argc, char** argv) {
    if (argc < 4) {
        std::cerr << "usage: msg_to_idl OUT.idl PACKAGE A.msg [B.msg ...]\n";
        return 2;
    }
    try {
        const std::string out_path = argv[1], package = argv[2];
        std::set<std::string> packages;
        std::vector<Message> messages;
        for (int i = 3; i < argc; ++i) messages.push_back(parse(argv[i], package, packages));
        std::ostringstream idl;
        idl << "// Generated by ros2/msg_to_idl.cpp from the .msg files of " << package << ": do not edit.\n";
        for (const std::string& p : packages) idl << "#include \"" << p << ".idl\"\n";
        idl << "module " << package << " { module msg { module dds_ {\n";
        for (const Message* m : in_dependency_order(messages)) {
            if (!m->constants.empty()) {
                idl << "    module " << m->name << "_Constants {\n";
                for (const Constant& c : m->constants)
                    idl << "        const " << c.type << " " << c.name << " = " << c.value << ";\n";
                idl << "    };\n";
            }
            idl << "    struct " << m->name << "_ {\n";
            for (const Field& f : m->fields) idl << "        " << member(f, m->name + ".msg") << "\n";
            idl << "    };\n";
        }
        idl << "}; }; };\n";
        std::ofstream out(out_path);
        out << idl.str();
        if (!out.flush()) throw std::runtime_error(out_path + ": cannot write");
    } catch (const std::exception& e) {
        std::cerr << "msg_to_idl: " << e.what() << "\n";
        return 1;
    }
    return 0;
}
