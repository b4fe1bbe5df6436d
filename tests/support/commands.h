// Running external programs (Blender, POV-Ray, the built filmback) from the end-to-end tests.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace fb::test {

// For /bin/sh: '...' with each ' written as '\''.
std::string quoted(const std::filesystem::path& path);

std::string read_text(const std::filesystem::path& file);

// The executable `name` in a folder of PATH, if any.
std::optional<std::filesystem::path> find_on_path(const std::string& name);

// Runs a shell command with its output in `log`; returns the wall time, or throws
// std::runtime_error with the log's last lines.
double run_logged(const std::string& command, const std::filesystem::path& log);

}  // namespace fb::test
