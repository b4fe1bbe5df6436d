#include "core/plugin/abi_layout.h"

namespace fb {

std::string check_size(const char* what, uint32_t size, uint32_t first, uint32_t host) {
  if (size > host)
    return std::string("plugin newer than this filmback: its ") + what + " is " +
           std::to_string(size) + " bytes, this filmback's is " + std::to_string(host) +
           " (update filmback, or rebuild the plugin against this SDK)";
  if (size < first)
    return std::string("plugin older than any layout this filmback reads: its ") + what + " is " +
           std::to_string(size) + " bytes, the first published layout's is " +
           std::to_string(first) + " (rebuild it against this SDK)";
  return {};
}

}  // namespace fb
