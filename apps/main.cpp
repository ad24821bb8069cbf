// rtsph: one executable, one subcommand per task. Each command lives in its own file.
#include <cstdio>
#include <exception>
#include <string>

#include "apps/commands.h"

int main(int argc, char** argv) {
#ifdef RTSPH_HAVE_VIEWER
  if (argc == 1) return rtsph::app::run_default(argc, argv);
#endif
  CLI::App app{"rtsph: real-time SPH fluid simulation"};
  app.require_subcommand(1);
  // Bad arguments get one line, like bad scenes (CLI11's default adds a second), pointing at
  // the help that lists the failing subcommand's options.
  app.failure_message([](const CLI::App* a, const CLI::Error& e) {
    const auto subs = a->get_subcommands();
    const std::string help = subs.empty() ? "rtsph --help lists the commands"
                                          : "rtsph " + subs.front()->get_name() + " --help lists its options";
    return "rtsph: " + std::string(e.what()) + " (" + help + ")\n";
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
  // A first word that is no command (CLI11 would only say one is required).
  if (argc > 1 && argv[1][0] != '-') {
    std::string names;
    bool known = false;
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
      known = known || sub->check_name(argv[1]);
      names += (names.empty() ? "" : ", ") + sub->get_name();
    }
    if (!known) {
      std::fprintf(stderr, "rtsph: unknown command '%s'; expected one of %s (rtsph --help)\n", argv[1], names.c_str());
      return 2;
    }
  }
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
