// Text -> JSON with errors that point at a line and column. UTF-8 is checked first so that a
// stray Latin-1 byte is reported as what it is rather than as a JSON syntax error.
#include <fmt/format.h>

#include <string>
#include <vector>

#include "scene/json_reader.h"
#include "scene/scene_error.h"

namespace rtsph::scene_detail {
namespace {

// Deeper documents are never scene files, and the recursive dump() of error messages must
// not be able to exhaust the stack on fuzzed input.
constexpr int kMaxDepth = 64;

struct Position {
  std::size_t line = 1, column = 1;
};

Position position_of(const std::string& text, std::size_t offset) {
  Position p;
  for (std::size_t i = 0; i < offset && i < text.size(); ++i) {
    if (text[i] == '\n') ++p.line, p.column = 1;
    else if ((static_cast<unsigned char>(text[i]) & 0xC0) != 0x80) ++p.column;
  }
  return p;
}

/// Offset of the first byte that is not well-formed UTF-8 (RFC 3629), or npos.
std::size_t first_invalid_utf8(const std::string& s) {
  const auto* b = reinterpret_cast<const unsigned char*>(s.data());
  const std::size_t n = s.size();
  for (std::size_t i = 0; i < n;) {
    const unsigned c = b[i];
    std::size_t len;
    unsigned lo = 0x80, hi = 0xBF;  // allowed range of the second byte
    if (c < 0x80) len = 1;
    else if (c >= 0xC2 && c <= 0xDF) len = 2;
    else if (c >= 0xE0 && c <= 0xEF) len = 3, lo = c == 0xE0 ? 0xA0 : 0x80, hi = c == 0xED ? 0x9F : 0xBF;
    else if (c >= 0xF0 && c <= 0xF4) len = 4, lo = c == 0xF0 ? 0x90 : 0x80, hi = c == 0xF4 ? 0x8F : 0xBF;
    else return i;
    if (i + len > n) return i;
    for (std::size_t k = 1; k < len; ++k) {
      const unsigned t = b[i + k];
      if (k == 1 ? (t < lo || t > hi) : (t < 0x80 || t > 0xBF)) return i;
    }
    i += len;
  }
  return std::string::npos;
}

// nlohmann's message starts with "[json.exception.parse_error.101] parse error at line 1,
// column 2: "; the position is printed by us, so keep only the explanation.
std::string explanation(const char* what) {
  std::string s = what;
  const auto col = s.find("column ");
  const auto colon = col == std::string::npos ? col : s.find(": ", col);
  return colon == std::string::npos ? s : s.substr(colon + 2);
}

// Duplicate keys: JSON parsers keep the last silently, so a pasted block's second "spacing"
// would win unseen. The parse callback keeps the open containers' paths and keys to name one.
struct DuplicateKey {
  std::string path;
};

class KeyTracker {
 public:
  void on(nlohmann::json::parse_event_t event, const Json& parsed) {
    using E = nlohmann::json::parse_event_t;
    switch (event) {
      case E::object_start: push(true); break;
      case E::array_start: push(false); break;
      case E::key: {
        Frame& f = open_.back();
        const std::string key = parsed.get<std::string>();
        for (const auto& k : f.keys)
          if (k == key) throw DuplicateKey{join(f.path, key)};
        f.keys.push_back(key);
        break;
      }
      case E::object_end:
      case E::array_end: open_.pop_back(); done(); break;
      case E::value: done(); break;
    }
  }

 private:
  struct Frame {
    bool object;
    std::string path;
    std::vector<std::string> keys;  // objects: the keys so far (a scene object has a handful)
    std::size_t index = 0;          // arrays: the element being read
  };
  static std::string join(const std::string& path, const std::string& key) {
    return path.empty() ? key : path + "." + key;
  }
  std::string child_path() const {
    if (open_.empty()) return "";
    const Frame& f = open_.back();
    return f.object ? join(f.path, f.keys.empty() ? "" : f.keys.back()) : fmt::format("{}[{}]", f.path, f.index);
  }
  void push(bool object) { open_.push_back(Frame{object, child_path(), {}, 0}); }
  void done() {
    if (!open_.empty() && !open_.back().object) ++open_.back().index;
  }
  std::vector<Frame> open_;
};

}  // namespace

Json parse_json_text(const std::string& text, const std::string& source) {
  if (const std::size_t bad = first_invalid_utf8(text); bad != std::string::npos) {
    const Position p = position_of(text, bad);
    throw SceneError(source, fmt::format("line {}, column {}", p.line, p.column),
                     fmt::format("byte 0x{:02X}", static_cast<unsigned char>(text[bad])),
                     "expected UTF-8 text");
  }
  KeyTracker keys;
  try {
    return Json::parse(text, [&](int depth, nlohmann::json::parse_event_t event, Json& parsed) {
      if (depth > kMaxDepth) throw std::length_error("nesting");
      keys.on(event, parsed);
      return true;
    });
  } catch (const DuplicateKey& d) {
    throw SceneError(source, d.path, "appears twice in its object",
                     "give each key once (JSON would keep only the last, silently)");
  } catch (const Json::parse_error& e) {
    const Position p = position_of(text, e.byte == 0 ? 0 : e.byte - 1);
    const std::size_t at = e.byte == 0 ? 0 : e.byte - 1;
    throw SceneError(source, fmt::format("line {}, column {}", p.line, p.column),
                     at < text.size() ? show(Json(text.substr(at, 1))) : "end of input",
                     "malformed JSON: " + explanation(e.what()));
  } catch (const std::length_error&) {
    throw SceneError(source, fmt::format("nested deeper than {} levels", kMaxDepth));
  } catch (const nlohmann::json::exception& e) {
    // Not a parse error (no byte offset): a number too large for a double, "number overflow
    // parsing '1e999'". Drop the library's error id and find the literal in the text.
    std::string what = e.what();
    if (const auto close = what.find("] "); what.rfind("[json.exception.", 0) == 0 && close != std::string::npos)
      what = what.substr(close + 2);
    const auto q = what.find("parsing '");
    const auto q_end = q == std::string::npos ? q : what.find('\'', q + 9);
    if (q_end != std::string::npos) {
      const std::string literal = what.substr(q + 9, q_end - q - 9);
      if (const auto at = text.find(literal); !literal.empty() && at != std::string::npos) {
        const Position p = position_of(text, at);
        throw SceneError(source, fmt::format("line {}, column {}", p.line, p.column), literal,
                         "malformed JSON: " + what.substr(0, q == 0 ? 0 : q - 1));
      }
    }
    throw SceneError(source, fmt::format("malformed JSON: {}", what));
  }
}

}  // namespace rtsph::scene_detail
