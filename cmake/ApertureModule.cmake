# aperture_add_module(<folder> DEPS <targets...> [PRIVATE_DEPS <targets...>])
# One library per top-level folder (STYLE.md 5): sources are the folder's *.cc files, the include
# root is the project root (#include "perception/camera/pinhole_camera.h"), the alias is
# aperture::<folder>. A folder without sources yet is an INTERFACE target so the layering holds.
# PRIVATE_DEPS are linked privately: their headers must not appear in the folder's public headers
# (servo's ViSP), so its dependents neither see nor link them directly.
# Every module is installed the same way (`cmake --install`): the library into lib/, its headers
# under include/aperture/<folder>/ (consumers keep the same #include lines) and the target into
# the `apertureTargets` export as aperture::<folder> (cmake/apertureConfig.cmake.in).
function(aperture_add_module name)
  cmake_parse_arguments(ARG "" "" "DEPS;PRIVATE_DEPS" ${ARGN})
  file(GLOB_RECURSE sources CONFIGURE_DEPENDS ${PROJECT_SOURCE_DIR}/${name}/*.cc)
  set(target aperture_${name})
  set(include_root $<BUILD_INTERFACE:${PROJECT_SOURCE_DIR}>
                   $<INSTALL_INTERFACE:${APERTURE_INSTALL_INCLUDEDIR}>)
  if(sources)
    add_library(${target} STATIC ${sources})
    target_include_directories(${target} PUBLIC ${include_root})
    target_link_libraries(${target} PUBLIC ${ARG_DEPS} PRIVATE ${ARG_PRIVATE_DEPS})
    target_compile_options(${target} PRIVATE -Wall -Wextra)
  else()
    add_library(${target} INTERFACE)
    target_include_directories(${target} INTERFACE ${include_root})
    target_link_libraries(${target} INTERFACE ${ARG_DEPS})
  endif()
  add_library(aperture::${name} ALIAS ${target})
  set_target_properties(${target} PROPERTIES EXPORT_NAME ${name})
  install(TARGETS ${target} EXPORT apertureTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
  if(EXISTS ${PROJECT_SOURCE_DIR}/${name})
    install(DIRECTORY ${PROJECT_SOURCE_DIR}/${name}/ DESTINATION ${APERTURE_INSTALL_INCLUDEDIR}/${name}
            FILES_MATCHING PATTERN "*.h")
  endif()
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
