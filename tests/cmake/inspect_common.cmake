# Helper of the cacao-inspect test scripts (tests/cmake/inspect.cmake, tests/cli/inspect_scene.cmake).
# inspect(expect_rc args...): runs INSPECT with the arguments, fails the test unless it exits
# expect_rc, and sets out and err to its stdout and stderr. RUN_ENV (optional, "|"-separated
# VAR=value) is the environment INSPECT alone runs in (the sanitizer build's preloads).
function(inspect expect_rc)
  string(REPLACE "|" ";" run_env "${RUN_ENV}")
  set(launch ${INSPECT})
  if(run_env)
    set(launch ${CMAKE_COMMAND} -E env ${run_env} ${INSPECT})
  endif()
  execute_process(COMMAND ${launch} ${ARGN} RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(NOT rc EQUAL expect_rc)
    message(FATAL_ERROR "cacao-inspect ${ARGN}: exit ${rc}, expected ${expect_rc}\n${out}${err}")
  endif()
  set(out "${out}" PARENT_SCOPE)
  set(err "${err}" PARENT_SCOPE)
endfunction()
