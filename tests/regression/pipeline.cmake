# The whole generator on a coarse ONERA M6 (64 x 16 wing faces, 32 layers), checked
# by the independent checker; a bad config fails with its position; a batch of two
# swept wings runs two at a time.
set(pipeline_folder ${PROJECT_BINARY_DIR}/regression/pipeline)
add_test(NAME pipeline_generate_onera_m6_coarse
         COMMAND mixmesh-cli generate ${PROJECT_SOURCE_DIR}/cases/onera_m6.toml
                 --set surface.chordwise_cells=64 --set surface.spanwise_cells=16
                 --set "output.formats=[\"vtu\",\"su2\"]"
                 --output-dir ${pipeline_folder} --report ${pipeline_folder}/report.toml)
set_tests_properties(pipeline_generate_onera_m6_coarse PROPERTIES LABELS regression
                     FIXTURES_SETUP pipeline_mesh
                     PASS_REGULAR_EXPRESSION "points [0-9]+  surface elements [0-9]+  hexahedra [1-9][0-9]*  tetrahedra [1-9][0-9]*  prisms [1-9][0-9]*  pyramids [1-9][0-9]*")
foreach(format vtu su2)
  add_test(NAME pipeline_check_mesh_onera_m6_coarse_${format}
           COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${pipeline_folder}/onera_m6.${format} --no-foam -q)
  set_tests_properties(pipeline_check_mesh_onera_m6_coarse_${format} PROPERTIES LABELS regression
                       FIXTURES_REQUIRED pipeline_mesh PASS_REGULAR_EXPRESSION "\nVALID")
endforeach()
add_test(NAME pipeline_own_check_onera_m6_coarse COMMAND mixmesh-cli check ${pipeline_folder}/onera_m6.vtu -q)
set_tests_properties(pipeline_own_check_onera_m6_coarse PROPERTIES LABELS regression FIXTURES_REQUIRED pipeline_mesh)
# Counts within about a fifth of today's (97,924 points, 70,959 hexahedra, 106,639
# tetrahedra, 2,886 prisms, 11,054 pyramids: thin outer cells split in stacks, see
# docs/interface.md), every layer grown, no retry, and the sliver floor of
# docs/robustness.md (largest dihedral 171.3 today).
add_test(NAME pipeline_report_onera_m6_coarse_ranges
         COMMAND ${MIXMESH_PYTHON} ${CMAKE_CURRENT_LIST_DIR}/pipeline/check_generate_report.py
                 ${pipeline_folder}/report.toml points=80000:120000 hexahedra=60000:85000
                 tetrahedra=80000:140000 prisms=2300:3500 pyramids=9000:13300 layers_completed=32:32
                 stopped_faces=0:0 hull_retries=0:0 min_scaled_jacobian=1e-9: largest_dihedral=:175)
set_tests_properties(pipeline_report_onera_m6_coarse_ranges PROPERTIES LABELS regression
                     FIXTURES_REQUIRED pipeline_mesh PASS_REGULAR_EXPRESSION "report ok")

add_test(NAME pipeline_bad_config_names_its_position
         COMMAND mixmesh-cli generate ${CMAKE_CURRENT_LIST_DIR}/pipeline/bad_march.toml
                 --output-dir ${pipeline_folder}/bad)
set_tests_properties(pipeline_bad_config_names_its_position PROPERTIES LABELS regression
                     PASS_REGULAR_EXPRESSION "bad_march.toml:8:10: 'march.layers' = 0 must be >= 1")

add_test(NAME pipeline_batch_sweep_two_jobs
         COMMAND mixmesh-cli batch ${CMAKE_CURRENT_LIST_DIR}/pipeline/swept_wings.toml -j 2
                 -o ${pipeline_folder}/batch)
set_tests_properties(pipeline_batch_sweep_two_jobs PROPERTIES LABELS regression
                     PASS_REGULAR_EXPRESSION "batch: 2 ok, 0 failed")

# Mesh-then-deform: a generated wing pitched by its [[deform]] steps (ARA, one step and
# a three-step ramp); the last deformed mesh checked by the independent checker.
add_test(NAME pipeline_generate_then_deform
         COMMAND mixmesh-cli generate ${PROJECT_SOURCE_DIR}/cases/pipeline/wing_pitch.toml
                 --output-dir ${pipeline_folder}/deform --report ${pipeline_folder}/deform/report.toml)
set_tests_properties(pipeline_generate_then_deform PROPERTIES LABELS regression FIXTURES_SETUP deformed_mesh
                     PASS_REGULAR_EXPRESSION "deform ramp step 3/3: largest displacement 0\\.[1-9][^\n]*\n.*wrote [^\n]*wing_pitch_ramp_0003.vtu"
                     FAIL_REGULAR_EXPRESSION "mixmesh: error|INVALID")
add_test(NAME pipeline_check_mesh_deformed
         COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${pipeline_folder}/deform/wing_pitch_ramp_0003.vtu
                 --no-foam -q)
set_tests_properties(pipeline_check_mesh_deformed PROPERTIES LABELS regression
                     FIXTURES_REQUIRED deformed_mesh PASS_REGULAR_EXPRESSION "\nVALID")
add_test(NAME pipeline_report_lists_deformed_meshes
         COMMAND ${MIXMESH_PYTHON} ${CMAKE_CURRENT_LIST_DIR}/pipeline/check_deform_report.py
                 ${pipeline_folder}/deform/report.toml wing_pitch_pitch wing_pitch_ramp_0001 wing_pitch_ramp_0002
                 wing_pitch_ramp_0003)
set_tests_properties(pipeline_report_lists_deformed_meshes PROPERTIES LABELS regression
                     FIXTURES_REQUIRED deformed_mesh PASS_REGULAR_EXPRESSION "report ok")

# A [[deform]] step whose mesh stays inverted (the wing moved through the far field)
# fails naming the config line and the step, and writes no file at all, not even the
# generated mesh or the steps before it.
add_test(NAME pipeline_failed_deform_writes_nothing
         COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:mixmesh-cli>
                 -DCONFIG=${CMAKE_CURRENT_LIST_DIR}/pipeline/wing_through_farfield.toml
                 -DFOLDER=${pipeline_folder}/failed_deform -P ${CMAKE_CURRENT_LIST_DIR}/pipeline/expect_no_files.cmake)
set_tests_properties(pipeline_failed_deform_writes_nothing PROPERTIES LABELS regression
                     PASS_REGULAR_EXPRESSION "wing_through_farfield.toml:[0-9]+:[0-9]+: \\[\\[deform\\]\\] 'through': step 1: [0-9]+ cells stay inverted")

# The same on the ONERA M6 case with its wake (cases/pipeline/onera_m6_pitch.toml):
# the mixed mesh and a four-step 3-degree pitch with ARA, the last mesh checked by
# meshio, VTK and checkMesh. About 40 s for the mesh and its steps and 10 s for the
# check: heavy.
add_test(NAME pipeline_onera_m6_generate_then_deform
         COMMAND mixmesh-cli generate ${PROJECT_SOURCE_DIR}/cases/pipeline/onera_m6_pitch.toml
                 --output-dir ${pipeline_folder}/onera_m6_pitch)
set_tests_properties(pipeline_onera_m6_generate_then_deform PROPERTIES LABELS "regression;heavy"
                     FIXTURES_SETUP onera_m6_pitched
                     PASS_REGULAR_EXPRESSION "wrote [^\n]*onera_m6_pitch_pitch_0004.vtu"
                     FAIL_REGULAR_EXPRESSION "mixmesh: error|INVALID")
add_test(NAME pipeline_check_mesh_onera_m6_pitched
         COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH}
                 ${pipeline_folder}/onera_m6_pitch/onera_m6_pitch_pitch_0004.vtu -q)
set_tests_properties(pipeline_check_mesh_onera_m6_pitched PROPERTIES LABELS "regression;heavy"
                     FIXTURES_REQUIRED onera_m6_pitched PASS_REGULAR_EXPRESSION "\nVALID")

# A hull that intersects itself is mended by lowering the layers round the crossing:
# growth stops at the tip's trailing edge of a strongly tapered wing (taper 0.21) at layer
# 23, and the hull crosses itself there; stopping the layers within reach at layer 18
# (where the stack is half as thick as the crossing is high, not half the layers, 14)
# clears it on the first retry. (The wings this test used before, a cranked wing and then
# a blunt base with a wake, mesh without a retry since the march's lines see every wall
# face they start from and the stacks round a base's corners are thinner.)
add_test(NAME pipeline_hull_crossing_lowers_the_layers
         COMMAND mixmesh-cli generate ${CMAKE_CURRENT_LIST_DIR}/pipeline/tip_stop_wing.toml
                 --output-dir ${pipeline_folder}/hull_crossing
                 --report ${pipeline_folder}/hull_crossing/report.toml)
set_tests_properties(pipeline_hull_crossing_lowers_the_layers PROPERTIES LABELS regression
                     FIXTURES_SETUP hull_crossing_mesh
                     PASS_REGULAR_EXPRESSION "the hull intersects itself near [^\n]* stop by layer 18 \\(retry 1 of 3\\).*points [0-9]+  surface elements")
add_test(NAME pipeline_check_mesh_hull_crossing
         COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${pipeline_folder}/hull_crossing/tip_stop_wing.vtu -q)
set_tests_properties(pipeline_check_mesh_hull_crossing PROPERTIES LABELS regression
                     FIXTURES_REQUIRED hull_crossing_mesh PASS_REGULAR_EXPRESSION "\nVALID")
add_test(NAME pipeline_report_counts_hull_retries
         COMMAND ${CMAKE_COMMAND} -E cat ${pipeline_folder}/hull_crossing/report.toml)
set_tests_properties(pipeline_report_counts_hull_retries PROPERTIES LABELS regression
                     FIXTURES_REQUIRED hull_crossing_mesh PASS_REGULAR_EXPRESSION "\nhull_retries = 1\n")

# A wing of tests/regression/pipeline/CONFIG.toml generated into FOLDER (test GENERATE_TEST,
# passing on EXPECTED) and its mesh judged VALID by the independent checker (CHECK_TEST).
function(pipeline_wing_case generate_test check_test config folder expected)
  add_test(NAME ${generate_test}
           COMMAND mixmesh-cli generate ${CMAKE_CURRENT_LIST_DIR}/pipeline/${config}.toml
                   --output-dir ${pipeline_folder}/${folder})
  set_tests_properties(${generate_test} PROPERTIES LABELS regression FIXTURES_SETUP ${folder}_mesh
                       PASS_REGULAR_EXPRESSION "${expected}")
  add_test(NAME ${check_test}
           COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${pipeline_folder}/${folder}/${config}.vtu -q)
  set_tests_properties(${check_test} PROPERTIES LABELS regression FIXTURES_REQUIRED ${folder}_mesh
                       PASS_REGULAR_EXPRESSION "\nVALID")
endfunction()

# A blunt base with a wake (random wing 2 of seed 11 at 80 x 16 wing faces): the base's
# lines and the sheet's first lines met in the concave corner between them, growth
# stopped along the base and the hull crossed itself (two retries). The lines near the
# corners march in thinner stacks: every layer grows, no retry, and the mesh is valid.
pipeline_wing_case(pipeline_blunt_base_with_a_wake_grows_every_layer pipeline_check_mesh_base_and_wake
                   base_and_wake_wing base_and_wake
                   "28/28 layers.*lines near a blunt base's corners with the wake in thinner stacks.*points [0-9]+  surface elements")
set_tests_properties(pipeline_blunt_base_with_a_wake_grows_every_layer PROPERTIES
                     FAIL_REGULAR_EXPRESSION "growth stopped|intersects itself|retry")

# An outer cell that can be neither split nor capped (twisted more than it is thick, at
# a tip's trailing edge where the growth stopped early) is a place to lower the layers,
# like a hull crossing: the wing meshes on the first retry (it failed with the
# interface's error before).
pipeline_wing_case(pipeline_unsplittable_cell_lowers_the_layers pipeline_check_mesh_unsplittable_cell
                   unsplittable_tip_cell_wing unsplittable_cell
                   "interface: a cell neither split nor capped; [^\n]* stop by layer 16 \\(retry 1 of 3\\).*points [0-9]+  surface elements")

# TetGen aborting on the anisotropic far field (tests/regression/pipeline/
# tetgen_abort_wing.toml, with the abort injected into the first TetGen run): generate
# falls back to isotropic sizing, and the mesh is valid.
pipeline_wing_case(pipeline_tetgen_abort_falls_back_to_isotropic pipeline_check_mesh_tetgen_abort
                   tetgen_abort_wing tetgen_abort
                   "TetGen crashed [^\n]*; building the far field with isotropic sizing instead.*points [0-9]+  surface elements")
set_tests_properties(pipeline_tetgen_abort_falls_back_to_isotropic PROPERTIES ENVIRONMENT MIXMESH_TETGEN_ABORT=1)

# The default ONERA M6 mesh (cases/onera_m6.toml, anisotropic far field) keeps its
# slivers down: the largest dihedral angle under 178.5 deg and under 0.5 % of the
# tetrahedra above the sliver pass's 160 deg (177.7 deg and 0.30 % when this test was
# written; 178.9 deg and 1.26 % before the point collapse and the taller wake caps).
# About 20 s: heavy.
add_test(NAME pipeline_generate_onera_m6_default
         COMMAND mixmesh-cli generate ${PROJECT_SOURCE_DIR}/cases/onera_m6.toml --quiet
                 --output-dir ${pipeline_folder}/onera_m6_default
                 --report ${pipeline_folder}/onera_m6_default/report.toml)
set_tests_properties(pipeline_generate_onera_m6_default PROPERTIES LABELS "regression;heavy"
                     FIXTURES_SETUP onera_m6_default FAIL_REGULAR_EXPRESSION "mixmesh: error")
add_test(NAME pipeline_onera_m6_default_slivers
         COMMAND ${MIXMESH_PYTHON} -c
                 "import sys, tomllib; r = tomllib.load(open(sys.argv[1], 'rb')); share = r['tetrahedra_above_target_dihedral'] / r['tetrahedra']; print('largest dihedral', r['largest_dihedral'], 'above 160 deg', share); sys.exit(0 if r['largest_dihedral'] < 178.5 and share < 0.005 else 1)"
                 ${pipeline_folder}/onera_m6_default/report.toml)
set_tests_properties(pipeline_onera_m6_default_slivers PROPERTIES LABELS "regression;heavy"
                     FIXTURES_REQUIRED onera_m6_default)


# --dump-stages makes its folder when it is missing (it failed late, after the march,
# with "cannot open for writing").
add_test(NAME pipeline_dump_stages_makes_its_folder
         COMMAND ${CMAKE_COMMAND} -DPROGRAM=$<TARGET_FILE:mixmesh-cli>
                 -DCONFIG=${CMAKE_CURRENT_LIST_DIR}/pipeline/base_and_wake_wing.toml
                 -DFOLDER=${pipeline_folder}/dump_stages -P ${CMAKE_CURRENT_LIST_DIR}/pipeline/dump_stages.cmake)
set_tests_properties(pipeline_dump_stages_makes_its_folder PROPERTIES LABELS regression)
