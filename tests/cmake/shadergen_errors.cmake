# shadergen reports a compile error with the permutation key and the source file and line, exits
# non-zero and writes nothing. The broken source is cacao.comp plus one bad line that only the blur
# permutations compile, so the line number and the keys are known in advance. A second copy whose
# #include names a missing file fails the same way, naming the including file, line and name.
# Inputs: SHADERGEN, SOURCE (shaders/cacao.comp; its folder is copied, with what it includes), WORK.
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK}/out)
get_filename_component(source_dir ${SOURCE} DIRECTORY)
file(COPY ${source_dir}/cacao_shared.h ${source_dir}/glsl DESTINATION ${WORK})
file(READ ${SOURCE} text)
string(REGEX MATCHALL "\n" newlines "${text}")
list(LENGTH newlines lines)
math(EXPR bad_line "${lines} + 2")
# Runs shadergen on source, which must fail (what: how it is broken) with each needle in its
# errors and nothing written; the errors are left in shadergen_err.
function(expect_refused source what)
  execute_process(COMMAND ${SHADERGEN} --source ${source} --out ${WORK}/out
                  RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
  if(rc EQUAL 0)
    message(FATAL_ERROR "shadergen accepted ${what}")
  endif()
  foreach(needle ${ARGN})
    string(FIND "${err}" "${needle}" at)
    if(at LESS 0)
      message(FATAL_ERROR "${what}: expected '${needle}' in shadergen's errors:\n${err}")
    endif()
  endforeach()
  file(GLOB written ${WORK}/out/*)
  if(written)
    message(FATAL_ERROR "shadergen wrote files despite ${what}: ${written}")
  endif()
  set(shadergen_err "${err}" PARENT_SCOPE)
endfunction()

file(WRITE ${WORK}/cacao.comp "${text}#if CACAO_PASS == CACAO_PASS_BLUR\nthis_is_not_glsl x = ;\n#endif\n")
expect_refused(${WORK}/cacao.comp "a broken source" "blur.1.fp32: GLSL compilation failed"
               "blur.8.fp16: GLSL compilation failed" "cacao.comp:${bad_line}" "16 permutation(s) failed; nothing written")
string(FIND "${shadergen_err}" "generate.q2:" at)
if(NOT at LESS 0)
  message(FATAL_ERROR "a permutation without the bad line was reported:\n${shadergen_err}")
endif()
message("shadergen names the key and cacao.comp:${bad_line}, exits non-zero, writes nothing")

# An #include of a file that is not there: one message naming the includer, its line and the file.
file(WRITE ${WORK}/missing.comp "#version 450\n#include \"glsl/no_such_file.glsl\"\n")
expect_refused(${WORK}/missing.comp "a source that includes a missing file" "missing.comp:2" "glsl/no_such_file.glsl")
message("a missing include: ${shadergen_err}")
