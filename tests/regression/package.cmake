# find_package(mixmesh) from an installed tree: install into the build folder,
# configure and build a consumer project against it, run it.
set(package_prefix ${PROJECT_BINARY_DIR}/package-test/prefix)
set(package_build ${PROJECT_BINARY_DIR}/package-test/consumer)
add_test(NAME package_install
         COMMAND ${CMAKE_COMMAND} --install ${PROJECT_BINARY_DIR} --prefix ${package_prefix})
add_test(NAME package_consumer_configure
         COMMAND ${CMAKE_COMMAND} -S ${PROJECT_SOURCE_DIR}/tests/package -B ${package_build}
                 -DCMAKE_PREFIX_PATH=${package_prefix} -DCMAKE_BUILD_TYPE=Release)
add_test(NAME package_consumer_build COMMAND ${CMAKE_COMMAND} --build ${package_build})
add_test(NAME package_consumer_run COMMAND ${package_build}/consumer)
set_tests_properties(package_install PROPERTIES LABELS regression FIXTURES_SETUP package_installed)
set_tests_properties(package_consumer_configure PROPERTIES LABELS regression
                     FIXTURES_REQUIRED package_installed FIXTURES_SETUP package_configured)
set_tests_properties(package_consumer_build PROPERTIES LABELS regression
                     FIXTURES_REQUIRED package_configured FIXTURES_SETUP package_built)
set_tests_properties(package_consumer_run PROPERTIES LABELS regression FIXTURES_REQUIRED package_built
                     PASS_REGULAR_EXPRESSION "^1\n$")
# The installed picture scripts run from the installation's share folder.
add_test(NAME package_scripts_installed
         COMMAND ${MIXMESH_PYTHON} ${package_prefix}/share/mixmesh/scripts/plot-quality-histograms.py --help)
set_tests_properties(package_scripts_installed PROPERTIES LABELS regression FIXTURES_REQUIRED package_installed
                     PASS_REGULAR_EXPRESSION "plot-quality-histograms.py REPORT.json")
