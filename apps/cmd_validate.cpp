// `rtsph validate [CASE…] [--method M|all] [--quick|--full] [--out DIR] [--threads N] [--set K=V]`: the
// validation suite. The cases, their comparison and the report (plots through matplotlib) live
// in the Python package (python/rtsph/validate), on the same engine; this command finds a
// Python that has it and hands over every argument. Exit codes: 0 every case passed, 1 one
// failed, 2 bad arguments or no Python package.
#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "apps/commands.h"

namespace rtsph::app {
namespace {

/// $RTSPH_PYTHON, else the clone's .venv (scripts/setup-python.sh), else python3 on PATH.
std::string find_python() {
  if (const char* p = std::getenv("RTSPH_PYTHON"); p && *p) return p;
#ifdef RTSPH_SOURCE_DIR
  const std::filesystem::path venv = std::filesystem::path(RTSPH_SOURCE_DIR) / ".venv" / "bin" / "python";
  if (std::filesystem::exists(venv)) return venv.string();
#endif
  return "python3";
}

/// Runs `python -c code` with its output discarded; true when it exits 0.
bool python_can(const std::string& python, const char* code) {
  const pid_t pid = fork();
  if (pid < 0) return false;
  if (pid == 0) {
    std::freopen("/dev/null", "w", stdout);
    std::freopen("/dev/null", "w", stderr);
    execlp(python.c_str(), python.c_str(), "-c", code, static_cast<char*>(nullptr));
    _exit(127);
  }
  int status = 0;
  waitpid(pid, &status, 0);
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

int run_validate(const std::vector<std::string>& args) {
  const std::string python = find_python();
  if (!python_can(python, "import rtsph.validate, matplotlib")) {
    std::fprintf(stderr, "rtsph validate: %s cannot import rtsph.validate and matplotlib: run scripts/setup-python.sh "
                 "(or set RTSPH_PYTHON to a Python that has them)\n", python.c_str());
    return 2;
  }
  std::vector<std::string> argv_s = {python, "-m", "rtsph.validate"};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  std::fflush(nullptr);
  execvp(python.c_str(), argv.data());
  std::perror("rtsph validate: exec");
  return 2;
}

}  // namespace

void add_validate_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("validate", "Run the validation cases against analytic solutions and experiments, "
                                             "and write a report (needs the Python package: scripts/setup-python.sh; "
                                             "`rtsph validate --help` lists its options)");
  // Every argument, --help included, goes to the Python side, which parses and documents them.
  cmd->set_help_flag();
  cmd->prefix_command();
  cmd->callback([cmd, &exit_code] { exit_code = run_validate(cmd->remaining()); });
}

}  // namespace rtsph::app
