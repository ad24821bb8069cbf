#pragma once
// Each subcommand registers itself on the CLI11 app; its callback stores the exit code.
#include <CLI/CLI.hpp>


namespace rtsph::app {

/// A number above zero (or, with zero_ok, at least zero), with a message a person can read:
/// CLI11's PositiveNumber and NonNegativeNumber print their range to the last digit of DBL_MAX.
inline CLI::Validator number_from_zero(bool zero_ok) {
  return CLI::Validator(
      [zero_ok](std::string& in) -> std::string {
        double v = 0;
        if (!CLI::detail::lexical_cast(in, v)) return "'" + in + "' is not a number";
        if (zero_ok ? v >= 0 : v > 0) return {};
        return "'" + in + (zero_ok ? "' must be zero or more" : "' must be above zero");
      },
      zero_ok ? "NONNEGATIVE" : "POSITIVE");
}
inline CLI::Validator positive_number() { return number_from_zero(false); }
inline CLI::Validator non_negative_number() { return number_from_zero(true); }

void add_run_command(CLI::App& app, int& exit_code);
void add_bench_command(CLI::App& app, int& exit_code);
void add_scenes_command(CLI::App& app, int& exit_code);
void add_validate_command(CLI::App& app, int& exit_code);  // hands over to python -m rtsph.validate
#ifdef RTSPH_HAVE_VIEWER
void add_view_command(CLI::App& app, int& exit_code);    // apps/viewer/
void add_render_command(CLI::App& app, int& exit_code);  // apps/viewer/
/// `rtsph` with no arguments: the viewer on dam_break_3d, or a headless render without display.
int run_default(int argc, char** argv);
#endif

}  // namespace rtsph::app
