// rtsph: one executable, one subcommand per task. Each command lives in its own file.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>

#include "apps/commands.h"

int main(int argc, char** argv) {
  // OpenMP workers that spin at barriers stall whenever another process holds a core (a 2-thread
  // run beside a busy process measured 10.2 s spinning vs 0.46 s sleeping; on an idle machine
  // the two are within noise). libgomp reads the policy once at load, so set it and re-exec.
  if (!std::getenv("OMP_WAIT_POLICY")) {
    setenv("OMP_WAIT_POLICY", "passive", 1);
    execv("/proc/self/exe", argv);  // if this fails, carry on with the spinning default
  }
#ifdef RTSPH_HAVE_VIEWER
  if (argc == 1) return rtsph::app::run_default(argc, argv);
#endif
  CLI::App app{"rtsph: real-time SPH fluid simulation"};
  app.require_subcommand(1);
  // Bad arguments get one line, like bad scenes (CLI11's default adds a second).
  app.failure_message([](const CLI::App*, const CLI::Error& e) {
    return "rtsph: " + std::string(e.what()) + " (rtsph --help lists the options)\n";
  });
  int exit_code = 0;
  rtsph::app::add_run_command(app, exit_code);
  rtsph::app::add_bench_command(app, exit_code);
  rtsph::app::add_scenes_command(app, exit_code);
  rtsph::app::add_validate_command(app, exit_code);
#ifdef RTSPH_HAVE_VIEWER
  rtsph::app::add_view_command(app, exit_code);
  rtsph::app::add_render_command(app, exit_code);
#endif
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rtsph: %s\n", e.what());
    return 1;
  }
  return exit_code;
}
