// rtsph: one executable, one subcommand per task. Each command lives in its own file.
#include <cstdio>
#include <exception>

#include "apps/commands.h"

int main(int argc, char** argv) {
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
