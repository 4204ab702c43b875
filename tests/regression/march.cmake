# The boundary layer of the ONERA M6 case through the command line at a small surface
# resolution (64 x 16 wing faces), checked by the independent checker: zero
# non-positive volumes, conforming, closed boundary, every boundary face tagged. With
# the wake sheet, the tip trailing edge is a junction of the sheet's free edge with the
# tip cap: the layers alone are closed there only because the cap triangle at that node
# marches on both sheet lines (docs/march.md, Junction); before, the gap between the
# three lines there reached the wall and left two non-manifold boundary edges. Bad
# [march] input is rejected with one line naming the config.
set(march_output ${CMAKE_CURRENT_BINARY_DIR}/march_regression)
file(MAKE_DIRECTORY ${march_output})
set(march_small --set surface.chordwise_cells=64 --set surface.spanwise_cells=16)

# march_checked(NAME OUTPUT ARGS...): `mixmesh march ARGS -o OUTPUT` must finish with no
# face stopped, and NAME_check judges OUTPUT with the independent checker.
function(march_checked name output)
  add_test(NAME ${name} COMMAND $<TARGET_FILE:mixmesh-cli> march ${ARGN} -o ${output})
  set_tests_properties(${name} PROPERTIES LABELS regression FAIL_REGULAR_EXPRESSION "faces stopped at layer"
                                          FIXTURES_SETUP ${name})
  add_test(NAME ${name}_check COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${output} --no-foam)
  set_tests_properties(${name}_check PROPERTIES LABELS regression FIXTURES_REQUIRED ${name})
endfunction()

march_checked(march_onera_m6_small_without_wake ${march_output}/onera_m6_small_without_wake.vtu
              ${PROJECT_SOURCE_DIR}/cases/onera_m6.toml ${march_small} --set surface.wake.enabled=false)
march_checked(march_onera_m6_small ${march_output}/onera_m6_small_layers.vtu
              ${PROJECT_SOURCE_DIR}/cases/onera_m6.toml ${march_small} --set surface.wake.length=2.0 --compare)

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

# Wing variants of cases/batch/wing_variants.toml that used to fail after the march, run
# through the whole pipeline at a small size and checked by the independent checker:
# - taper 0.3 (48 x 8 faces): the trailing-edge cells at the tip are twisted by more than
#   they are thick; no centre split is valid and the interface caps them with a raised
#   pyramid;
# - taper 1, no sweep (64 x 16 faces): the lines at the wake's downstream end stay in its
#   plane to the last bit; drifting 1e-15 off it, they made the far field fill the nearly
#   flat hull there with slivers that validation rejects.
set(march_variant --set wing.naca="0008" --set wing.leading_edge_sweep=0.0 --set wing.tip_twist=5.0
                  --set march.layers=24)
add_test(NAME march_wing_tip_trailing_edge_taper_0_3
         COMMAND $<TARGET_FILE:mixmesh-cli> generate ${PROJECT_SOURCE_DIR}/cases/batch/wing_variants.toml
                 ${march_variant} --set wing.taper=0.3 --set surface.chordwise_cells=48
                 --set surface.spanwise_cells=8 --output-dir ${march_output}/tip_trailing_edge --quiet)
set_tests_properties(march_wing_tip_trailing_edge_taper_0_3 PROPERTIES LABELS regression)
add_test(NAME march_wing_tip_trailing_edge_taper_0_3_check
         COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${march_output}/tip_trailing_edge/wing_variants.vtu --no-foam)
set_property(TEST march_wing_tip_trailing_edge_taper_0_3 APPEND PROPERTY FIXTURES_SETUP march_wing_tip_trailing_edge_taper_0_3)
set_tests_properties(march_wing_tip_trailing_edge_taper_0_3_check PROPERTIES LABELS regression
                     FIXTURES_REQUIRED march_wing_tip_trailing_edge_taper_0_3)

add_test(NAME march_wing_wake_end_in_plane_taper_1
         COMMAND $<TARGET_FILE:mixmesh-cli> generate ${PROJECT_SOURCE_DIR}/cases/batch/wing_variants.toml
                 ${march_variant} --set wing.taper=1.0 --output-dir ${march_output}/wake_end --quiet)
set_tests_properties(march_wing_wake_end_in_plane_taper_1 PROPERTIES LABELS regression)
add_test(NAME march_wing_wake_end_in_plane_taper_1_check
         COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${march_output}/wake_end/wing_variants.vtu --no-foam)
set_property(TEST march_wing_wake_end_in_plane_taper_1 APPEND PROPERTY FIXTURES_SETUP march_wing_wake_end_in_plane_taper_1)
set_tests_properties(march_wing_wake_end_in_plane_taper_1_check PROPERTIES LABELS regression
                     FIXTURES_REQUIRED march_wing_wake_end_in_plane_taper_1)

# The half-base quads at a cranked wing's kink (a forward-swept outboard trailing edge)
# join the lines on their own side of the wake sheet: measured along their long edge
# on the sheet, both came out on one side and the march stopped with "shared by 4 faces
# on one side".
march_checked(march_cranked_base_with_wake ${march_output}/cranked_base.vtu
              ${CMAKE_CURRENT_LIST_DIR}/march_cranked_base.toml)

# A line that starts below the plane of one of its wall faces takes the direction that
# sees them all (in the symmetry plane for a line there): the swept sharp trailing
# edge's line on the plane leaned under the upper surface's last face.
march_checked(march_swept_sharp_edge_on_the_plane ${march_output}/swept_sharp_edge.vtu
              ${CMAKE_CURRENT_LIST_DIR}/march_swept_sharp_edge.toml)
