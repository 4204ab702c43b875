# The pictures of `mixmesh compare`, made headless by the scripts: a cut through a
# Gmsh block with all four cell types must show each type's colour, and the bar chart
# of Wild's Table 1 must come out at the requested size and not blank. Bad input to
# the scripts and to the command fails with one line.
set(compare_output ${CMAKE_CURRENT_BINARY_DIR}/compare_regression)
file(MAKE_DIRECTORY ${compare_output})
set(compare_check ${CMAKE_CURRENT_LIST_DIR}/compare_picture_check.py)

add_test(NAME compare_cut_picture
         COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/plot-mesh-cut.py
                 ${PROJECT_SOURCE_DIR}/cases/meshes/mixed_block.msh --axis y --position 0.43 --size 1200x700
                 --zoom 0.8 1.2 0.2 0.4 -o ${compare_output}/mixed_block_cut.png)
add_test(NAME compare_cut_picture_check
         COMMAND ${MIXMESH_PYTHON} ${compare_check} ${compare_output}/mixed_block_cut.png --size 1200x700
                 --cell-types hexahedron wedge tetra pyramid)
set_property(TEST compare_cut_picture APPEND PROPERTY FIXTURES_SETUP compare_cut_picture)
set_tests_properties(compare_cut_picture_check PROPERTIES FIXTURES_REQUIRED compare_cut_picture)

# A cut through the prism half only: no hexahedron or pyramid colour may appear.
add_test(NAME compare_cut_picture_window
         COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/plot-mesh-cut.py
                 ${PROJECT_SOURCE_DIR}/cases/meshes/mixed_block.msh --axis x --position 1.6 --size 800x600
                 -o ${compare_output}/mixed_block_cut_x.png)
add_test(NAME compare_cut_picture_window_check
         COMMAND ${MIXMESH_PYTHON} ${compare_check} ${compare_output}/mixed_block_cut_x.png --size 800x600
                 --cell-types wedge tetra --absent-cell-types hexahedron pyramid)
set_property(TEST compare_cut_picture_window APPEND PROPERTY FIXTURES_SETUP compare_cut_picture_window)
set_tests_properties(compare_cut_picture_window_check PROPERTIES FIXTURES_REQUIRED compare_cut_picture_window)

add_test(NAME compare_bar_chart
         COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/plot-compare.py
                 ${CMAKE_CURRENT_LIST_DIR}/compare/wild_table1.csv --size 1400x600 -o ${compare_output}/bars.png)
add_test(NAME compare_bar_chart_check
         COMMAND ${MIXMESH_PYTHON} ${compare_check} ${compare_output}/bars.png --size 1400x600)
set_property(TEST compare_bar_chart APPEND PROPERTY FIXTURES_SETUP compare_bar_chart)
set_tests_properties(compare_bar_chart_check PROPERTIES FIXTURES_REQUIRED compare_bar_chart)

# The hybrid's isotropic surface alone (fast): the ONERA M6 wing at half the chordwise
# resolution, i.e. twice the default edge length.
add_test(NAME compare_hybrid_surface
         COMMAND $<TARGET_FILE:mixmesh-cli> compare ${PROJECT_SOURCE_DIR}/cases/onera_m6.toml --hybrid-surface-only
                 --set surface.chordwise_cells=100 --output-dir ${compare_output})
set_tests_properties(compare_hybrid_surface PROPERTIES
                     PASS_REGULAR_EXPRESSION "hybrid surface: [0-9]+ triangles, [0-9]+ points, edge length mean 0.01[12]")

# Bad input: a plane that misses the mesh, a missing CSV, an unknown config key, an
# empty close-up window.
add_test(NAME compare_cut_misses_mesh
         COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/plot-mesh-cut.py
                 ${PROJECT_SOURCE_DIR}/cases/meshes/mixed_block.msh --axis z --position 5 -o ${compare_output}/none.png)
set_tests_properties(compare_cut_misses_mesh PROPERTIES PASS_REGULAR_EXPRESSION "no volume cell crosses the plane z = 5")
add_test(NAME compare_cut_empty_zoom
         COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/plot-mesh-cut.py
                 ${PROJECT_SOURCE_DIR}/cases/meshes/mixed_block.msh --zoom 1 0.5 0 1 -o ${compare_output}/none.png)
set_tests_properties(compare_cut_empty_zoom PROPERTIES PASS_REGULAR_EXPRESSION "--zoom needs HMIN < HMAX")
add_test(NAME compare_bars_missing_table
         COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/plot-compare.py ${compare_output}/absent.csv
                 -o ${compare_output}/none.png)
set_tests_properties(compare_bars_missing_table PROPERTIES PASS_REGULAR_EXPRESSION "absent.csv: No such file")
add_test(NAME compare_bad_config
         COMMAND $<TARGET_FILE:mixmesh-cli> compare ${PROJECT_SOURCE_DIR}/cases/onera_m6.toml --set farfield.colour=1
                 --output-dir ${compare_output} --no-pictures)
set_tests_properties(compare_bad_config PROPERTIES PASS_REGULAR_EXPRESSION "unknown key 'farfield.colour'")

set_tests_properties(compare_cut_picture compare_cut_picture_check compare_cut_picture_window
                     compare_cut_picture_window_check compare_bar_chart compare_bar_chart_check
                     compare_hybrid_surface compare_cut_misses_mesh compare_cut_empty_zoom compare_bars_missing_table compare_bad_config
                     PROPERTIES LABELS regression)
