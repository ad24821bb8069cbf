# Leak-checked builds: the flags ask for AddressSanitizer or LeakSanitizer (the asan-ubsan and
# fuzz presets, or -fsanitize=address by hand). In them, and only there, every executable gets
# tests/support/keep_modules_loaded.cpp (dlclose is a no-op, so GL driver modules stay mapped
# until LeakSanitizer names them at exit and tests/lsan.supp can suppress their leaks), and
# tests/CMakeLists.txt adds the test that LeakSanitizer still reports a leak in rtsph's own code.
set(rtsph_all_flags "${CMAKE_C_FLAGS} ${CMAKE_CXX_FLAGS} ${CMAKE_EXE_LINKER_FLAGS}")
if(rtsph_all_flags MATCHES "-fsanitize=([^ ]*,)?(address|leak)(,| |$)")
  set(RTSPH_LEAK_CHECKED ON)
else()
  set(RTSPH_LEAK_CHECKED OFF)
endif()
message(STATUS "rtsph: leak-checked build (LeakSanitizer, driver modules kept loaded): ${RTSPH_LEAK_CHECKED}")

# Call once, after every add_subdirectory: links the no-op dlclose into every executable below
# the top directory when the build is leak-checked. The symbol is exported from the executable
# so that it wins lookup for dlopen'ed libraries too (libglvnd, Mesa's EGL) that the link does
# not see.
function(rtsph_keep_modules_loaded_in_executables)
  if(NOT RTSPH_LEAK_CHECKED)
    return()
  endif()
  add_library(rtsph_keep_modules_loaded OBJECT
              ${CMAKE_SOURCE_DIR}/tests/support/keep_modules_loaded.cpp)
  target_link_options(rtsph_keep_modules_loaded INTERFACE "-Wl,--export-dynamic-symbol=dlclose")
  set(dirs ${CMAKE_SOURCE_DIR})
  while(dirs)
    list(POP_FRONT dirs dir)
    get_property(targets DIRECTORY ${dir} PROPERTY BUILDSYSTEM_TARGETS)
    foreach(target ${targets})
      get_target_property(type ${target} TYPE)
      if(type STREQUAL "EXECUTABLE")
        target_link_libraries(${target} PRIVATE rtsph_keep_modules_loaded)
      endif()
    endforeach()
    get_property(subdirs DIRECTORY ${dir} PROPERTY SUBDIRECTORIES)
    list(APPEND dirs ${subdirs})
  endwhile()
endfunction()
