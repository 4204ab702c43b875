# Mesh file formats checked by independent readers: the four-type reference mesh and
# the Gmsh-made cases/meshes/mixed_block.msh are written in every format, then read
# by check_mesh.py (meshio), by meshio directly (counts, prism volumes), by Gmsh (if
# installed) and, for CGNS, which meshio cannot read with mixed elements, by cgnscheck
# (if installed) and by our own reader compared with the reference.
add_executable(io_write_reference ${CMAKE_CURRENT_LIST_DIR}/io_write_reference.cpp)
target_compile_options(io_write_reference PRIVATE ${mixmesh_warnings})
target_include_directories(io_write_reference PRIVATE ${CMAKE_CURRENT_LIST_DIR}/../support)
target_link_libraries(io_write_reference PRIVATE mixmesh_io)

set(io_folder ${CMAKE_CURRENT_BINARY_DIR}/io_regression)
set(io_meshio_check ${CMAKE_CURRENT_LIST_DIR}/io_meshio_check.py)
find_program(MIXMESH_GMSH gmsh)
find_program(MIXMESH_CGNSCHECK cgnscheck)
set(io_gmsh_option "")
if(MIXMESH_GMSH)
  set(io_gmsh_option --gmsh ${MIXMESH_GMSH})
endif()

# 1. The reference mesh in 8 files.
add_test(NAME io_write_reference_every_format COMMAND io_write_reference ${io_folder}/reference)
set_tests_properties(io_write_reference_every_format PROPERTIES LABELS regression FIXTURES_SETUP io_reference)
set(io_reference_files four_types.vtu four_types_ascii.vtu four_types.su2 four_types_msh41.msh
    four_types_msh41_binary.msh four_types_msh22.msh four_types_msh22_binary.msh)
foreach(file IN LISTS io_reference_files)
  add_test(NAME io_check_mesh_reference_${file}
           COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${io_folder}/reference/${file} --no-foam)
  set_tests_properties(io_check_mesh_reference_${file} PROPERTIES LABELS regression FIXTURES_REQUIRED io_reference)
  list(APPEND io_reference_paths ${io_folder}/reference/${file})
endforeach()
add_test(NAME io_meshio_reference
         COMMAND ${MIXMESH_PYTHON} ${io_meshio_check} ${io_gmsh_option}
                 --expect tetra=1,pyramid=1,wedge=1,hexahedron=1,triangle=6,quad=8 ${io_reference_paths})
add_test(NAME io_cgns_reference_reads_back
         COMMAND io_write_reference --compare-cgns ${io_folder}/reference/four_types.cgns)
set_tests_properties(io_meshio_reference io_cgns_reference_reads_back
                     PROPERTIES LABELS regression FIXTURES_REQUIRED io_reference)
if(MIXMESH_CGNSCHECK)
  add_test(NAME io_cgnscheck_reference COMMAND ${MIXMESH_CGNSCHECK} ${io_folder}/reference/four_types.cgns)
  set_tests_properties(io_cgnscheck_reference PROPERTIES LABELS regression FIXTURES_REQUIRED io_reference
                       FAIL_REGULAR_EXPRESSION "ERROR")
endif()

# 2. mixed_block.msh (Gmsh) converted by `mixmesh convert` into every format and back.
set(io_block ${PROJECT_SOURCE_DIR}/cases/meshes/mixed_block.msh)
set(io_block_counts tetra=708,pyramid=16,wedge=132,hexahedron=48,triangle=334,quad=88)
set(io_block_outputs mixed_block.vtu mixed_block.su2 mixed_block.cgns mixed_block_41.msh mixed_block_22.msh)
foreach(output IN LISTS io_block_outputs)
  set(options "")
  if(output STREQUAL "mixed_block_22.msh")
    set(options --msh-version 2.2 --binary)
  endif()
  add_test(NAME io_convert_block_${output}
           COMMAND mixmesh-cli convert ${io_block} ${io_folder}/block/${output} ${options})
  set_tests_properties(io_convert_block_${output} PROPERTIES LABELS regression FIXTURES_SETUP io_block)
endforeach()
add_test(NAME io_make_block_folder COMMAND ${CMAKE_COMMAND} -E make_directory ${io_folder}/block)
set_tests_properties(io_make_block_folder PROPERTIES LABELS regression FIXTURES_SETUP io_block_folder)
foreach(output IN LISTS io_block_outputs)
  set_tests_properties(io_convert_block_${output} PROPERTIES FIXTURES_REQUIRED io_block_folder)
endforeach()
# The CGNS copy, converted back to .vtu by our reader, must still be the same mesh.
add_test(NAME io_convert_block_back_from_cgns
         COMMAND mixmesh-cli convert ${io_folder}/block/mixed_block.cgns ${io_folder}/block/from_cgns.vtu)
set_tests_properties(io_convert_block_back_from_cgns PROPERTIES LABELS regression FIXTURES_REQUIRED io_block
                     FIXTURES_SETUP io_block_back)
foreach(file mixed_block.vtu mixed_block.su2 mixed_block_41.msh mixed_block_22.msh from_cgns.vtu)
  add_test(NAME io_check_mesh_block_${file}
           COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${io_folder}/block/${file} --no-foam)
  set_tests_properties(io_check_mesh_block_${file} PROPERTIES LABELS regression
                       FIXTURES_REQUIRED "io_block;io_block_back")
  list(APPEND io_block_paths ${io_folder}/block/${file})
endforeach()
add_test(NAME io_meshio_block
         COMMAND ${MIXMESH_PYTHON} ${io_meshio_check} ${io_gmsh_option} --expect ${io_block_counts} ${io_block_paths})
set_tests_properties(io_meshio_block PROPERTIES LABELS regression FIXTURES_REQUIRED "io_block;io_block_back")
if(MIXMESH_CGNSCHECK)
  add_test(NAME io_cgnscheck_block COMMAND ${MIXMESH_CGNSCHECK} ${io_folder}/block/mixed_block.cgns)
  set_tests_properties(io_cgnscheck_block PROPERTIES LABELS regression FIXTURES_REQUIRED io_block
                       FAIL_REGULAR_EXPRESSION "ERROR")
endif()

# 3. Files Gmsh writes in its other encodings (binary 4.1, ASCII and binary 2.2) read by us.
if(MIXMESH_GMSH)
  foreach(variant "msh41;-bin" "msh22;" "msh22;-bin")
    list(GET variant 0 version)
    list(GET variant 1 binary)
    set(name gmsh_${version}${binary})
    add_test(NAME io_gmsh_writes_${name}
             COMMAND ${MIXMESH_GMSH} -0 ${io_block} -format ${version} ${binary} -o ${io_folder}/block/${name}.msh)
    add_test(NAME io_read_${name}
             COMMAND mixmesh-cli convert ${io_folder}/block/${name}.msh ${io_folder}/block/${name}.vtu)
    add_test(NAME io_check_mesh_${name}
             COMMAND ${MIXMESH_PYTHON} ${MIXMESH_CHECK_MESH} ${io_folder}/block/${name}.vtu --no-foam)
    set_tests_properties(io_gmsh_writes_${name} PROPERTIES LABELS regression FIXTURES_REQUIRED io_block_folder
                         FIXTURES_SETUP io_${name}_written)
    set_tests_properties(io_read_${name} PROPERTIES LABELS regression FIXTURES_REQUIRED io_${name}_written
                         FIXTURES_SETUP io_${name}_read)
    set_tests_properties(io_check_mesh_${name} PROPERTIES LABELS regression FIXTURES_REQUIRED io_${name}_read)
  endforeach()
endif()
