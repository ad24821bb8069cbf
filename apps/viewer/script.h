#pragma once
// Scripted input for the viewer (`rtsph view SCENE --script FILE`), used by the smoke test and
// for reproducible demos. One command per line, '#' starts a comment:
//   wait N                     draw N frames
//   sync                       wait until the solver has finished pending steps and drawn
//   key NAME                   press and release a key: space n r g 1 5-9 tab left right up
//                              down q w a s z x f12 v h esc
//   drag BUTTON MODS X0 Y0 X1 Y1 [FRAMES]
//                              mouse drag; BUTTON left|middle|right, MODS none|shift|ctrl;
//                              coordinates are fractions of the window (0..1, y down)
//   scroll DY                  mouse wheel (positive zooms in)
//   screenshot PATH            save the view as PNG
//   quit                       close the viewer (exit status 0)
#include <string>
#include <vector>

namespace rtsph::app {

struct ScriptCommand {
  std::string op;
  std::vector<std::string> args;
  int line = 0;
};

/// Parses and checks a script; throws std::invalid_argument ("FILE:LINE: ...") on errors.
std::vector<ScriptCommand> load_script(const std::string& path);

/// GLFW key code for a script key name, or -1.
int script_key(const std::string& name);

}  // namespace rtsph::app
