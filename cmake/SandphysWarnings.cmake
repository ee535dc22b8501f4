add_library(sandphys_warnings INTERFACE)
target_compile_options(sandphys_warnings INTERFACE -Wall -Wextra -Wpedantic -Wshadow
                                                   -Wnon-virtual-dtor -Wno-missing-field-initializers)
if(SANDPHYS_WERROR)
  target_compile_options(sandphys_warnings INTERFACE -Werror)
endif()
