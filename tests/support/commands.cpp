#include "tests/support/commands.h"

#include <sys/wait.h>

#include <chrono>
#include <cstdlib>
#include <deque>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace fb::test {
namespace {

namespace fs = std::filesystem;

std::string last_lines(const std::string& text, size_t count) {
  std::istringstream in(text);
  std::deque<std::string> lines;
  for (std::string line; std::getline(in, line);) {
    lines.push_back(line);
    if (lines.size() > count) lines.pop_front();
  }
  std::string out;
  for (const std::string& line : lines)
    out += line + "\n";
  return out;
}

}  // namespace

std::string quoted(const fs::path& path) {
  std::string out = "'";
  for (char c : path.string())
    out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::optional<fs::path> find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  std::string rest = path ? path : "";
  while (!rest.empty()) {
    const size_t colon = rest.find(':');
    const fs::path candidate = fs::path(rest.substr(0, colon)) / name;
    std::error_code ec;
    if (fs::is_regular_file(candidate, ec)) return candidate;
    rest = colon == std::string::npos ? "" : rest.substr(colon + 1);
  }
  return std::nullopt;
}

double run_logged(const std::string& command, const fs::path& log) {
  const auto start = std::chrono::steady_clock::now();
  const int status = std::system((command + " > " + quoted(log) + " 2>&1").c_str());
  const std::chrono::duration<double> seconds = std::chrono::steady_clock::now() - start;
  if (status == -1 || !WIFEXITED(status) || WEXITSTATUS(status) != 0)
    throw std::runtime_error("command failed (status " + std::to_string(status) + "): " + command +
                             "\nlast lines of " + log.string() + ":\n" +
                             last_lines(read_text(log), 30));
  return seconds.count();
}

}  // namespace fb::test
