# Helper of the cacao-inspect test scripts (tests/cmake/inspect.cmake, tests/cli/inspect_scene.cmake).
# inspect(expect_rc args...): runs INSPECT with the arguments, fails the test unless it exits
# expect_rc, and sets out and err to its stdout and stderr.
function(inspect expect_rc)
  execute_process(COMMAND ${INSPECT} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL expect_rc)
    message(FATAL_ERROR "cacao-inspect ${ARGN}: exit ${rc}, expected ${expect_rc}\n${out}${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()
