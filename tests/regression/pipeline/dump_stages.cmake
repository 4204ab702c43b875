# Runs PROGRAM generate CONFIG with --dump-stages into a folder that does not exist yet
# (FOLDER/stages/new): the folder is made and the far field's boundary written there.
file(REMOVE_RECURSE ${FOLDER})
execute_process(COMMAND ${PROGRAM} generate ${CONFIG} --set march.layers=4 --quiet --output-dir ${FOLDER}/mesh
                        --dump-stages ${FOLDER}/stages/new
                RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE errors)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "generate failed: ${output}${errors}")
endif()
if(NOT EXISTS ${FOLDER}/stages/new/boundary.vtk)
  message(FATAL_ERROR "no boundary.vtk in ${FOLDER}/stages/new")
endif()
