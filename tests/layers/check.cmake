# ctest script: building TARGET in BUILD_DIR must fail with the layer-boundary message.
execute_process(COMMAND ${CMAKE_COMMAND} --build ${BUILD_DIR} --target ${TARGET}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(rc EQUAL 0)
  message(FATAL_ERROR "${TARGET} built, but it crosses a layer boundary: the check is broken")
endif()
# MATCH: what the refusal says, when it is not a layer-boundary #error (a header not found).
if(NOT DEFINED MATCH)
  set(MATCH "layer boundary: ${EXPECT}")
endif()
if(NOT "${out}${err}" MATCHES "${MATCH}")
  message(FATAL_ERROR "${TARGET} failed for another reason than the layer boundary:\n${out}${err}")
endif()
message(STATUS "${TARGET}: refused as expected (layer boundary: ${EXPECT})")
