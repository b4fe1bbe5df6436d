// How filmback asks glibc's malloc to give large freed blocks back to the system.
#pragma once

namespace fb {

// Fixes glibc's mmap threshold at its initial 128 KiB (docs/benchmarks.md, "Issue 17: where the
// unaccounted memory goes"). Call once at start-up, before any thread starts.
void keep_large_allocations_in_mmap();

}  // namespace fb
