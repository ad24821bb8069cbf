#include "apps/viewer/script.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <fmt/format.h>

#include <algorithm>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

namespace rtsph::app {

int script_key(const std::string& name) {
  static const std::map<std::string, int> keys = {
      {"space", GLFW_KEY_SPACE}, {"n", GLFW_KEY_N},       {"r", GLFW_KEY_R},
      {"g", GLFW_KEY_G},         {"1", GLFW_KEY_1},       {"5", GLFW_KEY_5},
      {"6", GLFW_KEY_6},         {"7", GLFW_KEY_7},       {"8", GLFW_KEY_8},
      {"9", GLFW_KEY_9},         {"tab", GLFW_KEY_TAB},   {"left", GLFW_KEY_LEFT},
      {"right", GLFW_KEY_RIGHT}, {"up", GLFW_KEY_UP},     {"down", GLFW_KEY_DOWN},
      {"q", GLFW_KEY_Q},         {"w", GLFW_KEY_W},       {"a", GLFW_KEY_A},
      {"s", GLFW_KEY_S},         {"z", GLFW_KEY_Z},       {"x", GLFW_KEY_X},
      {"f12", GLFW_KEY_F12},     {"v", GLFW_KEY_V},       {"h", GLFW_KEY_H},
      {"esc", GLFW_KEY_ESCAPE},  {"f", GLFW_KEY_F},
  };
  auto it = keys.find(name);
  return it == keys.end() ? -1 : it->second;
}

std::vector<ScriptCommand> load_script(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::invalid_argument(fmt::format("--script {}: cannot open the file", path));
  std::vector<ScriptCommand> out;
  std::string line;
  int n = 0;
  auto fail = [&](const std::string& why) {
    throw std::invalid_argument(fmt::format("{}:{}: {}", path, n, why));
  };
  auto number = [&](const std::string& s) {
    try {
      std::size_t used = 0;
      double v = std::stod(s, &used);
      if (used != s.size()) fail("not a number: " + s);
      return v;
    } catch (const std::logic_error&) {
      fail("not a number: " + s);
    }
    return 0.0;
  };
  while (std::getline(in, line)) {
    ++n;
    if (auto hash = line.find('#'); hash != std::string::npos) line.resize(hash);
    std::istringstream ss(line);
    ScriptCommand c;
    c.line = n;
    if (!(ss >> c.op)) continue;
    std::transform(c.op.begin(), c.op.end(), c.op.begin(), ::tolower);
    for (std::string a; ss >> a;) c.args.push_back(a);
    const auto argc = c.args.size();
    if (c.op == "wait") {
      if (argc != 1 || number(c.args[0]) < 0) fail("usage: wait FRAMES");
    } else if (c.op == "sync" || c.op == "quit") {
      if (argc != 0) fail("usage: " + c.op);
    } else if (c.op == "key") {
      if (argc != 1 || script_key(c.args[0]) < 0) fail("usage: key NAME (space n r g 1 5-9 tab left right up down q w a s z x f12 v h esc)");
    } else if (c.op == "drag") {
      if (argc != 6 && argc != 7) fail("usage: drag left|middle|right none|shift|ctrl X0 Y0 X1 Y1 [FRAMES]");
      if (c.args[0] != "left" && c.args[0] != "middle" && c.args[0] != "right") fail("drag: button must be left, middle or right");
      if (c.args[1] != "none" && c.args[1] != "shift" && c.args[1] != "ctrl") fail("drag: modifier must be none, shift or ctrl");
      for (std::size_t i = 2; i < argc; ++i) number(c.args[i]);
    } else if (c.op == "scroll") {
      if (argc != 1) fail("usage: scroll DY");
      number(c.args[0]);
    } else if (c.op == "screenshot") {
      if (argc != 1) fail("usage: screenshot PATH");
    } else {
      fail("unknown command '" + c.op + "'");
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace rtsph::app
