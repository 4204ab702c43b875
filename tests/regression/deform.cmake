# Deformation cases: the NACA 0012 pitch (ARA with rotation terms and the original
# translation-only predictor) and the wing under a bending + twist mode shape.
set(deform_output ${CMAKE_CURRENT_BINARY_DIR}/deform)
file(MAKE_DIRECTORY ${deform_output})
set(naca_case ${PROJECT_SOURCE_DIR}/cases/naca0012)
set(wing_case ${PROJECT_SOURCE_DIR}/cases/wing)

# 0 → 20° in 5° steps: every step valid (the command fails otherwise), and at 20° the
# wall-normal grid lines of the airfoil turn with it to within 2°.
add_test(NAME deform_naca0012_pitch
         COMMAND mixmesh-cli deform ${naca_case}/naca0012.msh --motion ${naca_case}/pitch.toml
                 -o ${deform_output}/naca0012_pitch.vtu)
set_tests_properties(deform_naca0012_pitch PROPERTIES LABELS regression
  PASS_REGULAR_EXPRESSION "step 4: wall-line angle change: moving walls [01]\\.[0-9]+ deg"
  FAIL_REGULAR_EXPRESSION "error|INVALID")

# The same with the translation-only predictor: the wall lines skew by more than 2°.
add_test(NAME deform_naca0012_pitch_translation_only
         COMMAND mixmesh-cli deform ${naca_case}/naca0012.msh --motion ${naca_case}/pitch_translation_only.toml
                 --keep-invalid -o ${deform_output}/naca0012_pitch_translation.vtu)
set_tests_properties(deform_naca0012_pitch_translation_only PROPERTIES LABELS regression
  PASS_REGULAR_EXPRESSION "step 4: wall-line angle change: moving walls ([2-9]|[1-9][0-9]+)\\.[0-9]+ deg")

# The independent checker on the 20° mesh, and the leading-edge angles of both runs.
add_test(NAME deform_naca0012_pitch_leading_edge
         COMMAND ${MIXMESH_PYTHON} ${CMAKE_CURRENT_LIST_DIR}/deform_wall_angles.py ${naca_case}/naca0012.msh
                 ${deform_output}/naca0012_pitch_0004.vtu --marker airfoil --at-most 2.0)
set_property(TEST deform_naca0012_pitch APPEND PROPERTY FIXTURES_SETUP deform_naca0012_pitch)
set_tests_properties(deform_naca0012_pitch_leading_edge PROPERTIES LABELS regression
  FIXTURES_REQUIRED deform_naca0012_pitch)

# Wing, bending + twist mode with sliding root and tip planes: valid by check_mesh.py.
add_test(NAME deform_wing_bend_twist
         COMMAND mixmesh-cli deform ${wing_case}/wing.msh --motion ${wing_case}/bend_twist.toml
                 -o ${deform_output}/wing_bend_twist.vtu)
set_tests_properties(deform_wing_bend_twist PROPERTIES LABELS regression FAIL_REGULAR_EXPRESSION "error|INVALID")
add_test(NAME deform_wing_bend_twist_check
         COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} --no-foam -q ${deform_output}/wing_bend_twist.vtu)
set_property(TEST deform_wing_bend_twist APPEND PROPERTY FIXTURES_SETUP deform_wing_bend_twist)
set_tests_properties(deform_wing_bend_twist_check PROPERTIES LABELS regression FIXTURES_REQUIRED deform_wing_bend_twist)

# The quasi-2D viscous NACA 0012 (one cell thick between sliding planes, first layer
# 1e-5 chords) pitched 90° in one step with ARA: valid by the independent checker
# including checkMesh, and the wall-normal lines turn with the airfoil to within 2°
# (they are found on the planes).
add_test(NAME deform_quasi2d_pitch
         COMMAND mixmesh-cli deform ${wing_case}/quasi2d.msh --motion ${wing_case}/quasi2d_pitch.toml
                 -o ${deform_output}/quasi2d_pitched.vtu)
set_tests_properties(deform_quasi2d_pitch PROPERTIES LABELS regression FIXTURES_SETUP quasi2d_pitched
  PASS_REGULAR_EXPRESSION "step 1: wall-line angle change: moving walls [01]\\.[0-9]+ deg"
  FAIL_REGULAR_EXPRESSION "error|INVALID|moving walls 0\\.000 deg")
add_test(NAME deform_quasi2d_pitch_check
         COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} -q ${deform_output}/quasi2d_pitched.vtu)
set_tests_properties(deform_quasi2d_pitch_check PROPERTIES LABELS regression FIXTURES_REQUIRED quasi2d_pitched)

# A structured C-mesh of the NACA 0012 with its wake cut, first cell 1e-5 chords, one
# hexahedron thick (cases/cmesh/make_cmesh.py, made here): pitched 45° with ARA and 90°
# with IDW in one step, each valid by the independent checker including checkMesh.
add_test(NAME deform_cmesh_make
         COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/cases/cmesh/make_cmesh.py --output ${deform_output}/cmesh.msh)
set_tests_properties(deform_cmesh_make PROPERTIES LABELS regression FIXTURES_SETUP cmesh)
foreach(method ara idw)
  add_test(NAME deform_cmesh_pitch_${method}
           COMMAND mixmesh-cli deform ${deform_output}/cmesh.msh --motion ${PROJECT_SOURCE_DIR}/cases/cmesh/pitch_${method}.toml
                   -o ${deform_output}/cmesh_pitched_${method}.vtu)
  set_tests_properties(deform_cmesh_pitch_${method} PROPERTIES LABELS regression FIXTURES_REQUIRED cmesh
    FIXTURES_SETUP cmesh_${method} FAIL_REGULAR_EXPRESSION "error|INVALID")
  add_test(NAME deform_cmesh_pitch_${method}_check
           COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} -q ${deform_output}/cmesh_pitched_${method}.vtu)
  set_tests_properties(deform_cmesh_pitch_${method}_check PROPERTIES LABELS regression FIXTURES_REQUIRED cmesh_${method})
endforeach()

# Bad input fails with one line and writes nothing.
add_test(NAME deform_rejects_unknown_marker
         COMMAND mixmesh-cli deform ${naca_case}/naca0012.msh --motion ${CMAKE_CURRENT_LIST_DIR}/deform_unknown_marker.toml
                 -o ${deform_output}/never_written.vtu)
set_tests_properties(deform_rejects_unknown_marker PROPERTIES LABELS regression WILL_FAIL TRUE)

# Without --keep-invalid the translation-only run fails at 10° with the inverted cells.
add_test(NAME deform_naca0012_translation_only_fails
         COMMAND mixmesh-cli deform ${naca_case}/naca0012.msh --motion ${naca_case}/pitch_translation_only.toml
                 -o ${deform_output}/naca0012_never_written.vtu)
set_tests_properties(deform_naca0012_translation_only_fails PROPERTIES LABELS regression
  PASS_REGULAR_EXPRESSION "step 2: [0-9]+ cells stay inverted after repair; (triangle|quad) [0-9]+ at \\(")

# The motions of issue #15 on the default ONERA M6 mesh with its wake, each in one step
# (cases/pipeline/onera_m6_motions.toml: IDW and ARA, pitch +-15 degrees and a plunge of
# half the root chord; then the bending mode of scripts/wing-motions.py on the generated
# mesh with both methods), each deformed mesh judged by the independent checker. Heavy:
# about three minutes (docs/deform.md, "Motions of issue #15").
# A mesh-then-deform case of cases/pipeline, NAME.toml, run by `mixmesh generate` (heavy):
# it passes when NAME_LAST.vtu is written, and the independent checker judges each
# NAME_<mesh>.vtu of the remaining arguments.
function(pipeline_deform_case name last)
  set(output ${CMAKE_CURRENT_BINARY_DIR}/deform_${name})
  add_test(NAME deform_${name}
           COMMAND mixmesh-cli generate ${PROJECT_SOURCE_DIR}/cases/pipeline/${name}.toml --output-dir ${output})
  set_tests_properties(deform_${name} PROPERTIES LABELS "regression;heavy" FIXTURES_SETUP deform_${name}
                       PASS_REGULAR_EXPRESSION "wrote [^\n]*${name}_${last}.vtu"
                       FAIL_REGULAR_EXPRESSION "mixmesh: error|INVALID")
  foreach(mesh ${ARGN})
    add_test(NAME deform_${name}_check_${mesh}
             COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${output}/${name}_${mesh}.vtu --no-foam -q)
    set_tests_properties(deform_${name}_check_${mesh} PROPERTIES LABELS "regression;heavy"
                         FIXTURES_REQUIRED deform_${name} PASS_REGULAR_EXPRESSION "\nVALID")
  endforeach()
endfunction()

set(m6_motions_output ${CMAKE_CURRENT_BINARY_DIR}/deform_onera_m6_motions)
pipeline_deform_case(onera_m6_motions plunge_ara pitch_up pitch_down plunge pitch_up_ara pitch_down_ara plunge_ara)
add_test(NAME deform_onera_m6_motions_bend_files
         COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/wing-motions.py
                 ${m6_motions_output}/onera_m6_motions.vtu ${m6_motions_output}/motions 0.2 0.8059 1.1963)
set_tests_properties(deform_onera_m6_motions_bend_files PROPERTIES LABELS "regression;heavy"
                     FIXTURES_REQUIRED deform_onera_m6_motions FIXTURES_SETUP deform_onera_m6_bend_files)
foreach(method ara idw)
  add_test(NAME deform_onera_m6_motions_bend_${method}
           COMMAND mixmesh-cli deform ${m6_motions_output}/onera_m6_motions.vtu
                   --motion ${m6_motions_output}/motions/bend_${method}.toml
                   -o ${m6_motions_output}/onera_m6_motions_bend_${method}.vtu)
  set_tests_properties(deform_onera_m6_motions_bend_${method} PROPERTIES LABELS "regression;heavy"
                       FIXTURES_REQUIRED deform_onera_m6_bend_files
                       FIXTURES_SETUP deform_onera_m6_bend_${method}
                       FAIL_REGULAR_EXPRESSION "mixmesh: error|INVALID")
  add_test(NAME deform_onera_m6_motions_check_bend_${method}
           COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH}
                   ${m6_motions_output}/onera_m6_motions_bend_${method}.vtu --no-foam -q)
  set_tests_properties(deform_onera_m6_motions_check_bend_${method} PROPERTIES LABELS "regression;heavy"
                       FIXTURES_REQUIRED deform_onera_m6_bend_${method} PASS_REGULAR_EXPRESSION "\nVALID")
endforeach()

# The ONERA M6 in a pitch–plunge cycle (cases/pipeline/onera_m6_pitch_plunge.toml:
# ±10°, ±0.5 root chord, 8 steps each from the generated mesh, IDW and ARA); the
# independent checker judges the four extreme steps of each method. Heavy: about two
# minutes for the generation and the 16 steps.
pipeline_deform_case(onera_m6_pitch_plunge ara_0008 idw_0002 idw_0004 idw_0006 idw_0008 ara_0002 ara_0004 ara_0006
                     ara_0008)
