#include "tests/fuzz/scratch_folder.h"

#include <unistd.h>

#include <fstream>

namespace fb::fuzz {

namespace fs = std::filesystem;

ScratchFolder::ScratchFolder(const std::string& name)
    : root_(fs::temp_directory_path() /
            ("filmback_fuzz_" + name + "_" + std::to_string(getpid()))) {
  fs::remove_all(root_);
  fs::create_directories(root_);
}

ScratchFolder::~ScratchFolder() {
  std::error_code ec;
  fs::remove_all(root_, ec);
}

fs::path ScratchFolder::write(const std::string& relative, const uint8_t* data, size_t size) const {
  const fs::path path = root_ / relative;
  fs::create_directories(path.parent_path());
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

fs::path ScratchFolder::write(const std::string& relative, const std::string& text) const {
  return write(relative, reinterpret_cast<const uint8_t*>(text.data()), text.size());
}

void ScratchFolder::link(const std::string& relative, const std::string& target) const {
  const fs::path path = root_ / relative;
  fs::create_directories(path.parent_path());
  std::error_code ec;
  fs::remove(path, ec);
  fs::create_symlink(target, path);
}

}  // namespace fb::fuzz
