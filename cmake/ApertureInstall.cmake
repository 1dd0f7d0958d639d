# `cmake --install` packages aperture for other CMake projects: the modules' libraries, headers and
# targets (installed by aperture_add_module), plus apertureConfig.cmake, its version file and the
# dependency finder it shares with this build, in lib/cmake/aperture/. A consumer writes
#   find_package(aperture 0.1 REQUIRED)
#   target_link_libraries(my_app PRIVATE aperture::perception)
# (examples/consumer/ is one, built against a staged install by tests/install/).
include(CMakePackageConfigHelpers)
set(APERTURE_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/aperture)
install(EXPORT apertureTargets NAMESPACE aperture:: DESTINATION ${APERTURE_INSTALL_CMAKEDIR})
configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/apertureConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/apertureConfig.cmake
                              INSTALL_DESTINATION ${APERTURE_INSTALL_CMAKEDIR})
write_basic_package_version_file(${PROJECT_BINARY_DIR}/apertureConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/apertureConfig.cmake
              ${PROJECT_BINARY_DIR}/apertureConfigVersion.cmake
              ${PROJECT_SOURCE_DIR}/cmake/ApertureLibraryDependencies.cmake
        DESTINATION ${APERTURE_INSTALL_CMAKEDIR})
