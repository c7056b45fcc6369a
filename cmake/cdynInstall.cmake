# cdynInstall.cmake — `cmake --install` of the library (README.md, "Using cdyn as a
# library"): the three public libraries, their headers under include/cdyn/, and a CMake
# package so that an outside project writes
#     find_package(cdyn 0.1 REQUIRED)
#     target_link_libraries(app PRIVATE cdyn::cdyn cdyn::meshing cdyn::io)
# and the `cdyn` program into bin/ (its default scene and plot scripts are compiled in,
# so it runs without the source tree).  The command-line front end's library
# (cdyn_frontend) is not part of the library API and is not installed.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

set(CDYN_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/cdyn)

install(TARGETS cdyn cdyn_meshing cdyn_io EXPORT cdynTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
        FILE_SET HEADERS DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}
        FILE_SET compat DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT cdynTargets NAMESPACE cdyn:: DESTINATION ${CDYN_INSTALL_CMAKEDIR})

configure_package_config_file(${PROJECT_SOURCE_DIR}/cmake/cdynConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/cdynConfig.cmake
                              INSTALL_DESTINATION ${CDYN_INSTALL_CMAKEDIR})
# 0.x: a minor version may change the API, so only the same major.minor is compatible.
write_basic_package_version_file(${PROJECT_BINARY_DIR}/cdynConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/cdynConfig.cmake ${PROJECT_BINARY_DIR}/cdynConfigVersion.cmake
        DESTINATION ${CDYN_INSTALL_CMAKEDIR})

# The `cdyn` program: apps/ is added after this file (the libraries' install rules come
# first), so the rule is deferred to the end of the top directory, when it exists.
cmake_language(DEFER DIRECTORY ${PROJECT_SOURCE_DIR}
               CALL install TARGETS cdyn_app RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
