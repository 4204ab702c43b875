# Runs PROGRAM generate CONFIG --output-dir FOLDER, which must fail and leave FOLDER
# empty (or absent); prints the program's output for the test's regular expression.
file(REMOVE_RECURSE ${FOLDER})
execute_process(COMMAND ${PROGRAM} generate ${CONFIG} --output-dir ${FOLDER}
                RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE errors)
message("${output}${errors}")
if(status EQUAL 0)
  message(FATAL_ERROR "generate succeeded; a failure was expected")
endif()
file(GLOB left ${FOLDER}/*)
if(left)
  message(FATAL_ERROR "files left behind: ${left}")
endif()
