#include "vk/engine/kernel_interface.hpp"

#include <algorithm>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {
namespace {

// The few SPIR-V opcodes, decorations and storage classes read here.
constexpr std::uint32_t kMagic = 0x07230203;
constexpr std::uint32_t OpExecutionMode = 16, ExecutionModeLocalSize = 17, OpCapability = 17, CapabilityFloat16 = 9;
constexpr std::uint32_t OpStore = 62, OpCopyMemory = 63, OpAccessChain = 65, OpInBoundsAccessChain = 66,
                        OpPtrAccessChain = 67, OpAtomicStore = 228, OpAtomicFirst = 229, OpAtomicLast = 242,
                        OpAtomicFAddEXT = 6035;
constexpr std::uint32_t OpMemberName = 6;
constexpr std::uint32_t OpTypeInt = 21, OpTypeFloat = 22, OpTypeVector = 23, OpTypeStruct = 30, OpTypePointer = 32,
                        OpVariable = 59, OpDecorate = 71, OpMemberDecorate = 72;
constexpr std::uint32_t DecorationSpecId = 1, DecorationBinding = 33, DecorationOffset = 35;
constexpr std::uint32_t StoragePushConstant = 9, StoragePhysicalBuffer = 5349;

[[noreturn]] void bad(const std::string& why) { throw Error(ErrorKind::Device, "internal: kernel SPIR-V: " + why); }

// A literal string's bytes, nul-terminated, four to a word from the lowest-order byte.
std::string literal_string(const std::uint32_t* words, std::size_t count) {
    std::string s;
    for (std::size_t i = 0; i < count * 4; ++i) {
        const char c = char(words[i / 4] >> (8 * (i % 4)) & 0xffu);
        if (c == '\0') break;
        s += c;
    }
    return s;
}

}  // namespace

std::string_view to_string(PushType t) {
    switch (t) {
        case PushType::U32: return "uint";
        case PushType::I32: return "int";
        case PushType::F32: return "float";
        case PushType::Address: return "buffer address";
        case PushType::Other: break;
    }
    return "another type";
}

KernelInterface reflect_kernel(std::span<const std::uint32_t> spirv) {
    if (spirv.size() < 5 || spirv[0] != kMagic) bad("no SPIR-V header");
    std::map<std::uint32_t, std::uint32_t> type_bytes;         // every sized type seen
    std::map<std::uint32_t, PushType> scalar_types;            // the types a push member may have
    std::map<std::uint32_t, std::map<std::uint32_t, std::string>> member_names;  // struct -> member -> name
    std::array<std::uint32_t, 3> local_size{};
    std::map<std::uint32_t, std::vector<std::uint32_t>> members;  // struct id -> member types
    std::map<std::uint32_t, std::map<std::uint32_t, std::uint32_t>> offsets;  // struct -> member -> offset
    std::map<std::uint32_t, std::pair<std::uint32_t, std::uint32_t>> pointers;  // id -> (storage class, pointee)
    std::map<std::uint32_t, std::uint32_t> bindings;           // variable id -> binding
    std::uint32_t push_pointer = 0, invocations = 0;
    bool splits_products = false, float16_arithmetic = false;
    std::map<std::uint32_t, std::uint32_t> chain_base;  // access chain id -> the id it indexes
    std::set<std::uint32_t> stored;                      // pointers stored through (directly or by atomics)
    for (std::size_t at = 5; at < spirv.size();) {
        const std::uint32_t count = spirv[at] >> 16, op = spirv[at] & 0xffff;
        if (count == 0 || at + count > spirv.size()) bad("truncated instruction");
        const std::uint32_t* w = &spirv[at];
        if (op == OpAccessChain || op == OpInBoundsAccessChain || op == OpPtrAccessChain) {
            if (count >= 4) chain_base[w[2]] = w[3];
        } else if (op == OpStore || op == OpCopyMemory || op == OpAtomicStore) {
            if (count >= 2) stored.insert(w[1]);
        } else if ((op >= OpAtomicFirst && op <= OpAtomicLast) || op == OpAtomicFAddEXT) {
            if (count >= 4) stored.insert(w[3]);
        }
        switch (op) {
            case OpCapability:
                if (count >= 2 && w[1] == CapabilityFloat16) float16_arithmetic = true;
                break;
            case OpExecutionMode:
                if (count >= 6 && w[2] == ExecutionModeLocalSize) {
                    invocations = w[3] * w[4] * w[5];
                    local_size = {w[3], w[4], w[5]};
                }
                break;
            case OpMemberName:
                if (count >= 4) member_names[w[1]][w[2]] = literal_string(w + 3, count - 3);
                break;
            case OpTypeInt:
                type_bytes[w[1]] = w[2] / 8;
                if (count >= 4 && w[2] == 32) scalar_types[w[1]] = w[3] ? PushType::I32 : PushType::U32;
                break;
            case OpTypeFloat:
                type_bytes[w[1]] = w[2] / 8;
                if (w[2] == 32) scalar_types[w[1]] = PushType::F32;
                break;
            case OpTypeVector:
                if (type_bytes.count(w[2])) type_bytes[w[1]] = type_bytes[w[2]] * w[3];
                break;
            case OpTypeStruct: members[w[1]].assign(w + 2, w + count); break;
            case OpTypePointer:
                pointers[w[1]] = {w[2], w[3]};
                if (w[2] == StoragePhysicalBuffer) {
                    type_bytes[w[1]] = 8;
                    scalar_types[w[1]] = PushType::Address;
                }
                break;
            case OpVariable:
                if (w[3] == StoragePushConstant) push_pointer = w[1];
                break;
            case OpDecorate:
                if (count >= 4 && w[2] == DecorationBinding) bindings[w[1]] = w[3];
                if (count >= 4 && w[2] == DecorationSpecId && w[3] == kSplitProductsConstant) splits_products = true;
                break;
            case OpMemberDecorate:
                if (count >= 5 && w[3] == DecorationOffset) offsets[w[1]][w[2]] = w[4];
                break;
            default: break;
        }
        at += count;
    }
    KernelInterface k;
    k.invocations = invocations;
    k.local_size = local_size;
    k.splits_products = splits_products;
    k.float16_arithmetic = float16_arithmetic;
    for (std::uint32_t pointer : stored) {
        for (int depth = 0; depth < 64 && chain_base.count(pointer); ++depth) pointer = chain_base[pointer];
        if (const auto b = bindings.find(pointer); b != bindings.end()) k.written |= 1u << b->second;
    }
    std::set<std::uint32_t> used;
    for (const auto& [variable, binding] : bindings) used.insert(binding);
    k.bindings = std::uint32_t(used.size());
    if (!used.empty() && *used.rbegin() + 1 != k.bindings) bad("bindings are not 0 .. n-1");
    if (push_pointer) {
        const auto p = pointers.find(push_pointer);
        if (p == pointers.end() || !members.count(p->second.second)) bad("push constants are not a block");
        const std::uint32_t block = p->second.second;
        const auto& types = members[block];
        for (std::uint32_t m = 0; m < types.size(); ++m) {
            const auto size = type_bytes.find(types[m]);
            const auto offset = offsets[block].find(m);
            if (size == type_bytes.end() || offset == offsets[block].end()) bad("push constant member of unknown size");
            k.push_bytes = std::max(k.push_bytes, offset->second + size->second);
            const auto type = scalar_types.find(types[m]);
            k.push.push_back({member_names[block][m], type == scalar_types.end() ? PushType::Other : type->second,
                              offset->second});
        }
    }
    return k;
}

}  // namespace vkfuse::vk
