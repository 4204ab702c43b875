# IDW parameter study: deform_idw_study (the C++ driver of scripts/idw-study.py) and the
# study itself on gmsh meshes. The quick variant checks on the square that the rotation
# term (sr = 2) beats no rotation term (sr = inf) at every st, as the paper finds for
# rotations; the full study (three shapes, 6 × 6 exponent pairs up to 360°) is heavy.
if(TARGET mixmesh_deform)
  add_executable(deform_idw_study ${PROJECT_SOURCE_DIR}/tests/bench/deform_idw_study.cpp)
  target_compile_options(deform_idw_study PRIVATE ${mixmesh_warnings})
  target_link_libraries(deform_idw_study PRIVATE mixmesh_deform)

  add_test(NAME deform_idw_study_quick
           COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/idw-study.py
                   --program $<TARGET_FILE:deform_idw_study> --out ${CMAKE_CURRENT_BINARY_DIR}/idw-study-quick
                   --quick --require-angle 45 --check-rotation-term)
  set_tests_properties(deform_idw_study_quick PROPERTIES LABELS regression)

  add_test(NAME deform_idw_study_full
           COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/idw-study.py
                   --program $<TARGET_FILE:deform_idw_study> --out ${CMAKE_CURRENT_BINARY_DIR}/idw-study)
  set_tests_properties(deform_idw_study_full PROPERTIES LABELS "regression;heavy")
endif()

# The IDW method through `mixmesh deform` (method = "idw" in the motion file): the NACA 0012
# pitched 0 → 20° in 5° steps stays valid at every step (the command validates every cell's
# signed area and fails otherwise; check_mesh.py reads volume meshes only), and at 20° its
# wall-normal grid lines turn with the airfoil to within 2° (the rotation term keeps the
# near-wall cells rigid).
if(TARGET mixmesh-cli)
  set(idw_output ${CMAKE_CURRENT_BINARY_DIR}/deform_idw)
  file(MAKE_DIRECTORY ${idw_output})
  set(idw_naca ${PROJECT_SOURCE_DIR}/cases/naca0012/naca0012.msh)
  add_test(NAME deform_idw_naca0012_pitch
           COMMAND mixmesh-cli deform ${idw_naca} --motion ${CMAKE_CURRENT_LIST_DIR}/deform_idw_pitch.toml
                   -o ${idw_output}/naca0012_pitch.vtu)
  set_tests_properties(deform_idw_naca0012_pitch PROPERTIES LABELS regression
    PASS_REGULAR_EXPRESSION "step 4: wall-line angle change: moving walls [01]\\.[0-9]+ deg"
    FAIL_REGULAR_EXPRESSION "error|INVALID")
  add_test(NAME deform_idw_naca0012_pitch_leading_edge
           COMMAND ${MIXMESH_PYTHON} ${CMAKE_CURRENT_LIST_DIR}/deform_wall_angles.py ${idw_naca}
                   ${idw_output}/naca0012_pitch_0004.vtu --marker airfoil --at-most 2.0)
  set_tests_properties(deform_idw_naca0012_pitch_leading_edge PROPERTIES LABELS regression
                       DEPENDS deform_idw_naca0012_pitch)

  # 3D: the wing's bending + twist mode with symmetry planes, valid by check_mesh.py.
  add_test(NAME deform_idw_wing_bend_twist
           COMMAND mixmesh-cli deform ${PROJECT_SOURCE_DIR}/cases/wing/wing.msh
                   --motion ${CMAKE_CURRENT_LIST_DIR}/deform_idw_wing.toml -o ${idw_output}/wing_bend_twist.vtu)
  set_tests_properties(deform_idw_wing_bend_twist PROPERTIES LABELS regression FAIL_REGULAR_EXPRESSION "error|INVALID")
  add_test(NAME deform_idw_wing_bend_twist_check
           COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} --no-foam -q ${idw_output}/wing_bend_twist.vtu)
  set_tests_properties(deform_idw_wing_bend_twist_check PROPERTIES LABELS regression
                       DEPENDS deform_idw_wing_bend_twist)
endif()

# scripts/compare-deform-methods.py on the NACA 0012 pitch case, cut short at 10°: both
# methods keep the mesh valid to 10° and the table reports both (the full comparison, to
# failure, is in docs/idw.md).
if(TARGET mixmesh-cli)
  add_test(NAME deform_idw_compare_methods_quick
           COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/compare-deform-methods.py
                   --program $<TARGET_FILE:mixmesh-cli> --mesh ${PROJECT_SOURCE_DIR}/cases/naca0012/naca0012.msh
                   --methods idw,ara --max-angle 10 --report-angle 10
                   --out ${CMAKE_CURRENT_BINARY_DIR}/deform_idw/compare)
  set_tests_properties(deform_idw_compare_methods_quick PROPERTIES LABELS regression
    PASS_REGULAR_EXPRESSION "IDW rotation form[^\n]*\\| 10° \\(valid up to 10°\\) \\| 0\\.[0-9]+ \\| 0 \\|.*ARA[^\n]*\\| 10° \\(valid up to 10°\\) \\| 0\\.[0-9]+ \\| 0 \\|")
endif()
