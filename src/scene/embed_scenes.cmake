# Script mode: cmake -DOUT=<file.cpp> -DSCENES=<a.json|b.json> -P embed_scenes.cmake
# Writes a C++ file holding each scene as a raw string literal. OUT is rewritten only when its
# content changes, so an unchanged scene set does not rebuild the library.
set(delim "rtsph_scene")
string(REPLACE "|" ";" SCENES "${SCENES}")
list(SORT SCENES)
set(body "")
foreach(path ${SCENES})
  get_filename_component(name ${path} NAME_WE)
  file(READ ${path} text)
  string(FIND "${text}" ")${delim}\"" clash)
  if(NOT clash EQUAL -1)
    message(FATAL_ERROR "${path} contains the raw-string delimiter )${delim}\"")
  endif()
  string(APPEND body "      {\"${name}\", R\"${delim}(${text})${delim}\"},\n")
endforeach()
set(cpp "// Generated from scenes/*.json by src/scene/embed_scenes.cmake; do not edit.
#include \"scene/builtin_data.h\"

namespace rtsph::scene_detail {

const std::vector<EmbeddedScene>& embedded_scenes() {
  static const std::vector<EmbeddedScene> scenes = {
${body}  };
  return scenes;
}

}  // namespace rtsph::scene_detail
")
file(WRITE ${OUT}.tmp "${cpp}")
configure_file(${OUT}.tmp ${OUT} COPYONLY)
