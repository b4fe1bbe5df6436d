#include "core/cmd/bench_system.h"

#include <cstdlib>
#include <ctime>
#include <fstream>
#include <sstream>
#include <thread>

namespace fb {
namespace {

// "VmRSS:     12345 kB" -> bytes.
std::optional<size_t> status_kib(const std::string& text, const std::string& key) {
  const size_t at = text.find("\n" + key + ":");
  if (at == std::string::npos) return std::nullopt;
  std::istringstream in(text.substr(at + key.size() + 2));
  size_t kib = 0;
  if (!(in >> kib)) return std::nullopt;
  return kib * 1024;
}

}  // namespace

std::optional<ResidentSet> resident_set() {
  std::ifstream in("/proc/self/status");
  std::stringstream text;
  text << "\n" << in.rdbuf();
  const auto current = status_kib(text.str(), "VmRSS"), peak = status_kib(text.str(), "VmHWM");
  if (!current || !peak) return std::nullopt;
  return ResidentSet{*current, *peak};
}

bool restart_peak_resident_set() {
  std::ofstream out("/proc/self/clear_refs");
  out << "5";
  out.close();
  return bool(out);
}

std::string processor_description() {
  std::ifstream in("/proc/cpuinfo");
  std::string model = "unknown processor";
  for (std::string line; std::getline(in, line);)
    if (line.rfind("model name", 0) == 0 && line.find(':') != std::string::npos) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " logical CPUs";
}

std::optional<double> load_average() {
  double load[1];
  if (getloadavg(load, 1) != 1) return std::nullopt;
  return load[0];
}

std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%d %H:%M UTC", &utc);
  return text;
}

}  // namespace fb
