# The robustness suite (scripts/robustness.sh): random ordinary wings from
# scripts/random-wings.py through `mixmesh generate` and the independent checker with
# OpenFOAM's checkMesh. Heavy: minutes per wing on two cores, and not yet passed (see
# docs/robustness.md).
#   robustness_wings_validity: 8 wings of seed 2; every one must mesh and check valid.
#   robustness_wings_floors:   48 wings of seed 3 against the quality floors as well.
set(robustness_output ${CMAKE_CURRENT_BINARY_DIR}/robustness)
add_test(NAME robustness_wings_validity
         COMMAND bash ${PROJECT_SOURCE_DIR}/scripts/robustness.sh 8 2 ${robustness_output}/seed-2 -j 2
                 --validity-only)
set_tests_properties(robustness_wings_validity PROPERTIES LABELS "regression;heavy"
                     ENVIRONMENT "MIXMESH=$<TARGET_FILE:mixmesh-cli>")
add_test(NAME robustness_wings_floors
         COMMAND bash ${PROJECT_SOURCE_DIR}/scripts/robustness.sh 48 3 ${robustness_output}/seed-3 -j 2)
set_tests_properties(robustness_wings_floors PROPERTIES LABELS "regression;heavy"
                     ENVIRONMENT "MIXMESH=$<TARGET_FILE:mixmesh-cli>")

# Quick: the generator's configs (both design spaces) are accepted and their surfaces build.
add_test(NAME robustness_configs_accepted
         COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/robustness/configs_accepted.sh $<TARGET_FILE:mixmesh-cli>
                 ${MIXMESH_PYTHON} ${robustness_output}/configs-accepted 40 7)
set_tests_properties(robustness_configs_accepted PROPERTIES LABELS "regression")
