// A harness's own folder under the temporary directory: the scene file each input is written to,
// the files a scene may reach for beside it, and files outside it that it must never read.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>

namespace fb::fuzz {

class ScratchFolder {
 public:
  // <temp>/filmback_fuzz_<name>_<pid>, emptied; removed again when the harness exits normally.
  explicit ScratchFolder(const std::string& name);
  ~ScratchFolder();
  ScratchFolder(const ScratchFolder&) = delete;
  ScratchFolder& operator=(const ScratchFolder&) = delete;

  // Writes `size` bytes to `relative` (folders created) and returns the full path.
  std::filesystem::path write(const std::string& relative, const uint8_t* data, size_t size) const;
  std::filesystem::path write(const std::string& relative, const std::string& text) const;
  // A symbolic link at `relative` pointing to `target` (as written).
  void link(const std::string& relative, const std::string& target) const;
  const std::filesystem::path& root() const { return root_; }

 private:
  std::filesystem::path root_;
};

}  // namespace fb::fuzz
