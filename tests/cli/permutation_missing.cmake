# A quality level this build did not embed is refused by the runtime at resize
# (CACAO_ERROR_PERMUTATION_MISSING); the command must turn that into one clear line naming the
# missing permutation, a non-zero exit and no output, while an embedded level still works. Needs
# the subset build (medium and high only) that the subset_build test leaves in SUBSET_BUILD; the
# command is built there (only its own sources are new) and the test is skipped without it.
include(${CMAKE_CURRENT_LIST_DIR}/cli_common.cmake)
if(NOT EXISTS ${SUBSET_BUILD}/CMakeCache.txt)
  message("SKIPPED: no subset build at ${SUBSET_BUILD} (run the subset_build test first)")
  return()
endif()
execute_process(COMMAND ${CMAKE_COMMAND} --build ${SUBSET_BUILD} --target cacao_cli table_dump RESULT_VARIABLE rc
                OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the command in the subset build failed:\n${out}${err}")
endif()
# The count the subset build embeds (subset_build checks it against its hand-derived list).
execute_process(COMMAND ${SUBSET_BUILD}/tests/table_dump --embedded-count RESULT_VARIABLE rc OUTPUT_VARIABLE embedded
                OUTPUT_STRIP_TRAILING_WHITESPACE)
if(NOT rc EQUAL 0 OR NOT embedded MATCHES "^[1-9][0-9]*$")
  message(FATAL_ERROR "table_dump --embedded-count in the subset build: exit ${rc}, '${embedded}'")
endif()
set(CACAO ${SUBSET_BUILD}/tools/cli/cacao)
cacao_ok(version --version)
if(NOT version_out MATCHES "\\(${embedded} embedded shader permutations\\)")
  message(FATAL_ERROR "the subset build embeds ${embedded} permutations, which --version should say: ${version_out}")
endif()
cacao_run(r --scene ${ROOM} --quality lowest --validate -o ${WORK}/out.png)
if(r_rc EQUAL 0 OR NOT r_err MATCHES "permutation .[a-z_0-9.]+. is not embedded" OR EXISTS ${WORK}/out.png)
  message(FATAL_ERROR "quality lowest in a medium/high build: expected a clear refusal, got ${r_rc}: ${r_err}")
endif()
message("refused as expected: ${r_err}")
cacao_ok(ok --scene ${ROOM} --quality medium --validate -o ${WORK}/out.png)
