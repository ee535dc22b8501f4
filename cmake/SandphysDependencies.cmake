# Every dependency comes from Debian's packages; a missing one fails configure and names the
# package that provides it (scripts/install-deps.sh installs them all).
function(sandphys_require found what debian_package)
  if(NOT ${found})
    message(FATAL_ERROR "sandphys needs ${what}: install the Debian package '${debian_package}' "
                        "(or run scripts/install-deps.sh)")
  endif()
endfunction()

find_package(OpenGL COMPONENTS OpenGL EGL)
sandphys_require(OpenGL_OpenGL_FOUND "OpenGL (libOpenGL)" "libopengl-dev")
sandphys_require(OpenGL_EGL_FOUND "EGL" "libegl-dev")
find_package(GLEW)
sandphys_require(GLEW_FOUND "GLEW" "libglew-dev")
find_package(Eigen3 3.3 NO_MODULE)
sandphys_require(Eigen3_FOUND "Eigen 3" "libeigen3-dev")
# Mesh files for sampled bodies (loadMesh). Debian 12 ships assimp 5.2 with a CMake package.
find_package(assimp 5 CONFIG)
sandphys_require(assimp_FOUND "assimp (mesh files for sandphys::loadMesh)" "libassimp-dev")
# Recordings (sandphys/recording.h): zstd compresses their snapshots, xxHash (used inline from its
# header) checksums them.
find_package(zstd CONFIG)
sandphys_require(zstd_FOUND "zstd (recordings)" "libzstd-dev")
find_package(PkgConfig)
if(PkgConfig_FOUND)
  pkg_check_modules(XXHASH IMPORTED_TARGET GLOBAL libxxhash)
endif()
sandphys_require(XXHASH_FOUND "xxHash (recordings, found with pkg-config)" "libxxhash-dev")
# Only xxHash's header is used (XXH_INLINE_ALL), so that a static sandphys does not carry
# -lxxhash into a game's link.

if(SANDPHYS_SAMPLES OR SANDPHYS_BENCH OR SANDPHYS_TESTS)
  find_package(nlohmann_json 3)
  sandphys_require(nlohmann_json_FOUND "nlohmann-json" "nlohmann-json3-dev")
  find_package(CLI11 CONFIG)
  sandphys_require(CLI11_FOUND "CLI11" "libcli11-dev")
endif()
if(SANDPHYS_SAMPLES OR SANDPHYS_TESTS)
  # PNG screenshots: Debian's stb ships the compiled implementation in libstb.so.
  find_package(PkgConfig)
  if(PkgConfig_FOUND)
    pkg_check_modules(STB IMPORTED_TARGET stb)
  endif()
  sandphys_require(STB_FOUND "stb (stb_image_write, found with pkg-config)" "libstb-dev")
endif()
if(SANDPHYS_BULLET)
  # Debian's Bullet 3.24 (single precision); its CMake file sets variables only, so pkg-config
  # gives the imported target.
  find_package(PkgConfig)
  if(PkgConfig_FOUND)
    pkg_check_modules(BULLET IMPORTED_TARGET GLOBAL bullet)
  endif()
  sandphys_require(BULLET_FOUND "Bullet for the bridge (SANDPHYS_BULLET; found with pkg-config)"
                   "libbullet-dev")
endif()
if(SANDPHYS_TESTS)
  find_package(GTest)
  sandphys_require(GTest_FOUND "GoogleTest" "libgtest-dev")
endif()

# The viewer: GLFW 3.3 for the window and Dear ImGui for the panel. Debian's libimgui-dev ships
# only a pkg-config file (its libimgui.a already holds the GLFW and OpenGL 3 backends); GLFW is
# looked for as a CMake package first and through pkg-config otherwise. Each ends up as one
# imported target, sandphys::glfw and sandphys::imgui, so the viewer links the same either way.
if(SANDPHYS_SAMPLES AND SANDPHYS_VIEWER)
  find_package(PkgConfig QUIET)
  find_package(glfw3 3.3 CONFIG QUIET)
  set(SANDPHYS_GLFW_OK FALSE)
  if(glfw3_FOUND)
    add_library(sandphys::glfw INTERFACE IMPORTED GLOBAL)
    target_link_libraries(sandphys::glfw INTERFACE glfw)
    set(SANDPHYS_GLFW_OK TRUE)
  elseif(PkgConfig_FOUND)
    pkg_check_modules(SANDPHYS_GLFW QUIET IMPORTED_TARGET GLOBAL glfw3>=3.3)
    if(SANDPHYS_GLFW_FOUND)
      add_library(sandphys::glfw INTERFACE IMPORTED GLOBAL)
      target_link_libraries(sandphys::glfw INTERFACE PkgConfig::SANDPHYS_GLFW)
      set(SANDPHYS_GLFW_OK TRUE)
    endif()
  endif()
  sandphys_require(SANDPHYS_GLFW_OK "GLFW >= 3.3 for the viewer (SANDPHYS_VIEWER)" "libglfw3-dev")
  sandphys_require(PkgConfig_FOUND "pkg-config to find Dear ImGui (SANDPHYS_VIEWER)" "pkg-config")
  # imgui.pc requires stb.pc (libstb-dev, a dependency of libimgui-dev).
  pkg_check_modules(SANDPHYS_IMGUI QUIET IMPORTED_TARGET GLOBAL imgui)
  sandphys_require(SANDPHYS_IMGUI_FOUND "Dear ImGui for the viewer (SANDPHYS_VIEWER)"
                   "libimgui-dev")
  add_library(sandphys::imgui INTERFACE IMPORTED GLOBAL)
  # libimgui.a's GLFW backend needs GLFW after it on the link line; its OpenGL 3 backend loads GL
  # with dlopen.
  target_link_libraries(sandphys::imgui INTERFACE PkgConfig::SANDPHYS_IMGUI sandphys::glfw
                                                  ${CMAKE_DL_LIBS})
endif()
