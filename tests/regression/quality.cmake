# mixmesh check on small meshes: exit status 0 valid, 1 invalid, 2 unreadable, the
# JSON report's findings, and agreement with the independent check_mesh.py.
set(quality_check_driver ${CMAKE_CURRENT_SOURCE_DIR}/regression/quality/check_cli.py)
foreach(case valid inverted)
  add_test(NAME quality_check_${case}
           COMMAND ${MIXMESH_PYTHON} ${quality_check_driver} $<TARGET_FILE:mixmesh-cli> ${case}
                   ${CMAKE_CURRENT_BINARY_DIR}/quality --independent ${MIXMESH_CHECK_MESH})
  set_tests_properties(quality_check_${case} PROPERTIES LABELS regression)
endforeach()
foreach(case unreadable missing)
  add_test(NAME quality_check_${case}
           COMMAND ${MIXMESH_PYTHON} ${quality_check_driver} $<TARGET_FILE:mixmesh-cli> ${case}
                   ${CMAKE_CURRENT_BINARY_DIR}/quality)
  set_tests_properties(quality_check_${case} PROPERTIES LABELS regression)
endforeach()
