# Embeds GLSL files into a generated C++ source at build time. The custom command depends on every
# shader, so editing one rebuilds (no reconfigure needed); adding a file needs a reconfigure.
#
# sandphys_embed_shaders(<out_var> <shader_root> [SUBDIRS <dir>...] [FUNCTION <name>])
# SUBDIRS limits the files to those folders of shader_root (names stay relative to shader_root,
# so "#include" works across them); FUNCTION names the generated accessor in sandphys::gl
# (default embeddedShaders, the library's), so that a consumer such as the samples' renderer can
# embed its own shaders beside the library's.
function(sandphys_embed_shaders out_var shader_root)
  cmake_parse_arguments(ARG "" "FUNCTION" "SUBDIRS" ${ARGN})
  if(NOT ARG_FUNCTION)
    set(ARG_FUNCTION embeddedShaders)
  endif()
  if(NOT ARG_SUBDIRS)
    set(ARG_SUBDIRS ".")
  endif()
  set(shader_files "")
  foreach(subdir IN LISTS ARG_SUBDIRS)
    file(GLOB_RECURSE found CONFIGURE_DEPENDS
         "${shader_root}/${subdir}/*.comp" "${shader_root}/${subdir}/*.glsl"
         "${shader_root}/${subdir}/*.vert" "${shader_root}/${subdir}/*.frag")
    list(APPEND shader_files ${found})
  endforeach()
  list(SORT shader_files)
  if(ARG_FUNCTION STREQUAL "embeddedShaders")
    set(generated "${CMAKE_CURRENT_BINARY_DIR}/embedded_shaders.cpp")
  else()
    set(generated "${CMAKE_CURRENT_BINARY_DIR}/${ARG_FUNCTION}.cpp")
  endif()
  add_custom_command(
    OUTPUT "${generated}"
    COMMAND ${CMAKE_COMMAND} -DSHADER_ROOT=${shader_root} -DOUTPUT=${generated}
            -DFUNCTION=${ARG_FUNCTION}
            "-DFILES=${shader_files}" -P "${PROJECT_SOURCE_DIR}/cmake/embed_shaders.cmake"
    DEPENDS ${shader_files} "${PROJECT_SOURCE_DIR}/cmake/embed_shaders.cmake"
    COMMENT "Embedding GLSL shaders"
    VERBATIM)
  set(${out_var} "${generated}" PARENT_SCOPE)
endfunction()
