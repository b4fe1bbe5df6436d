// The programs `filmback bench` runs beside itself: Blender (Cycles, the glTF export) and Python
// (the plots), and where their scripts are installed.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace fb {

struct ProgramRun {
  bool started = false;  // false: `argv[0]` is not on PATH (or cannot be executed)
  int exit_status = -1;  // the exit status when it exited normally, else -1
  double wall_s = 0;     // from just before the spawn until it was reaped
};

// Runs `argv` (argv[0] looked up on PATH) with stdin from /dev/null and stdout and stderr into
// `log`, and waits for it. Throws InputError only when the log cannot be created.
ProgramRun run_program(const std::vector<std::string>& argv, const std::filesystem::path& log);

// "program ... failed (exit status N); its output is in LOG", or "... not found on PATH".
std::string describe_failure(const ProgramRun& run, const std::string& what,
                             const std::filesystem::path& log);

// This process's executable (/proc/self/exe), for commands that run filmback itself; empty if
// the kernel does not say.
std::filesystem::path this_program();

// A script of `filmback bench` (share/filmback/bench/ beside the executable's folder, as the build
// tree mirrors the install tree, else the installed one): InputError naming it when absent.
std::filesystem::path bench_script(const std::string& name);

}  // namespace fb
