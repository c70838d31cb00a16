# kasumi_target(NAME) applies the project's warnings and sanitizer flags to one of our targets.
function(kasumi_target name)
  target_compile_options(${name} PRIVATE -Wall -Wextra -Wpedantic -Wshadow)
  if(KASUMI_WERROR)
    target_compile_options(${name} PRIVATE -Werror)
  endif()
  if(KASUMI_SANITIZE)
    target_compile_options(${name} PRIVATE -fsanitize=address,undefined -fno-omit-frame-pointer
                                           -fno-sanitize-recover=undefined)
    target_link_options(${name} PRIVATE -fsanitize=address,undefined)
    get_target_property(type ${name} TYPE)
    if(type STREQUAL "EXECUTABLE")
      target_sources(${name} PRIVATE ${PROJECT_SOURCE_DIR}/core/sanitizer_defaults.cpp)
    endif()
  endif()
endfunction()

# kasumi_library(NAME SOURCES...) declares one folder's library; include paths are from the root
# so headers read "core/math.h".
function(kasumi_library name)
  add_library(kasumi_${name} STATIC ${ARGN})
  target_include_directories(kasumi_${name} PUBLIC ${PROJECT_SOURCE_DIR})
  kasumi_target(kasumi_${name})
  if(KASUMI_SANITIZE)
    target_link_options(kasumi_${name} INTERFACE -fsanitize=address,undefined)
  endif()
endfunction()
