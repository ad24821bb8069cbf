# Included from src/CMakeLists.txt: compiles scenes/*.json into rtsph_scene so built-in scenes
# work from any directory. The JSON files stay the source of truth.
file(GLOB rtsph_scene_jsons CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/scenes/*.json)
# A list passed through the command line must not contain ';' (it would split the argument).
string(REPLACE ";" "|" rtsph_scene_list "${rtsph_scene_jsons}")
set(rtsph_scene_data ${CMAKE_BINARY_DIR}/generated/builtin_scenes_data.cpp)
add_custom_command(
  OUTPUT ${rtsph_scene_data}
  COMMAND ${CMAKE_COMMAND} -DOUT=${rtsph_scene_data} "-DSCENES=${rtsph_scene_list}"
          -P ${CMAKE_CURRENT_LIST_DIR}/embed_scenes.cmake
  DEPENDS ${rtsph_scene_jsons} ${CMAKE_CURRENT_LIST_DIR}/embed_scenes.cmake
  COMMENT "Embedding built-in scenes"
  VERBATIM)
target_sources(rtsph_scene PRIVATE ${rtsph_scene_data})
