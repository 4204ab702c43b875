# Installed CMake package: find_package(mixmesh) then link mixmesh::mixmesh.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

install(TARGETS mixmesh ${mixmesh_modules} EXPORT mixmeshTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR}
        LIBRARY DESTINATION ${CMAKE_INSTALL_LIBDIR}
        RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(DIRECTORY include/mixmesh DESTINATION ${CMAKE_INSTALL_INCLUDEDIR})
install(EXPORT mixmeshTargets NAMESPACE mixmesh:: DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mixmesh)
configure_package_config_file(cmake/mixmeshConfig.cmake.in
                              ${PROJECT_BINARY_DIR}/mixmeshConfig.cmake
                              INSTALL_DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mixmesh)
write_basic_package_version_file(${PROJECT_BINARY_DIR}/mixmeshConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${PROJECT_BINARY_DIR}/mixmeshConfig.cmake ${PROJECT_BINARY_DIR}/mixmeshConfigVersion.cmake
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/cmake/mixmesh)
# The picture scripts `check --hist` and `compare` run (found in share/mixmesh/scripts).
install(FILES scripts/plot-compare.py scripts/plot-mesh-cut.py
              scripts/plot-quality-histograms.py
        DESTINATION ${CMAKE_INSTALL_DATADIR}/mixmesh/scripts)
