#include "core/cmd/bench_process.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstring>

#include "core/util/error.h"

extern char** environ;

namespace fb {

namespace fs = std::filesystem;

ProgramRun run_program(const std::vector<std::string>& argv, const fs::path& log) {
  // The log is opened here, not by the spawn's file actions, so that failing to create it is told
  // apart from the program not being found.
  const int log_fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (log_fd < 0) throw_input(log.string(), "", std::string("cannot create: ") + strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_adddup2(&actions, log_fd, STDOUT_FILENO);
  posix_spawn_file_actions_adddup2(&actions, log_fd, STDERR_FILENO);
  std::vector<char*> args;
  for (const std::string& a : argv)
    args.push_back(const_cast<char*>(a.c_str()));
  args.push_back(nullptr);

  ProgramRun run;
  const auto start = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, args[0], &actions, nullptr, args.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  close(log_fd);
  if (spawned != 0) return run;
  run.started = true;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  run.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (WIFEXITED(status)) run.exit_status = WEXITSTATUS(status);
  return run;
}

std::string describe_failure(const ProgramRun& run, const std::string& what, const fs::path& log) {
  if (!run.started) return what + ": the program was not found on PATH";
  return what + " failed (" +
         (run.exit_status >= 0 ? "exit status " + std::to_string(run.exit_status)
                               : std::string("killed by a signal")) +
         "); its output is in " + log.string();
}

fs::path this_program() {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  return ec ? fs::path() : exe;
}

fs::path bench_script(const std::string& name) {
  std::error_code ec;
  const fs::path exe = this_program();
  fs::path script = exe.parent_path().parent_path() / "share/filmback/bench" / name;
  if (exe.empty() || !fs::is_regular_file(script, ec))
    script = fs::path(FILMBACK_INSTALL_SHARE_DIR) / "bench" / name;
  if (!fs::is_regular_file(script, ec))
    throw_input(script.string(), "", "a script of filmback bench is missing (reinstall filmback)");
  return script;
}

}  // namespace fb
