# Embeds GLSL files into a generated C++ source at build time. The custom command depends on every
# shader, so editing one rebuilds (no reconfigure needed); adding a file needs a reconfigure.
function(sandphys_embed_shaders out_var shader_root)
  file(GLOB_RECURSE shader_files CONFIGURE_DEPENDS
       "${shader_root}/*.comp" "${shader_root}/*.glsl" "${shader_root}/*.vert"
       "${shader_root}/*.frag")
  list(SORT shader_files)
  set(generated "${CMAKE_CURRENT_BINARY_DIR}/embedded_shaders.cpp")
  add_custom_command(
    OUTPUT "${generated}"
    COMMAND ${CMAKE_COMMAND} -DSHADER_ROOT=${shader_root} -DOUTPUT=${generated}
            "-DFILES=${shader_files}" -P "${PROJECT_SOURCE_DIR}/cmake/embed_shaders.cmake"
    DEPENDS ${shader_files} "${PROJECT_SOURCE_DIR}/cmake/embed_shaders.cmake"
    COMMENT "Embedding GLSL shaders"
    VERBATIM)
  set(${out_var} "${generated}" PARENT_SCOPE)
endfunction()
