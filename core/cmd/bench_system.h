// What `filmback bench` reports about the machine and the process: memory from the kernel's own
// accounting, the processor and the load.
#pragma once

#include <cstddef>
#include <optional>
#include <string>

namespace fb {

// Resident set size now and its peak (/proc/self/status VmRSS and VmHWM), bytes.
struct ResidentSet {
  size_t current = 0, peak = 0;
};
std::optional<ResidentSet> resident_set();

// Restarts the peak at the current size (/proc/self/clear_refs "5", Linux 4.0 and later), so the
// next peak is the scene's own; false when the kernel refuses, and the peak stays the process's.
bool restart_peak_resident_set();

// The processor's model name (/proc/cpuinfo), its logical CPUs, and the 1-minute load average.
std::string processor_description();
std::optional<double> load_average();

// "2026-11-25 14:03 UTC".
std::string utc_now();

}  // namespace fb
