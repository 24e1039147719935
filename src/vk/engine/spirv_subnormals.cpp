#include "vk/engine/spirv_subnormals.hpp"

#include <string>

#include "vkfuse/core/error.hpp"

namespace vkfuse::vk {
namespace {

// SPIR-V's numbers for what the patch reads and writes (the SPIR-V
// specification, section 3).
constexpr std::uint32_t kMagic = 0x07230203;
constexpr std::size_t kHeaderWords = 5;
constexpr std::uint32_t kOpExtension = 10, kOpEntryPoint = 15, kOpExecutionMode = 16, kOpCapability = 17;
constexpr std::uint32_t kCapabilityDenormPreserve = 4464;
constexpr std::uint32_t kModeDenormPreserve = 4459;
constexpr std::uint32_t kVersion14 = 0x00010400;
constexpr char kExtension[] = "SPV_KHR_float_controls";

std::uint32_t instruction(std::uint32_t opcode, std::size_t words) { return std::uint32_t(words) << 16 | opcode; }

[[noreturn]] void malformed(const std::string& what) {
    throw Error(ErrorKind::Device, "SPIR-V module: " + what + " (an embedded kernel is damaged)");
}

}  // namespace

std::vector<std::uint32_t> preserving_subnormals(std::span<const std::uint32_t> spirv) {
    if (spirv.size() < kHeaderWords || spirv[0] != kMagic) malformed("no SPIR-V header");
    // One walk over the module's instructions, noting where each section the
    // patch adds to ends.
    std::size_t after_capabilities = kHeaderWords, after_entry_points = 0;
    std::vector<std::uint32_t> entry_points;
    for (std::size_t at = kHeaderWords; at < spirv.size();) {
        const std::uint32_t opcode = spirv[at] & 0xffffu, words = spirv[at] >> 16;
        if (words == 0 || at + words > spirv.size()) malformed("an instruction runs past the module's end");
        if (opcode == kOpCapability && words == 2) {
            if (spirv[at + 1] == kCapabilityDenormPreserve) return {spirv.begin(), spirv.end()};
            after_capabilities = at + words;
        }
        if (opcode == kOpEntryPoint) {
            if (words < 3) malformed("a short OpEntryPoint");
            entry_points.push_back(spirv[at + 2]);
            after_entry_points = at + words;
        }
        if (opcode == kOpExecutionMode && words >= 3 && spirv[at + 2] == kModeDenormPreserve)
            return {spirv.begin(), spirv.end()};
        at += words;
    }
    if (entry_points.empty()) malformed("no entry point");

    std::vector<std::uint32_t> out;
    out.reserve(spirv.size() + 16 + 4 * entry_points.size());
    out.insert(out.end(), spirv.begin(), spirv.begin() + std::ptrdiff_t(after_capabilities));
    out.push_back(instruction(kOpCapability, 2));
    out.push_back(kCapabilityDenormPreserve);
    if (spirv[1] < kVersion14) {  // the extension became core in SPIR-V 1.4
        // A literal string: its bytes, nul-terminated, four to a word from
        // the lowest-order byte.
        std::uint32_t name[(sizeof kExtension + 3) / 4] = {};
        for (std::size_t i = 0; i < sizeof kExtension; ++i)
            name[i / 4] |= std::uint32_t(static_cast<unsigned char>(kExtension[i])) << (8 * (i % 4));
        out.push_back(instruction(kOpExtension, 1 + std::size(name)));
        out.insert(out.end(), std::begin(name), std::end(name));
    }
    out.insert(out.end(), spirv.begin() + std::ptrdiff_t(after_capabilities),
               spirv.begin() + std::ptrdiff_t(after_entry_points));
    for (std::uint32_t id : entry_points) {
        out.push_back(instruction(kOpExecutionMode, 4));
        out.push_back(id);
        out.push_back(kModeDenormPreserve);
        out.push_back(32);  // the float width it applies to
    }
    out.insert(out.end(), spirv.begin() + std::ptrdiff_t(after_entry_points), spirv.end());
    return out;
}

}  // namespace vkfuse::vk
