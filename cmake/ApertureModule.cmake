# aperture_add_module(<folder> DEPS <targets...> [PRIVATE_DEPS <targets...>])
# One library per top-level folder (STYLE.md 5): sources are the folder's *.cc files, the include
# root is the project root (#include "perception/camera/pinhole_camera.h"), the alias is
# aperture::<folder>. A folder without sources yet is an INTERFACE target so the layering holds.
# PRIVATE_DEPS are linked privately: their headers must not appear in the folder's public headers
# (servo's ViSP), so its dependents neither see nor link them directly.
function(aperture_add_module name)
  cmake_parse_arguments(ARG "" "" "DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${name}/*.cc)
  set(target aperture_${name})
  if(sources)
    add_library(${target} STATIC ${sources})
    target_include_directories(${target} PUBLIC ${PROJECT_SOURCE_DIR})
    target_link_libraries(${target} PUBLIC ${ARG_DEPS})
    if(ARG_PRIVATE_DEPS)
      target_link_libraries(${target} PRIVATE ${ARG_PRIVATE_DEPS})
    endif()
    target_compile_options(${target} PRIVATE -Wall -Wextra)
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE ${PROJECT_SOURCE_DIR})
    target_link_libraries(${target} INTERFACE ${ARG_DEPS})
  endif()
  add_library(aperture::${name} ALIAS ${target})
endfunction()

# aperture_add_test_suite(<folder> DEPS <targets...> [SOURCES <files...>] [LABELS <labels...>])
# tests/<folder>/*_test.cc (plus SOURCES, relative to tests/) become one GoogleTest executable
# registered with ctest; LABELS tag its tests (`ctest -LE <label>` leaves them out).
function(aperture_add_test_suite name)
  cmake_parse_arguments(ARG "" "" "DEPS;SOURCES;LABELS" ${ARGN})
  file(GLOB sources CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/${name}/*.cc)
  if(NOT sources)
    return()
  endif()
  list(TRANSFORM ARG_SOURCES PREPEND ${CMAKE_CURRENT_SOURCE_DIR}/)
  set(target aperture_${name}_tests)
  add_executable(${target} ${sources} ${ARG_SOURCES})
  target_link_libraries(${target} PRIVATE ${ARG_DEPS} GTest::gtest GTest::gmock GTest::gtest_main)
  target_compile_options(${target} PRIVATE -Wall -Wextra)
  target_compile_definitions(${target} PRIVATE
      APERTURE_TEST_DATA_DIR="${CMAKE_CURRENT_SOURCE_DIR}/data"
      APERTURE_BINARY="$<TARGET_FILE:aperture>"
      APERTURE_VERSION_FOR_TEST="${PROJECT_VERSION}")
  set(properties TIMEOUT 600)
  if(ARG_LABELS)
    list(APPEND properties LABELS "${ARG_LABELS}")
  endif()
  gtest_discover_tests(${target} DISCOVERY_TIMEOUT 60 PROPERTIES ${properties})
endfunction()
