# The boundary layer of the ONERA M6 case through the command line at a small surface
# resolution (64 x 16 wing faces), checked by the independent checker: zero
# non-positive volumes, conforming, closed boundary. With the wake sheet the layers are
# marched too (no column may stop), but the boundary of the layers alone has two
# non-manifold edges at the tip trailing edge (docs/march.md, Limits), so the
# independent check runs on the case without wake. Bad [march] input is rejected with
# one line naming the config.
set(march_output ${CMAKE_CURRENT_BINARY_DIR}/march_regression)
file(MAKE_DIRECTORY ${march_output})
set(march_small --set surface.chordwise_cells=64 --set surface.spanwise_cells=16)

add_test(NAME march_onera_m6_small_without_wake
         COMMAND $<TARGET_FILE:mixmesh-cli> march ${PROJECT_SOURCE_DIR}/cases/onera_m6.toml ${march_small}
                 --set surface.wake.enabled=false -o ${march_output}/onera_m6_small_without_wake.vtu)
set_tests_properties(march_onera_m6_small_without_wake PROPERTIES LABELS regression
                     FAIL_REGULAR_EXPRESSION "faces stopped at layer")
add_test(NAME march_onera_m6_small_without_wake_check
         COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${march_output}/onera_m6_small_without_wake.vtu --no-foam)
set_tests_properties(march_onera_m6_small_without_wake_check PROPERTIES LABELS regression
                     DEPENDS march_onera_m6_small_without_wake)

add_test(NAME march_onera_m6_small
         COMMAND $<TARGET_FILE:mixmesh-cli> march ${PROJECT_SOURCE_DIR}/cases/onera_m6.toml ${march_small}
                 --set surface.wake.length=2.0 -o ${march_output}/onera_m6_small_layers.vtu --compare)
set_tests_properties(march_onera_m6_small PROPERTIES LABELS regression
                     FAIL_REGULAR_EXPRESSION "faces stopped at layer")

add_test(NAME march_onera_m6_full
         COMMAND $<TARGET_FILE:mixmesh-cli> march ${PROJECT_SOURCE_DIR}/cases/onera_m6.toml
                 -o ${march_output}/onera_m6_layers.vtu)
set_tests_properties(march_onera_m6_full PROPERTIES LABELS "regression;heavy"
                     FAIL_REGULAR_EXPRESSION "faces stopped at layer")

add_test(NAME march_rejects_bad_growth
         COMMAND $<TARGET_FILE:mixmesh-cli> march ${PROJECT_SOURCE_DIR}/cases/onera_m6.toml --set march.growth_rate=0.5
                 -o ${march_output}/never_written.vtu)
set_tests_properties(march_rejects_bad_growth PROPERTIES LABELS regression
                     PASS_REGULAR_EXPRESSION "growth_rate")
