#pragma once
// The one VkResult checker (docs/design.md §5): every Vulkan call that returns a VkResult goes through
// DS_VK, which throws dicsynth::Error naming the call, the result and the file:line of the call.
#include <vulkan/vulkan.h>

#include <source_location>
#include <string>

namespace dicsynth::gpu {

// "VK_ERROR_DEVICE_LOST", …; "VkResult(<n>)" for codes this build does not know.
std::string vkResultName(VkResult result);

// Throws Error("<callText> failed: <result name>") when result is an error code (< 0); success codes
// (VK_SUCCESS, VK_TIMEOUT, VK_INCOMPLETE, …) are returned for the caller to inspect.
VkResult checkVk(VkResult result, const char* callText,
                 std::source_location here = std::source_location::current());

}  // namespace dicsynth::gpu

#define DS_VK(call) ::dicsynth::gpu::checkVk((call), #call)
