// One shared library opened at run time: the plugin loader's (core/plugin/loader.cpp) and the
// subdivision module's (core/subdiv/subdiv_loader.cpp). Each caller words its own errors; this
// keeps the one way filmback asks the dynamic loader.
#pragma once

#include <filesystem>
#include <string>

namespace fb {

class SharedLibrary {
 public:
  // Opens `file` with RTLD_NOW | RTLD_LOCAL: every symbol the library needs is bound now, so a
  // missing one is reported when it is opened, naming the file, not at its first call; and its
  // own symbols stay local, so that every plugin may export the same entry point. Never throws:
  // see is_open() and error().
  explicit SharedLibrary(const std::filesystem::path& file);
  ~SharedLibrary();  // closes it
  SharedLibrary(SharedLibrary&& other) noexcept;
  SharedLibrary& operator=(SharedLibrary&& other) noexcept;
  SharedLibrary(const SharedLibrary&) = delete;
  SharedLibrary& operator=(const SharedLibrary&) = delete;

  bool is_open() const { return handle_ != nullptr; }
  // Why it did not open: the dynamic loader's reason, without the path it starts with (the
  // caller's message names the file already).
  const std::string& error() const { return error_; }
  // The address of an exported symbol, or nullptr when the library has none.
  void* symbol(const char* name) const;

 private:
  void* handle_ = nullptr;
  std::string error_;
};

}  // namespace fb
