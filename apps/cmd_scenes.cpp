// `rtsph scenes`: the built-in scenes, one per line (or the scene-format reference).
#include <cstdio>

#include "apps/commands.h"
#include "scene/scene.h"

namespace rtsph::app {

void add_scenes_command(CLI::App& app, int& exit_code) {
  auto* cmd = app.add_subcommand("scenes", "List the built-in scenes");
  auto markdown = std::make_shared<bool>(false);
  cmd->add_flag("--markdown", *markdown, "Print the scene-format reference (docs/scene-format.md)");
  cmd->callback([markdown, &exit_code] {
    if (*markdown) {
      std::fputs(scene_format_markdown().c_str(), stdout);
    } else {
      for (const auto& [name, help] : builtin_scenes()) std::printf("%-22s %s\n", name.c_str(), help.c_str());
    }
    exit_code = 0;
  });
}

}  // namespace rtsph::app
