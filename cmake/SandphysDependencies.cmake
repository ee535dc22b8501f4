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

if(SANDPHYS_SAMPLES OR SANDPHYS_BENCH OR SANDPHYS_TESTS)
  find_package(nlohmann_json 3)
  sandphys_require(nlohmann_json_FOUND "nlohmann-json" "nlohmann-json3-dev")
  find_package(CLI11 CONFIG)
  sandphys_require(CLI11_FOUND "CLI11" "libcli11-dev")
endif()
if(SANDPHYS_TESTS)
  find_package(GTest)
  sandphys_require(GTest_FOUND "GoogleTest" "libgtest-dev")
endif()
