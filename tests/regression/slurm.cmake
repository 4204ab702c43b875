# `mixmesh batch --slurm` on a real Slurm, never a mock: scripts/slurm-cluster.sh
# starts a one-node cluster with accounting on this machine (it must be installed:
# `scripts/slurm-cluster.sh install`, which scripts/test.sh runs) and stops it
# afterwards. Four wings run as a job array, and their collected summary must equal
# a local `-j 2` run's; a case that fails shows as FAILED and with its error line. Labelled "slurm" only, as they need root and the daemons:
# scripts/test.sh runs them in a pass of their own, after the others.
set(slurm_folder ${PROJECT_BINARY_DIR}/regression/slurm)
add_test(NAME slurm_cluster_start COMMAND ${PROJECT_SOURCE_DIR}/scripts/slurm-cluster.sh start)
set_tests_properties(slurm_cluster_start PROPERTIES LABELS slurm FIXTURES_SETUP slurm_cluster TIMEOUT 120)
add_test(NAME slurm_cluster_stop COMMAND ${PROJECT_SOURCE_DIR}/scripts/slurm-cluster.sh stop)
set_tests_properties(slurm_cluster_stop PROPERTIES LABELS slurm FIXTURES_CLEANUP slurm_cluster TIMEOUT 120)

add_test(NAME slurm_array_matches_local_batch
         COMMAND bash ${CMAKE_CURRENT_LIST_DIR}/slurm/array_matches_local.sh $<TARGET_FILE:mixmesh-cli>
                 ${CMAKE_CURRENT_LIST_DIR}/slurm/four_wings.toml
                 ${CMAKE_CURRENT_LIST_DIR}/pipeline/wing_through_farfield.toml ${slurm_folder}/array)
set_tests_properties(slurm_array_matches_local_batch PROPERTIES LABELS slurm FIXTURES_REQUIRED slurm_cluster
                     TIMEOUT 900 PASS_REGULAR_EXPRESSION "slurm array matches the local batch"
                     FAIL_REGULAR_EXPRESSION "FAILED:")
