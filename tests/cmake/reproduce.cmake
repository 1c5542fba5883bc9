# generated/ reproduces byte for byte from shaders/ with the installed compilers.
# Inputs: SHADERGEN, SOURCE, GENERATED (committed dir), WORK.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
execute_process(COMMAND ${SHADERGEN} --source ${SOURCE} --out ${WORK}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
message("${out}${err}")
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "shadergen failed (${rc})")
endif()
file(READ ${GENERATED}/VERSIONS committed_versions)
file(READ ${WORK}/VERSIONS installed_versions)
if(NOT committed_versions STREQUAL installed_versions)
  string(REPLACE "\n" " " a "${committed_versions}")
  string(REPLACE "\n" " " b "${installed_versions}")
  message("CACAO_SKIP: generated/ was made with [${a}] but the installed compilers are [${b}]; "
          "their SPIR-V differs legitimately. Rebuild with -DCACAO_REGENERATE=ON to rewrite generated/.")
  return()
endif()
foreach(f cacao_spirv.c cacao_table.c VERSIONS)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${GENERATED}/${f} ${WORK}/${f} RESULT_VARIABLE diff)
  if(NOT diff EQUAL 0)
    message(FATAL_ERROR "generated/${f} is stale: a fresh shadergen run differs. "
                        "Rebuild with -DCACAO_REGENERATE=ON and commit generated/.")
  endif()
endforeach()
message("generated/ reproduces byte for byte")
