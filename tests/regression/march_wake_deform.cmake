# Mesh-then-deform of a wing with a wake sheet: the small swept wing of
# march_wake_deform.toml with its 5-chord wake, generated and pitched 3 degrees with
# ARA in two steps; the generated mesh and the last deformed mesh must pass the
# independent checker. With the wake's first spacing kept to the sheet's end and its
# hull cells split about centre points, ARA left 2,320 inverted cells and the
# run wrote nothing (docs/march.md, "Wake layers").
set(march_wake_output ${CMAKE_CURRENT_BINARY_DIR}/march_wake_deform)
file(MAKE_DIRECTORY ${march_wake_output})

add_test(NAME march_wake_deform
         COMMAND $<TARGET_FILE:mixmesh-cli> generate ${CMAKE_CURRENT_LIST_DIR}/march_wake_deform.toml
                 --output-dir ${march_wake_output})
set_tests_properties(march_wake_deform PROPERTIES LABELS regression FIXTURES_SETUP march_wake_deform
                     FAIL_REGULAR_EXPRESSION "faces stopped at layer")
add_test(NAME march_wake_deform_check_generated
         COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${march_wake_output}/march_wake_deform.vtu --no-foam)
add_test(NAME march_wake_deform_check_pitched
         COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${march_wake_output}/march_wake_deform_pitch_0002.vtu
                 --no-foam)
set_tests_properties(march_wake_deform_check_generated march_wake_deform_check_pitched PROPERTIES
                     LABELS regression FIXTURES_REQUIRED march_wake_deform)

# The same wing bent (scripts/wing-motions.py: 15 % of the semi-span, 5 degrees of tip
# twist) with ARA in one step. Its layers are 0.2 mm thick under faces 0.17 m long; when
# the layer transport spread ARA's offset at the tops along the lines, 202 cells stayed
# folded (docs/deform.md, "Layer stacks move with their base").
add_test(NAME march_wake_deform_bend_files
         COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/wing-motions.py
                 ${march_wake_output}/march_wake_deform.vtu ${march_wake_output}/motions 0.25 1.0 2.0)
set_tests_properties(march_wake_deform_bend_files PROPERTIES LABELS regression
                     FIXTURES_REQUIRED march_wake_deform FIXTURES_SETUP march_wake_deform_bend_files)
add_test(NAME march_wake_deform_bend_ara
         COMMAND $<TARGET_FILE:mixmesh-cli> deform ${march_wake_output}/march_wake_deform.vtu
                 --motion ${march_wake_output}/motions/bend_ara.toml -o ${march_wake_output}/bent_ara.vtu)
set_tests_properties(march_wake_deform_bend_ara PROPERTIES LABELS regression FAIL_REGULAR_EXPRESSION "error|INVALID"
                     FIXTURES_REQUIRED march_wake_deform_bend_files FIXTURES_SETUP march_wake_deform_bend_ara)
add_test(NAME march_wake_deform_bend_ara_check
         COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${march_wake_output}/bent_ara.vtu --no-foam)
set_tests_properties(march_wake_deform_bend_ara_check PROPERTIES LABELS regression
                     FIXTURES_REQUIRED march_wake_deform_bend_ara)
