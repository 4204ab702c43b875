# IDW parameter study: deform_idw_study (the C++ driver of scripts/idw-study.py) and the
# study itself on gmsh meshes. The quick rotation variant checks on the square that the
# rotation term (sr = 2) beats no rotation term (sr = inf) at every st, as the paper finds
# for rotations; the quick translation variant checks that sr changes nothing when the body
# only translates and that st = 1 carries it strictly further than st = 0.5 and st = 4. The
# full studies (three shapes; rotation 6 × 6 pairs up to 360°, translation 8 × 3 pairs, the
# paper's combined movements on the rectangle) are heavy, except translation (~10 s).
# Each study has its own output folder: they write the same shapes' meshes (gmsh's .geo,
# .msh and the text mesh), and ctest -j runs them side by side.
if(TARGET mixmesh_deform)
  add_executable(deform_idw_study ${PROJECT_SOURCE_DIR}/tests/bench/deform_idw_study.cpp)
  target_compile_options(deform_idw_study PRIVATE ${mixmesh_warnings})
  target_link_libraries(deform_idw_study PRIVATE mixmesh_deform)

  add_test(NAME deform_idw_study_quick
           COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/idw-study.py
                   --program $<TARGET_FILE:deform_idw_study> --out ${CMAKE_CURRENT_BINARY_DIR}/idw-study-quick/rotation
                   --quick --require-angle 45 --check-rotation-term)
  set_tests_properties(deform_idw_study_quick PROPERTIES LABELS regression)

  add_test(NAME deform_idw_study_translation_quick
           COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/idw-study.py
                   --program $<TARGET_FILE:deform_idw_study> --out ${CMAKE_CURRENT_BINARY_DIR}/idw-study-quick/translation
                   --motion translation --quick --check-translation-exponent)
  set_tests_properties(deform_idw_study_translation_quick PROPERTIES LABELS regression)

  # Bad input: one clear error line (printed only on the error path, which exits 1).
  add_test(NAME deform_idw_study_bad_motion
           COMMAND deform_idw_study no-such.mesh.txt --centre 0,0 --st 1 --sr 2 --max-steps 1 --motion spin)
  set_tests_properties(deform_idw_study_bad_motion PROPERTIES LABELS regression
    PASS_REGULAR_EXPRESSION "deform_idw_study: error: --motion: 'spin' is not rotation, translation or combined")
  add_test(NAME deform_idw_study_missing_mesh
           COMMAND deform_idw_study no-such.mesh.txt --centre 0,0 --st 1 --sr 2 --max-steps 1 --motion translation)
  set_tests_properties(deform_idw_study_missing_mesh PROPERTIES LABELS regression
    PASS_REGULAR_EXPRESSION "deform_idw_study: error: no-such.mesh.txt: cannot open")

  add_test(NAME deform_idw_study_full
           COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/idw-study.py
                   --program $<TARGET_FILE:deform_idw_study> --out ${CMAKE_CURRENT_BINARY_DIR}/idw-study/rotation)
  set_tests_properties(deform_idw_study_full PROPERTIES LABELS "regression;heavy")
  # The translation study is cheap (~10 s): on all three shapes and st = 0.5 … 4, sr changes
  # nothing and st = 1 goes strictly furthest.
  add_test(NAME deform_idw_study_translation_full
           COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/idw-study.py
                   --program $<TARGET_FILE:deform_idw_study> --out ${CMAKE_CURRENT_BINARY_DIR}/idw-study/translation
                   --motion translation --check-translation-exponent)
  set_tests_properties(deform_idw_study_translation_full PROPERTIES LABELS regression)
  add_test(NAME deform_idw_study_combined_full
           COMMAND ${MIXMESH_PYTHON} ${PROJECT_SOURCE_DIR}/scripts/idw-study.py
                   --program $<TARGET_FILE:deform_idw_study> --out ${CMAKE_CURRENT_BINARY_DIR}/idw-study/combined
                   --motion combined)
  set_tests_properties(deform_idw_study_combined_full PROPERTIES LABELS "regression;heavy")
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
  set_property(TEST deform_idw_naca0012_pitch APPEND PROPERTY FIXTURES_SETUP deform_idw_naca0012_pitch)
set_tests_properties(deform_idw_naca0012_pitch_leading_edge PROPERTIES LABELS regression
                       FIXTURES_REQUIRED deform_idw_naca0012_pitch)

  # 3D: the wing's bending + twist mode with symmetry planes, valid by check_mesh.py.
  add_test(NAME deform_idw_wing_bend_twist
           COMMAND mixmesh-cli deform ${PROJECT_SOURCE_DIR}/cases/wing/wing.msh
                   --motion ${CMAKE_CURRENT_LIST_DIR}/deform_idw_wing.toml -o ${idw_output}/wing_bend_twist.vtu)
  set_tests_properties(deform_idw_wing_bend_twist PROPERTIES LABELS regression FAIL_REGULAR_EXPRESSION "error|INVALID")
  add_test(NAME deform_idw_wing_bend_twist_check
           COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} --no-foam -q ${idw_output}/wing_bend_twist.vtu)
  set_property(TEST deform_idw_wing_bend_twist APPEND PROPERTY FIXTURES_SETUP deform_idw_wing_bend_twist)
set_tests_properties(deform_idw_wing_bend_twist_check PROPERTIES LABELS regression
                       FIXTURES_REQUIRED deform_idw_wing_bend_twist)
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
