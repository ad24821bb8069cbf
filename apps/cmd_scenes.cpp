// `rtsph scenes`: the built-in scenes, one per line (or the scene-format reference).
#include <algorithm>
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
      const auto scenes = builtin_scenes();
      int width = 0;  // the longest name, so every description starts in one column
      for (const auto& [name, help] : scenes) width = std::max(width, int(name.size()));
      for (const auto& [name, help] : scenes) std::printf("%-*s  %s\n", width, name.c_str(), help.c_str());
    }
    exit_code = 0;
  });
}

}  // namespace rtsph::app
